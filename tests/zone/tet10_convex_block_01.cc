// 10-node zones (tet10) on the meshes of jointed convex blocks: the largest
// block of a unit cube cut by two oblique joints (not a brick, so meshed by
// the lattice mesher through mesh_blocks, lattice_block_mesher.h) at h = 0.2 m, made
// quadratic by make_quadratic (edge-midpoint gridpoints, straight zones).
// Patch tests as tests/zone/tet10_patch_01 does on a brick:
// 1. a linear velocity field: every Gauss point gets the closed-form stress
//    of the uniform strain, to round-off;
// 2. a quadratic velocity field (linear strain): every Gauss point gets the
//    closed-form stress at its own position, to the order of the motion
//    within the step (1e-9); the same field on the 4-node zones of the same
//    mesh gives each zone one stress, off the closed form at its centroid by
//    far more (the tet10 zones' gain);
// 3. lumped masses (HRZ): all positive, summing to the block's mass.

#include <talus/base/parallel_environment.h>
#include <talus/geometry/block_generator.h>
#include <talus/solver/deformable_solver.h>
#include <talus/zone/block_mesher.h>
#include <talus/zone/tet10_kernel.h>
#include <talus/zone/tet10_mesh.h>

#include <cmath>
#include <cstdio>

#include "../tests.h"

using namespace talus;
using talus_test::verdict;

namespace
{
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
  BlockGenerator generator(ConvexPolyhedron::box(Vec3::Zero(), Vec3::Ones()), {});
  generator.cut_plane(Plane::through(Vec3(0.5, 0.45, 0.55), normal_from_dip(35.0, 60.0)));
  generator.cut_plane(Plane::through(Vec3(0.7, 0.5, 0.5), normal_from_dip(75.0, 100.0)));
  BlockModel blocks;
  for (const ConvexPolyhedron& b : generator.blocks())
    blocks.add_block(b, 0);
  unsigned int block = 0;
  for (unsigned int b = 1; b < blocks.n_blocks(); ++b)
    if (blocks.volume[b] > blocks.volume[block])
      block = b;
  MeshReport report;
  const TetMesh linear = mesh_blocks(blocks, {block}, EdgeLengthField(0.2), report);
  TetMesh mesh = linear;
  make_quadratic(mesh);
  std::printf("block of %u faces meshed at h = 0.2 m and made quadratic: every zone 10-node: "
              "%s\n",
              blocks.face_start[block + 1] - blocks.face_start[block],
              verdict(mesh.quadratic() && mesh.zone_edge_gridpoint.size() == linear.n_zones()));
  std::fprintf(stderr, "block %u: volume %.6g m^3, %u zones, %u gridpoints (%u vertices)\n", block,
               blocks.volume[block], mesh.n_zones(), mesh.n_gridpoints(), linear.n_gridpoints());

  ZoneMaterial rock;
  rock.set_young_poisson(1e10, 0.25);
  ZoneMaterial rock4 = rock;
  rock.element = ZoneElement::tet10;
  SolverSettings settings;
  settings.gravity = Vec3::Zero();
  const std::vector<unsigned int> material(mesh.n_zones(), 0);

  // 1. Linear velocity field on every gridpoint.
  {
    Eigen::Matrix3d G;
    G << 1.0, 0.3, -0.2, 0.5, -0.7, 0.4, 0.1, 0.6, 0.2;
    G *= 1e-9;
    GridpointCondition all;
    all.region = Box{Vec3(-1, -1, -1), Vec3(2, 2, 2)};
    all.velocity_gradient = G;
    DeformableSolver solver(mesh, {rock}, material, settings, {all});
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
    std::fprintf(stderr, "1. %zu Gauss points, largest relative deviation %g\n",
                 solver.stress().size() / 6, deviation);
    std::printf("1. linear velocity field: every Gauss-point stress on the closed form within "
                "1e-12: %s\n",
                verdict(solver.stress().size() == 24 * mesh.n_zones() && deviation < 1e-12));
  }
  // 2. Quadratic velocity field v = G x + 1e-9 (y z, x^2, x y) (m/s).
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
    DeformableSolver solver(mesh, {rock}, material, settings);
    for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
      solver.hold_gridpoint(g, velocity(at(mesh.position, g)));
    solver.step();
    solver.step();
    double scale = 0.0, deviation = 0.0, spread = 0.0;
    for (unsigned int z = 0; z < mesh.n_zones(); ++z)
    {
      double point[4][3];
      tet10_gauss_points(mesh, z, point);
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
    deviation /= scale;
    spread /= scale;
    std::printf("2. quadratic velocity field: every Gauss-point stress on the closed form at its "
                "position within 1e-8: %s\n",
                verdict(deviation < 1e-8));
    std::printf("   (the stress varies within a zone: largest difference between its Gauss "
                "points above 1e-3 of the largest stress: %s)\n",
                verdict(spread > 1e-3));

    // The same field on the 4-node zones of the same mesh: one stress per
    // zone, against the closed form at the zone's centroid.
    DeformableSolver solver4(linear, {rock4}, std::vector<unsigned int>(linear.n_zones(), 0),
                             settings);
    for (unsigned int g = 0; g < linear.n_gridpoints(); ++g)
      solver4.hold_gridpoint(g, velocity(at(linear.position, g)));
    solver4.step();
    solver4.step();
    double scale4 = 0.0, deviation4 = 0.0;
    for (unsigned int z = 0; z < linear.n_zones(); ++z)
    {
      Vec3 centroid = Vec3::Zero();
      for (unsigned int g : linear.zone_gridpoint[z])
        centroid += 0.25 * at(linear.position, g);
      double exact[6];
      elastic_stress(rock4, gradient(centroid), solver4.dt(), exact);
      for (int c = 0; c < 6; ++c)
      {
        scale4 = std::max(scale4, std::abs(exact[c]));
        deviation4 = std::max(deviation4, std::abs(solver4.stress()[6 * z + c] - exact[c]));
      }
    }
    deviation4 /= scale4;
    std::fprintf(stderr,
                 "2. tet10: largest relative deviation %g, spread within zones %g; tet4: largest "
                 "relative deviation at zone centroids %g\n",
                 deviation, spread, deviation4);
    std::printf("   4-node zones of the same mesh: largest error at their centroids above 1e-3, "
                "above 1e4 times the 10-node zones': %s\n",
                verdict(deviation4 > 1e-3 && deviation4 > 1e4 * deviation));
  }
  // 3. Lumped masses.
  {
    double total = 0.0, smallest = 1e300;
    for (unsigned int z = 0; z < mesh.n_zones(); ++z)
    {
      double m[10], k[10];
      tet10_mass_and_stiffness(mesh, z, rock.density, rock.bulk_modulus, rock.shear_modulus, m, k);
      for (int a = 0; a < 10; ++a)
      {
        total += m[a];
        smallest = std::min(smallest, m[a]);
      }
    }
    const double exact = rock.density * blocks.volume[block];
    std::fprintf(stderr, "3. lumped masses: sum %.15g kg, block %.15g kg, smallest %g kg\n", total,
                 exact, smallest);
    std::printf("3. lumped masses all positive: %s; summing to the block's mass within 1e-12: "
                "%s\n",
                verdict(smallest > 0.0),
                verdict(talus_test::relative_error(total, exact) <= 1e-12));
  }
}
