// Verification of a staged excavation: the Kirsch problem of kirsch_01
// (a circular hole of radius a = 1 m in elastic rock, E = 10 GPa, nu =
// 0.25, far-field stresses p = 0.1 MPa vertical and K p, K = 0.5,
// horizontal; plane strain, the quarter x, y >= 0 of a slab, outer square
// at L = 40 a loaded by the far-field tractions) solved as a staged
// analysis is: the hole starts full of rock (tests/deformable/hole_mesh.h
// with `filled`: an O-grid inside on the wall's own gridpoints).
//  - Stage 1: every zone at the in-situ stress, the tractions on the outer
//    boundary, a static run. The stress is in equilibrium, so nothing may
//    move: the largest displacement must stay below 1e-9 of Kirsch's wall
//    displacement u_r(a, 90).
//  - Stage 2: the zones inside the hole are removed
//    (DeformableSolver::remove_zones, what a 'Stage N' excavation does to a
//    body of zones) and displacements reset; a static run to ratio 1e-6.
//    The wall displacements and hoop stresses must meet Kirsch with
//    kirsch_01's tolerances for this mesh (8 sectors), and agree with the
//    same problem excavated from the start (the annulus alone, kirsch_01's
//    model) to 1e-3: the removed zones leave nothing behind (no mass, no
//    stiffness, no stress on the wall).

#include <talus/base/parallel_environment.h>
#include <talus/solver/deformable_solver.h>
#include <talus/zone/block_mesher.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "../tests.h"
#include "hole_mesh.h"
#include "kirsch_solution.h"

namespace
{
struct Answer
{
  double u0 = 0, u90 = 0;  ///< m, wall displacements on the axes
  std::vector<Vec3> where; ///< centroids of the zones that remain
  std::vector<double> stress;
};

/// A static run of the quarter slab with zones `mesh`, the zones inside the
/// hole removed after a first static stage when `staged`.
Answer solve(const TetMesh& mesh, double t, bool staged)
{
  ZoneMaterial rock;
  rock.set_young_poisson(E, nu);
  const std::unique_ptr<DeformableSolver> owned =
      kirsch_solver(mesh, rock, plane_strain_rollers(t, eps, big));
  DeformableSolver& solver = *owned;
  const std::vector<Vec3> centroids = zone_centroids(mesh);
  if (staged)
  {
    const unsigned long steps = solver.run_to_ratio(target, 20000);
    double largest = 0.0;
    for (double u : solver.displacements())
      largest = std::max(largest, std::abs(u));
    std::fprintf(stderr, "stage 1: %lu steps, largest displacement %.3g m\n", steps, largest);
    talus_test::check_within("  stage 1: largest displacement over Kirsch's u_r(a, 90)",
                             largest / std::abs(kirsch_wall_ur(0.5 * M_PI)), 0.0, 1e-9);
    std::vector<char> gone(mesh.n_zones(), 0);
    unsigned int n_gone = 0;
    for (unsigned int z = 0; z < mesh.n_zones(); ++z)
      if (centroids[z].head<2>().norm() < a)
        n_gone += gone[z] = 1;
    std::printf("  stage 2 removes %u zones inside the hole\n", n_gone);
    solver.remove_zones(gone);
    solver.reset_displacements();
  }
  const unsigned long steps = solver.run_to_ratio(target, 200000);
  std::printf("  %s static run: %s\n", staged ? "stage 2" : "direct",
              solver.unbalanced_ratio() < target ? "converged" : "NOT converged");
  std::fprintf(stderr, "%s: %lu steps\n", staged ? "stage 2" : "direct", steps);
  Answer answer;
  const std::vector<double> u = solver.displacements();
  answer.u0 = wall_ur(mesh, u, false);
  answer.u90 = wall_ur(mesh, u, true);
  for (unsigned int z = 0; z < mesh.n_zones(); ++z)
    if (!solver.zone_removed(z))
    {
      answer.where.push_back(centroids[z]);
      answer.stress.insert(answer.stress.end(), &solver.stress()[6 * z],
                           &solver.stress()[6 * z] + 6);
    }
  return answer;
}
} // namespace

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  const unsigned int n_theta = 8;
  HoleMesh hole = HoleMesh::square_slab(a, L, n_theta);
  const double dtheta = 0.5 * M_PI / n_theta;
  const double ring_ratio = hole.ring_ratio();
  const TetMesh direct_mesh = hole.build();
  hole.filled = true;
  const TetMesh filled_mesh = hole.build();
  std::printf("%u sectors: %u zones with the hole full, %u without\n", n_theta,
              filled_mesh.n_zones(), direct_mesh.n_zones());

  const Answer staged = solve(filled_mesh, hole.thickness, true);
  // Against Kirsch, with kirsch_01's tolerances at 8 sectors.
  talus_test::check_error("  u_r(a, 0) (m)", staged.u0, kirsch_wall_ur(0.0), 0.05);
  talus_test::check_error("  u_r(a, 90) (m)", staged.u90, kirsch_wall_ur(0.5 * M_PI), 0.05);
  for (const bool y_axis : {false, true})
  {
    const std::vector<ZoneHoop> zones =
        hoop_near_axis(staged.where, staged.stress, ring_ratio, dtheta, 3, 2, y_axis);
    const double exact = y_axis ? -p * (3.0 * K - 1.0) : -p * (3.0 - K);
    talus_test::check_error(std::string("  sigma_tt(a, ") + (y_axis ? "90" : "0") +
                                "), fit to the wall (Pa)",
                            wall_fit(zones, false), exact, 0.06);
    const WallMean wall = wall_mean(zones, ring_ratio, dtheta);
    talus_test::check_error(std::string("  sigma_tt, mean of the ") + std::to_string(wall.n) +
                                " zones at the wall next to theta = " + (y_axis ? "90" : "0") +
                                ", Kirsch at their centroids (Pa)",
                            wall.computed, wall.kirsch, 0.008);
  }
  // The same problem excavated from the start.
  const Answer direct = solve(direct_mesh, hole.thickness, false);
  talus_test::check_within("  staged u_r(a, 0) against the hole made at the start (m)", staged.u0,
                           direct.u0, 1e-3);
  talus_test::check_within("  staged u_r(a, 90) against the hole made at the start (m)", staged.u90,
                           direct.u90, 1e-3);
  for (const bool y_axis : {false, true})
    talus_test::check_within(
        std::string("  staged sigma_tt(a, ") + (y_axis ? "90" : "0") +
            "), fit, against the hole made at the start (Pa)",
        wall_fit(hoop_near_axis(staged.where, staged.stress, ring_ratio, dtheta, 3, 2, y_axis),
                 false),
        wall_fit(hoop_near_axis(direct.where, direct.stress, ring_ratio, dtheta, 3, 2, y_axis),
                 false),
        1e-3);
}
