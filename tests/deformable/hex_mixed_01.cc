// Patch tests of hexahedral zones of mixed discretization (eqs. 60-67) on a
// distorted mesh of a unit cube (4 x 4 x 4 hexahedra, each two overlays of
// five tetrahedra; interior gridpoints moved at random by up to 30 % of the
// zone size):
// 0. the mesh: ten tetrahedra per hexahedron on its eight corners, each
//    overlay filling the cube once, each overlay's boundary the cube's
//    surface once;
// 1. every gridpoint moved with a linear velocity field for one step: every
//    tetrahedron gets the same strain and stress (eq. 59 of that strain), to
//    round-off: the averaging of eqs. 62 and 66 changes nothing in a
//    uniform field;
// 2. a linear displacement imposed on the boundary only, the interior found
//    by the static solver: interior gridpoints on the linear field, every
//    tetrahedron at the same stress (each overlay's nodal forces of a
//    uniform stress cancel at interior gridpoints);
// 3. the whole cube turned rigidly by 90 degrees in 90 steps: no stress.

#include <talus/base/parallel_environment.h>
#include <talus/solver/deformable_solver.h>
#include <talus/zone/block_mesher.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "../tests.h"

using namespace talus;

namespace
{
bool on_boundary(const double* p)
{
  for (int d = 0; d < 3; ++d)
    if (std::abs(p[d]) < 1e-12 || std::abs(p[d] - 1.0) < 1e-12)
      return true;
  return false;
}

Vec3 point(const TetMesh& mesh, unsigned int g)
{
  return Vec3(mesh.position[3 * g], mesh.position[3 * g + 1], mesh.position[3 * g + 2]);
}

double tet_volume(const TetMesh& mesh, const std::array<unsigned int, 4>& t)
{
  const auto P = [&](int a) { return point(mesh, t[a]); };
  return (P(1) - P(0)).dot((P(2) - P(0)).cross(P(3) - P(0))) / 6.0;
}
} // namespace

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  BlockModel blocks;
  blocks.add_block(ConvexPolyhedron::box(Vec3::Zero(), Vec3(1, 1, 1)), 0);
  MeshReport report;
  TetMesh mesh = mesh_blocks(blocks, {0}, 0.25, report, ZoneElement::hex_mixed);
  std::printf("mesh: %u hexahedra, %u tetrahedra, %u gridpoints, %u + %u boundary faces, "
              "zone volume %.12g m^3 (each overlay counts half)\n",
              report.hexes, report.zones, report.gridpoints, report.boundary_faces,
              static_cast<unsigned int>(mesh.second_overlay_face_gridpoint.size()),
              report.zone_volume);
  // Each overlay of each hexahedron fills it, on its corners only.
  {
    double worst = 0.0;
    bool on_corners = true;
    for (unsigned int h = 0; h < mesh.n_hexes(); ++h)
    {
      double overlay[2] = {0.0, 0.0};
      for (unsigned int k = 0; k < 10; ++k)
      {
        const auto& t = mesh.zone_gridpoint[mesh.hex_first_zone[h] + k];
        overlay[k / 5] += tet_volume(mesh, t);
        for (unsigned int g : t)
          on_corners &=
              std::count(mesh.hex_gridpoint[h].begin(), mesh.hex_gridpoint[h].end(), g) == 1;
      }
      worst = std::max({worst, std::abs(overlay[0] - 1.0 / 64), std::abs(overlay[1] - 1.0 / 64)});
    }
    std::printf("each overlay fills its hexahedron: %s; tetrahedra on the hexahedron's corners: "
                "%s\n",
                worst < 1e-15 ? "yes" : "NO", on_corners ? "yes" : "NO");
    // Each overlay's boundary triangles cover the surface once: their area
    // vectors add up to zero and their areas to 6 m^2.
    for (const auto* faces : {&mesh.face_gridpoint, &mesh.second_overlay_face_gridpoint})
    {
      Vec3 sum = Vec3::Zero();
      double area = 0.0;
      for (const auto& f : *faces)
      {
        const Vec3 n =
            0.5 *
            (point(mesh, f[1]) - point(mesh, f[0])).cross(point(mesh, f[2]) - point(mesh, f[0]));
        sum += n;
        area += n.norm();
        // Outward: away from the cube's centre.
        if (n.dot(point(mesh, f[0]) - Vec3(0.5, 0.5, 0.5)) <= 0.0)
          area = -1e300;
      }
      talus_test::check(faces == &mesh.face_gridpoint ? "boundary area, first overlay (m^2)"
                                                      : "boundary area, second overlay (m^2)",
                        area, 6.0, 1e-14);
      std::printf("   closed and outward: %s\n", sum.norm() < 1e-14 ? "yes" : "NO");
    }
  }
  // Distort the interior.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> shift(-0.3 * 0.25, 0.3 * 0.25);
  for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
    if (!on_boundary(&mesh.position[3 * g]))
      for (int d = 0; d < 3; ++d)
        mesh.position[3 * g + d] += shift(random);
  {
    double smallest = 1e300;
    for (const auto& t : mesh.zone_gridpoint)
      smallest = std::min(smallest, tet_volume(mesh, t));
    std::printf("distorted mesh: every tetrahedron positive: %s\n", smallest > 0.0 ? "yes" : "NO");
  }
  ZoneMaterial rock;
  rock.set_young_poisson(1e10, 0.25);
  rock.element = ZoneElement::hex_mixed;
  SolverSettings settings;
  settings.gravity = Vec3::Zero();
  const std::vector<unsigned int> material(mesh.n_zones(), 0);
  Eigen::Matrix3d G; // a general (non-symmetric) velocity gradient, 1/s
  G << 1.0, 0.3, -0.2, 0.5, -0.7, 0.4, 0.1, 0.6, 0.2;
  G *= 1e-9;

  // 1. One step of a linear velocity field everywhere.
  {
    GridpointCondition all;
    all.region = Box{Vec3(-1, -1, -1), Vec3(2, 2, 2)};
    all.velocity_gradient = G;
    DeformableSolver solver(mesh, {rock}, material, settings, {all});
    solver.step(); // moves
    solver.step(); // the strain of that motion
    // Eq. 59 of the strain increment (G + G^T)/2 dt.
    const Eigen::Matrix3d e = 0.5 * (G + G.transpose()) * solver.dt();
    const double K = rock.bulk_modulus, mu = rock.shear_modulus;
    const Eigen::Matrix3d exact =
        (K - 2.0 / 3.0 * mu) * e.trace() * Eigen::Matrix3d::Identity() + 2.0 * mu * e;
    const double* s = solver.stress().data();
    const double computed[6] = {s[0], s[1], s[2], s[3], s[4], s[5]};
    const double expected[6] = {exact(0, 0), exact(1, 1), exact(2, 2),
                                exact(0, 1), exact(1, 2), exact(2, 0)};
    double error = 0.0;
    for (int c = 0; c < 6; ++c)
      error = std::max(error, std::abs(computed[c] - expected[c]) / exact.cwiseAbs().maxCoeff());
    std::fprintf(stderr, "1. spread %g, error against eq. 59 %g\n",
                 talus_test::stress_spread(solver.stress()), error);
    std::printf("1. linear velocity field: largest difference between tetrahedron stresses %s; "
                "stress against eq. 59: %s\n",
                talus_test::stress_spread(solver.stress()) < 1e-12 ? "below 1e-12 of the stress"
                                                                   : "TOO LARGE",
                error < 1e-8 ? "within 1e-8 (the strain is measured on the mid-step geometry: to "
                               "the order of the strain, 1e-9)"
                             : "WRONG");
  }
  // 2. Linear displacement on the boundary, interior by the static solver.
  {
    const double faces[6][6] = {{-1, -1, -1, 2, 2, 0}, {-1, -1, 1, 2, 2, 2},  {-1, -1, -1, 2, 0, 2},
                                {-1, 1, -1, 2, 2, 2},  {-1, -1, -1, 0, 2, 2}, {1, -1, -1, 2, 2, 2}};
    std::vector<GridpointCondition> boundary;
    for (const auto& f : faces)
    {
      GridpointCondition c;
      c.region = Box{Vec3(f[0], f[1], f[2]) * 1.0 +
                         Vec3::Constant(-1e-9).cwiseProduct(Vec3(f[0] < 0, f[1] < 0, f[2] < 0)),
                     Vec3(f[3], f[4], f[5]) + Vec3::Constant(1e-9)};
      c.velocity_gradient = G;
      boundary.push_back(c);
    }
    DeformableSolver solver(mesh, {rock}, material, settings, boundary);
    for (int k = 0; k < 10; ++k)
      solver.step();
    for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
      if (on_boundary(&mesh.position[3 * g]))
        solver.hold_gridpoint(g, Vec3::Zero());
    solver.run_to_ratio(1e-12, 200000);
    const std::vector<double> u = solver.displacements();
    double error = 0.0, size = 0.0;
    for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
    {
      const Vec3 exact = 10.0 * solver.dt() * G * point(mesh, g);
      error = std::max(error, (Vec3(u[3 * g], u[3 * g + 1], u[3 * g + 2]) - exact).norm());
      size = std::max(size, exact.norm());
    }
    std::fprintf(stderr, "2. displacement error %g, stress spread %g\n", error / size,
                 talus_test::stress_spread(solver.stress()));
    std::printf("2. boundary-driven patch: equilibrium reached: %s\n",
                solver.unbalanced_ratio() < 1e-12 ? "yes" : "NO");
    std::printf("   interior on the linear field: largest error %s of the largest displacement\n",
                error / size < 1e-6 ? "below 1e-6 (round-off of positions near 1 m)" : "TOO LARGE");
    std::printf("   tetrahedron stresses: largest difference %s\n",
                talus_test::stress_spread(solver.stress()) < 1e-7
                    ? "below 1e-7 of the stress (the geometry is updated, so uniform to the order "
                      "of the strain, 1e-8)"
                    : "TOO LARGE");
  }
  // 3. Rigid rotation by 90 degrees about an oblique axis in 90 steps.
  {
    DeformableSolver solver(mesh, {rock}, material, settings);
    const Vec3 axis = Vec3(1, 2, 3).normalized(), centre(0.5, 0.5, 0.5);
    const Eigen::Matrix3d R = Eigen::AngleAxisd(M_PI / 180.0, axis).toRotationMatrix();
    for (int k = 0; k < 90; ++k)
    {
      const std::vector<double> x = solver.positions();
      for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
      {
        const Vec3 p(x[3 * g], x[3 * g + 1], x[3 * g + 2]);
        solver.hold_gridpoint(g, ((R - Eigen::Matrix3d::Identity()) * (p - centre)) / solver.dt());
      }
      solver.step();
    }
    for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
      solver.hold_gridpoint(g, Vec3::Zero());
    solver.step();
    double largest = 0.0;
    for (double s : solver.stress())
      largest = std::max(largest, std::abs(s));
    std::fprintf(stderr, "3. largest stress / E %g\n", largest / rock.young());
    std::printf("3. rigid rotation by 90 degrees: largest stress over E: %s\n",
                largest / rock.young() < 1e-12 ? "below 1e-12" : "TOO LARGE");
  }
}
