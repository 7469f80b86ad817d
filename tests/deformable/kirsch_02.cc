// Verification: kirsch_01's problem (a circular hole of radius a = 1 m,
// E = 10 GPa, nu = 0.25, far field p = 0.1 MPa vertical and K p, K = 0.5,
// horizontal, plane strain, against Kirsch's solution; see kirsch_01.cc
// for the closed form and the error measures) with the quarter slab meshed
// the way blocks are: one closed polyhedral body (tests/deformable/
// hole_body.h) through gmsh (zone/convex_block_mesher.h), the hole a
// polygon of 32 facets in the quarter inscribed in the circle, zones of
// edge h0 = 0.05 a at the wall growing as h0 r / a up to 2 a, the outer
// boundary the square [0, 40 a]^2, the slab 0.2 a thick (u_z held on both
// faces). The error measures are kirsch_01's, in its windows of 16
// sectors (the zones whose centroids fall in them: the wall fit over
// r < 1.32 a and 11 degrees from an axis, the wall mean over r < 1.1 a and
// 5.6 degrees). One mesh, run twice: plain 4-node zones (against the
// implicit solve of the same mesh too, as kirsch_01) and nodal mixed
// discretization (eqs. 68-76; the implicit reference has no such zones).
//
// Against kirsch_01 at 16 sectors (15,000 zones, about 30 s on the loaded
// machine; errors u_r(a, 0) 0.8 %, u_r(a, 90) 0.4 %, wall fit 0.7 % and
// 0.3 %, wall zones 0.08 % and 0.02 %, rms 0.017 p), this mesh (21,000
// zones, 8,000 steps, about 45 s with both runs) gives, plain / nodal
// mixed: u_r 0.1-0.4 % / 0.15-0.3 % and 0.15 % / 0.02-0.04 %, wall fit
// 1.7-2.1 % / 0.7-1.0 % at theta = 0 and 0.8-1.4 % / 0.6-1.0 % at 90
// degrees, wall zones 0.9-1.1 % / 0.35-0.5 % and 0.15-0.5 % / 0.3-0.45 %,
// rms 0.027-0.028 p / 0.013 p (ranges over seven meshings: gmsh's HXT
// volume mesher does not give the same mesh twice, so the output holds
// verdicts only and the figures go to standard error). The wall
// displacements are kept or better, and with nodal mixed zones the rms and
// the wall fit at theta = 0 too; the hoop stress at the wall otherwise is
// not: the wall fit 2-5 times kirsch_01's, the means of the wall zones
// 5-20 times (kirsch_01's are means over the 24 symmetric tetrahedra of a
// hexahedron, which average out their error). The cause is constant-strain
// tetrahedra of an unstructured mesh at a free wall: the number of facets
// (16 to 128) does not move the errors, the zone size at the wall only
// slowly (implicit solves, fit at theta = 0 for h0 = 0.1 / 0.07 / 0.05 /
// 0.035 a: 4 / 3 / 2 / 1.3 %), nodal mixed discretization halves them. A
// slab 1 a thick with zones no longer than 1 a far out (well shaped
// everywhere) costs 3 times the zones for the same errors (h0 = 0.05 a:
// 63,000 zones; 19,000 at h0 = 0.1 a give u_r 3-4 % and 1.4 %): plane
// strain needs no resolution across the slab, so the slab is thin and the
// far zones flat.
//
// Tolerances: about 1.5 times the largest errors seen, kirsch_01's 16-sector
// errors for the wall displacements.

#include <talus/base/parallel_environment.h>
#include <talus/solver/deformable_solver.h>
#include <talus/zone/block_mesher.h>
#include <talus/zone/implicit_elastic.h>

#include <Eigen/Dense>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "../tests.h"
#include "hole_body.h"
#include "hole_mesh.h"
#include "kirsch_solution.h"

using namespace talus;

namespace
{
/// Relative errors against Kirsch and the bounds they must keep.
struct Errors
{
  double u0, u90, wall0, wall90, centroid0, centroid90, rms;
};

/// "name: relative error below tolerance: OK" (the mesh varies a little
/// from run to run, gmsh's volume mesher not being repeatable, so only the
/// verdict is compared; the figures go to standard error). Returns the
/// error.
double within(const std::string& name, double computed, double exact, double tolerance)
{
  talus_test::print_value(stderr, name, computed, exact, "\n");
  const double error = talus_test::relative_error(computed, exact);
  std::printf("%s: relative error below %.2g: %s\n", name.c_str(), tolerance,
              talus_test::verdict(error <= tolerance));
  return error;
}

/// Whether the explicit static answer is within 0.5 % of the implicit
/// one (the figures to standard error).
void agrees(const std::string& name, double explicit_answer, double implicit_answer)
{
  within(name, explicit_answer, implicit_answer, 5e-3);
}

/// The static run on `mesh` (slab thickness t), the error measures in the
/// windows of kirsch_01 with n_theta sectors (its first three rings and
/// two sectors next to an axis for the wall fit, its first ring and sector
/// for the zones at the wall), so that both tests measure the same
/// regions; with plain zones also the implicit reference solve.
Errors run(const TetMesh& mesh, double t, unsigned int n_theta, bool nodal_mixed,
           const Errors& tolerance)
{
  Errors errors;
  const double dtheta = 0.5 * M_PI / n_theta;
  const unsigned int n_r =
      static_cast<unsigned int>(std::lround(std::log(L / a) / std::log(1.0 + dtheta)));
  const double ring_ratio = std::pow(L / a, 1.0 / n_r);
  std::printf("%s zones:\n", nodal_mixed ? "nodal mixed" : "plain");

  ZoneMaterial rock;
  rock.set_young_poisson(E, nu);
  rock.nodal_mixed = nodal_mixed;
  SolverSettings settings;
  settings.gravity = Vec3::Zero();
  settings.damping = Damping::adaptive_global;
  const FacePressure right{Box{Vec3(L - eps, -big, -big), Vec3(L + eps, big, big)}, K * p};
  const FacePressure top{Box{Vec3(-big, L - eps, -big), Vec3(big, L + eps, big)}, p};
  InitialStress initial;
  initial.base[0] = Sx;
  initial.base[1] = Sy;
  initial.base[2] = Sz;
  DeformableSolver solver(mesh, {rock}, std::vector<unsigned int>(mesh.n_zones(), 0), settings,
                          plane_strain_rollers(t, eps, big), {right, top}, &initial);
  const auto solve_start = std::chrono::steady_clock::now();
  const unsigned long steps = solver.run_to_ratio(target, 200000);
  std::printf("  static run: %s\n",
              solver.unbalanced_ratio() < target ? "converged" : "NOT converged");
  std::fprintf(
      stderr, "  static run: %lu steps, %.1f s\n", steps,
      std::chrono::duration<double>(std::chrono::steady_clock::now() - solve_start).count());

  // Wall displacements against Kirsch.
  const std::vector<double> u = solver.displacements();
  const double u0 = wall_ur(mesh, u, false), u90 = wall_ur(mesh, u, true);
  errors.u0 = within("  u_r(a, 0) (m)", u0, kirsch_wall_ur(0.0), tolerance.u0);
  errors.u90 = within("  u_r(a, 90) (m)", u90, kirsch_wall_ur(0.5 * M_PI), tolerance.u90);

  // Hoop stress at the wall: least squares over the zones of the first
  // three rings and two sectors next to each axis, evaluated at the wall.
  for (const bool y_axis : {false, true})
  {
    const std::vector<ZoneHoop> zones =
        hoop_near_axis(mesh, solver.stress(), ring_ratio, dtheta, 3, 2, y_axis);
    const double exact = y_axis ? -p * (3.0 * K - 1.0) : -p * (3.0 - K);
    std::fprintf(stderr, "  %zu zones in the fit\n", zones.size());
    std::fprintf(stderr, "  the fit below applied to Kirsch at the same centroids: bias %.1e\n",
                 std::abs(wall_fit(zones, true) / exact - 1.0));
    (y_axis ? errors.wall90 : errors.wall0) =
        within(std::string("  sigma_tt(a, ") + (y_axis ? "90" : "0") + "), fit to the wall (Pa)",
               wall_fit(zones, false), exact, y_axis ? tolerance.wall90 : tolerance.wall0);
    // The zones of the first ring and sector: mean hoop stress at their
    // centroids.
    double computed = 0.0, closed = 0.0;
    unsigned int n = 0;
    for (const ZoneHoop& z : zones)
      if (z.r < a * ring_ratio && z.angle_from_axis < dtheta)
      {
        computed += z.computed;
        closed += z.kirsch;
        ++n;
      }
    std::fprintf(stderr, "  %u zones at the wall next to the axis\n", n);
    (y_axis ? errors.centroid90 : errors.centroid0) =
        within(std::string("  sigma_tt, mean of the zones at the wall next to theta = ") +
                   (y_axis ? "90" : "0") + ", Kirsch at their centroids (Pa)",
               computed / n, closed / n, y_axis ? tolerance.centroid90 : tolerance.centroid0);
  }
  // Every zone within 3a: root mean square of the hoop stress error, over p.
  {
    const std::vector<ZoneHoop> zones = hoop_near_axis(
        mesh, solver.stress(), std::pow(3.0, 1.0 / 3.0), dtheta, 3, 4 * n_theta, false);
    double sum = 0.0;
    for (const ZoneHoop& z : zones)
      sum += std::pow(z.computed - z.kirsch, 2);
    errors.rms = std::sqrt(sum / zones.size()) / p;
    std::fprintf(stderr, "  %zu zones within 3a\n", zones.size());
    std::fprintf(stderr, "  rms %.3g\n", errors.rms);
    std::printf(
        "  zones within 3a: rms of (sigma_tt - Kirsch at the centroid) / p below %.2g: %s\n",
        tolerance.rms, talus_test::verdict(errors.rms <= tolerance.rms));
  }

  if (nodal_mixed)
    return errors; // the implicit reference has plain zones only

  // The implicit reference on the same mesh: loads are the unbalanced
  // nodal forces of the initial stress state (f_n = sigma0 A_n / 3 for each
  // zone, A_n the outward area normal of the face opposite node n), which
  // cancel inside and on the loaded square sides except for the outer
  // tractions added below, leaving the excavation loads on the hole.
  ImplicitElasticProblem problem;
  problem.mesh = &mesh;
  problem.zone_bulk.assign(mesh.n_zones(), rock.bulk_modulus);
  problem.zone_shear.assign(mesh.n_zones(), rock.shear_modulus);
  problem.fixed.assign(mesh.n_gridpoints(), 0);
  problem.nodal_force.assign(3 * mesh.n_gridpoints(), 0.0);
  problem.tolerance = 1e-12;
  for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
  {
    const Vec3 x = point(mesh, g);
    problem.fixed[g] = (std::abs(x[0]) < eps ? 1 : 0) | (std::abs(x[1]) < eps ? 2 : 0) |
                       (std::abs(x[2]) < eps || std::abs(x[2] - t) < eps ? 4 : 0);
  }
  static const int opposite[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  for (const auto& z : mesh.zone_gridpoint)
    for (int n = 0; n < 4; ++n)
    {
      const Vec3 p0 = point(mesh, z[opposite[n][0]]);
      Vec3 area =
          0.5 * (point(mesh, z[opposite[n][1]]) - p0).cross(point(mesh, z[opposite[n][2]]) - p0);
      if (area.dot(p0 - point(mesh, z[n])) < 0.0)
        area = -area;
      const Vec3 f = Vec3(Sx * area[0], Sy * area[1], Sz * area[2]) / 3.0;
      for (int d = 0; d < 3; ++d)
        problem.nodal_force[3 * z[n] + d] += f[d];
    }
  for (const auto& face : mesh.face_gridpoint)
  {
    const Vec3 p0 = point(mesh, face[0]);
    const Vec3 c = (p0 + point(mesh, face[1]) + point(mesh, face[2])) / 3.0;
    const double pressure = std::abs(c[0] - L) < eps ? K * p : std::abs(c[1] - L) < eps ? p : 0.0;
    const Vec3 area = 0.5 * (point(mesh, face[1]) - p0).cross(point(mesh, face[2]) - p0);
    for (unsigned int g : face)
      for (int d = 0; d < 3; ++d)
        problem.nodal_force[3 * g + d] -= pressure * area[d] / 3.0;
  }
  const ImplicitElasticResult implicit = solve_implicit_elastic(problem);
  const double i0 = wall_ur(mesh, implicit.displacement, false);
  const double i90 = wall_ur(mesh, implicit.displacement, true);
  agrees("  explicit u_r(a, 0) against implicit (m)", u0, i0);
  agrees("  explicit u_r(a, 90) against implicit (m)", u90, i90);
  double largest = 0.0, difference = 0.0;
  for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
    if (point(mesh, g).head<2>().norm() < a + eps) // on the hole's facets
      for (int d = 0; d < 2; ++d)
      {
        largest = std::max(largest, std::abs(implicit.displacement[3 * g + d]));
        difference =
            std::max(difference, std::abs(u[3 * g + d] - implicit.displacement[3 * g + d]));
      }
  agrees("  explicit against implicit, largest wall difference over largest wall displacement",
         difference / largest + 1.0, 1.0);
  // Hoop stress at the wall from the implicit displacements (small
  // strain), fitted the same way.
  const std::vector<double> implicit_stress =
      small_strain_stress(mesh, implicit.displacement, rock);
  for (const bool y_axis : {false, true})
    agrees(
        std::string("  explicit sigma_tt(a, ") + (y_axis ? "90" : "0") +
            "), fit, against implicit (Pa)",
        wall_fit(hoop_near_axis(mesh, solver.stress(), ring_ratio, dtheta, 3, 2, y_axis), false),
        wall_fit(hoop_near_axis(mesh, implicit_stress, ring_ratio, dtheta, 3, 2, y_axis), false));
  return errors;
}
} // namespace

/// The mesh of the slab: hole wall zones of edge h0, growing in proportion
/// to the distance from the centre up to h_max.
TetMesh slab_mesh(double h0, unsigned int n_facets, double thickness, double h_max)
{
  HoleBody hole;
  hole.a = a;
  hole.R = L;
  hole.square = true;
  hole.n_facets = n_facets;
  hole.h0 = h0;
  hole.thickness = thickness;
  hole.h_max = h_max;
  const auto start = std::chrono::steady_clock::now();
  const TetMesh mesh = hole.build();
  const MeshReport report = measure_mesh(mesh);
  std::printf("%u facets, h0 %.2g a, thickness %.2g a, h_max %.2g a: about %s zones\n", n_facets,
              h0 / a, thickness / a, h_max / a, one_digit(report.zones).c_str());
  std::fprintf(stderr, "%u zones, %u gridpoints, smallest height %.3g m, meshed in %.2f s\n",
               report.zones, report.gridpoints, report.smallest_height,
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return mesh;
}

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  if (argc > 1)
  {
    // A study, no tolerances: h0 / a, facets, thickness / a, h_max / a,
    // nodal mixed (0 or 1), kirsch_01's windows of n_theta sectors, target
    // ratio (1: implicit only, in effect), outer half-width.
    const double h0 = std::atof(argv[1]) * a;
    const unsigned int n_facets = argc > 2 ? std::atoi(argv[2]) : 32;
    const double thickness = argc > 3 ? std::atof(argv[3]) * a : 0.2 * a;
    const double h_max = argc > 4 ? std::atof(argv[4]) * a : 2.0 * a;
    const bool nodal_mixed = argc > 5 && std::atoi(argv[5]) != 0;
    const unsigned int n_theta = argc > 6 ? std::atoi(argv[6]) : 16;
    if (argc > 7)
      target = std::atof(argv[7]);
    if (argc > 8)
      L = std::atof(argv[8]);
    const Errors loose{1, 1, 1, 1, 1, 1, 1};
    run(slab_mesh(h0, n_facets, thickness, h_max), thickness, n_theta, nodal_mixed, loose);
    return 0;
  }
  // One mesh, plain zones then nodal mixed ones, in kirsch_01's windows of
  // 16 sectors. Tolerances: see the comment at the top.
  const double thickness = 0.2 * a;
  const TetMesh mesh = slab_mesh(0.05 * a, 32, thickness, 2.0 * a);
  const Errors plain =
      run(mesh, thickness, 16, false, {0.008, 0.004, 0.03, 0.02, 0.016, 0.008, 0.035});
  const Errors mixed =
      run(mesh, thickness, 16, true, {0.008, 0.004, 0.014, 0.016, 0.008, 0.008, 0.02});
  std::printf("nodal mixed closer to Kirsch than plain zones: u_r(a, 90) %s, wall fit at theta = "
              "0 %s, wall zones at theta = 0 %s, rms %s\n",
              mixed.u90 < plain.u90 ? "yes" : "NO", mixed.wall0 < plain.wall0 ? "yes" : "NO",
              mixed.centroid0 < plain.centroid0 ? "yes" : "NO",
              mixed.rms < plain.rms ? "yes" : "NO");
}
