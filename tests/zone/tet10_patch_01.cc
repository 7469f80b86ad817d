// Patch tests of the 10-node tetrahedral zones (tet10_kernel.h) on a unit
// cube of 320 zones whose interior vertices are moved at random by up to
// 30 % of the zone size:
// 1. a linear velocity field on zones whose interior edge midpoints are
//    also moved (curved zones): every Gauss point gets the closed-form
//    elastic stress of the uniform strain (of the gradient on the mid-step
//    geometry, where the kernel measures it), to round-off;
// 2. a quadratic velocity field (linear strain) on straight-sided zones:
//    every Gauss point gets the closed-form stress at its own position
//    (a 4-node zone could only give the zone's mean), to the order of the
//    motion within the step (1e-9);
// 3. the curved mesh turned rigidly by 90 degrees in 90 steps: no stress;
// 4. lumped masses (HRZ): all positive, summing to the mass of the cube.

#include <talus/base/parallel_environment.h>
#include <talus/solver/deformable_solver.h>
#include <talus/zone/block_mesher.h>
#include <talus/zone/tet10_kernel.h>
#include <talus/zone/tet10_mesh.h>

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

/// Elastic stress (xx, yy, zz, xy, yz, zx) of the symmetric part of the
/// velocity gradient L times dt.
void elastic_stress(const ZoneMaterial& m, const Eigen::Matrix3d& L, double dt, double* s)
{
  const Eigen::Matrix3d e = 0.5 * (L + L.transpose()) * dt;
  const double lambda = m.bulk_modulus - 2.0 * m.shear_modulus / 3.0;
  const double tr = e.trace();
  s[0] = lambda * tr + 2 * m.shear_modulus * e(0, 0);
  s[1] = lambda * tr + 2 * m.shear_modulus * e(1, 1);
  s[2] = lambda * tr + 2 * m.shear_modulus * e(2, 2);
  s[3] = 2 * m.shear_modulus * e(0, 1);
  s[4] = 2 * m.shear_modulus * e(1, 2);
  s[5] = 2 * m.shear_modulus * e(2, 0);
}

Vec3 at(const std::vector<double>& x, unsigned int g)
{
  return Vec3(x[3 * g], x[3 * g + 1], x[3 * g + 2]);
}
} // namespace

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  BlockModel blocks;
  blocks.add_block(ConvexPolyhedron::box(Vec3::Zero(), Vec3(1, 1, 1)), 0);
  MeshReport report;
  TetMesh straight = mesh_blocks(blocks, {0}, 0.25, report);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> shift(-0.3 * 0.25, 0.3 * 0.25);
  for (unsigned int g = 0; g < straight.n_gridpoints(); ++g)
    if (!on_boundary(&straight.position[3 * g]))
      for (int d = 0; d < 3; ++d)
        straight.position[3 * g + d] += shift(random);
  make_quadratic(straight);
  TetMesh curved = straight;
  std::uniform_real_distribution<double> bend(-0.05 * 0.25, 0.05 * 0.25);
  unsigned int n_vertices = 0;
  for (const auto& t : curved.zone_gridpoint)
    for (unsigned int g : t)
      n_vertices = std::max(n_vertices, g + 1);
  for (unsigned int g = n_vertices; g < curved.n_gridpoints(); ++g)
    if (!on_boundary(&curved.position[3 * g]))
      for (int d = 0; d < 3; ++d)
        curved.position[3 * g + d] += bend(random);
  std::printf("mesh: %u 10-node zones, %u gridpoints (%u vertices), %u boundary triangles\n",
              curved.n_zones(), curved.n_gridpoints(), n_vertices, curved.n_faces());

  ZoneMaterial rock;
  rock.set_young_poisson(1e10, 0.25);
  rock.element = ZoneElement::tet10;
  SolverSettings settings;
  settings.gravity = Vec3::Zero();
  const std::vector<unsigned int> material(curved.n_zones(), 0);

  // 1. Linear velocity field on the curved mesh.
  {
    Eigen::Matrix3d G;
    G << 1.0, 0.3, -0.2, 0.5, -0.7, 0.4, 0.1, 0.6, 0.2;
    G *= 1e-9;
    GridpointCondition all;
    all.region = Box{Vec3(-1, -1, -1), Vec3(2, 2, 2)};
    all.velocity_gradient = G;
    DeformableSolver solver(curved, {rock}, material, settings, {all});
    solver.step(); // moves
    solver.step(); // the strain of that motion
    // The gradient on the mid-step geometry x0 + G x0 dt / 2, where the
    // kernel measures it: G (I + G dt / 2)^-1.
    const Eigen::Matrix3d L = G * (Eigen::Matrix3d::Identity() + 0.5 * solver.dt() * G).inverse();
    double exact[6];
    elastic_stress(rock, L, solver.dt(), exact);
    double scale = 0.0, deviation = 0.0;
    for (int c = 0; c < 6; ++c)
      scale = std::max(scale, std::abs(exact[c]));
    for (std::size_t p = 0; p < solver.stress().size() / 6; ++p)
      for (int c = 0; c < 6; ++c)
        deviation = std::max(deviation, std::abs(solver.stress()[6 * p + c] - exact[c]) / scale);
    std::fprintf(stderr, "1. largest deviation %g\n", deviation);
    std::printf("1. linear velocity field, curved zones: sigma_xx at Gauss point 0 %.10g Pa, "
                "closed form %.10g Pa;\n   largest relative error over %zu Gauss points and six "
                "components: %s\n",
                solver.stress()[0], exact[0], solver.stress().size() / 6,
                deviation < 1e-12 ? "below 1e-12" : "TOO LARGE");
  }
  // 2. Quadratic velocity field on straight-sided zones:
  // v = G x + 1e-9 (y z, x^2, x y) (m/s).
  {
    Eigen::Matrix3d G;
    G << 0.4, -0.2, 0.3, 0.1, 0.5, -0.6, 0.2, 0.3, -0.1;
    G *= 1e-9;
    const auto velocity = [&](const Vec3& x)
    { return Vec3(G * x + 1e-9 * Vec3(x[1] * x[2], x[0] * x[0], x[0] * x[1])); };
    const auto gradient = [&](const Vec3& x)
    {
      Eigen::Matrix3d L = G;
      L(0, 1) += 1e-9 * x[2];
      L(0, 2) += 1e-9 * x[1];
      L(1, 0) += 2e-9 * x[0];
      L(2, 0) += 1e-9 * x[1];
      L(2, 1) += 1e-9 * x[0];
      return L;
    };
    DeformableSolver solver(straight, {rock}, material, settings);
    for (unsigned int g = 0; g < straight.n_gridpoints(); ++g)
      solver.hold_gridpoint(g, velocity(at(straight.position, g)));
    solver.step();
    solver.step();
    double scale = 0.0, deviation = 0.0, spread = 0.0;
    for (unsigned int z = 0; z < straight.n_zones(); ++z)
    {
      double point[4][3];
      tet10_gauss_points(straight, z, point);
      for (int q = 0; q < 4; ++q)
      {
        double exact[6];
        elastic_stress(rock, gradient(Vec3(point[q][0], point[q][1], point[q][2])), solver.dt(),
                       exact);
        for (int c = 0; c < 6; ++c)
        {
          scale = std::max(scale, std::abs(exact[c]));
          deviation =
              std::max(deviation, std::abs(solver.stress()[6 * (4 * z + q) + c] - exact[c]));
          spread = std::max(spread, std::abs(solver.stress()[6 * (4 * z + q) + c] -
                                             solver.stress()[6 * (4 * z) + c]));
        }
      }
    }
    std::fprintf(stderr, "2. largest deviation %g, spread within zones %g\n", deviation / scale,
                 spread / scale);
    std::printf("2. quadratic velocity field: largest relative error of a Gauss-point stress "
                "against the closed form at its position: %s\n",
                deviation / scale < 1e-8 ? "below 1e-8" : "TOO LARGE");
    std::printf("   (the stress varies within a zone: largest difference between its Gauss "
                "points %s of the largest stress)\n",
                spread / scale > 1e-2 ? "above 1e-2" : "TOO SMALL");
  }
  // 3. Rigid rotation of the curved mesh by 90 degrees about an oblique axis
  // in 90 steps.
  {
    DeformableSolver solver(curved, {rock}, material, settings);
    const Vec3 axis = Vec3(1, 2, 3).normalized(), centre(0.5, 0.5, 0.5);
    const Eigen::Matrix3d R = Eigen::AngleAxisd(M_PI / 180.0, axis).toRotationMatrix();
    for (int k = 0; k < 90; ++k)
    {
      const std::vector<double> x = solver.positions();
      for (unsigned int g = 0; g < curved.n_gridpoints(); ++g)
        solver.hold_gridpoint(g, ((R - Eigen::Matrix3d::Identity()) * (at(x, g) - centre)) /
                                     solver.dt());
      solver.step();
    }
    for (unsigned int g = 0; g < curved.n_gridpoints(); ++g)
      solver.hold_gridpoint(g, Vec3::Zero());
    solver.step();
    double largest = 0.0;
    for (double s : solver.stress())
      largest = std::max(largest, std::abs(s));
    const std::vector<double> x = solver.positions();
    const Eigen::Matrix3d turned = Eigen::AngleAxisd(M_PI / 2, axis).toRotationMatrix();
    double position_error = 0.0;
    for (unsigned int g = 0; g < curved.n_gridpoints(); ++g)
      position_error =
          std::max(position_error,
                   (at(x, g) - (centre + turned * (at(curved.position, g) - centre))).norm());
    std::fprintf(stderr, "3. position error %g m, largest stress / E %g\n", position_error,
                 largest / rock.young());
    std::printf("3. rigid rotation by 90 degrees: turned as a rigid body: %s; largest stress "
                "over E %s\n",
                position_error < 1e-12 ? "yes" : "NO",
                largest / rock.young() < 1e-12 ? "below 1e-12" : "TOO LARGE");
  }
  // 4. Lumped masses.
  {
    double total = 0.0, smallest = 1e300;
    for (unsigned int z = 0; z < straight.n_zones(); ++z)
    {
      double m[10], k[10];
      tet10_mass_and_stiffness(straight, z, rock.density, rock.bulk_modulus, rock.shear_modulus, m,
                               k);
      for (int a = 0; a < 10; ++a)
      {
        total += m[a];
        smallest = std::min(smallest, m[a]);
      }
    }
    talus_test::check("4. sum of the lumped masses (kg)", total, rock.density * 1.0, 1e-12);
    std::printf("   every lumped mass positive: %s\n", smallest > 0.0 ? "yes" : "NO");
  }
}
