#pragma once

// The patch tests of a convex block's mesh, shared by convex_block_mesher_03
// (gmsh) and lattice_block_mesher_02 (the lattice mesher). Constant-strain
// tetrahedra represent a linear displacement field exactly, so on a valid
// mesh:
// 1. a linear displacement imposed on the mesh's boundary gridpoints, the
//    interior found by the explicit static solver (DeformableSolver, as in
//    deformable/patch_test_01): interior gridpoints on the linear field,
//    every zone at the same stress;
// 2. a uniform stress applied as tractions on the block's faces (each
//    boundary triangle loaded with the stress times the normal of the block
//    face it lies on), the displacement found by the implicit solver with
//    three gridpoints held on the exact field: the exact linear field
//    everywhere. This holds only if the mesh's surface is the block's
//    surface (each triangle's area vector is its share of the face's).

#include <talus/geometry/block_generator.h>
#include <talus/solver/deformable_solver.h>
#include <talus/zone/implicit_elastic.h>

#include <cmath>
#include <cstdio>
#include <iterator>
#include <set>

#include "../tests.h"
#include "convex_block_mesher_checks.h"

namespace block_patch
{
using namespace talus;

inline Vec3 position(const TetMesh& mesh, unsigned int g)
{
  return Vec3(mesh.position[3 * g], mesh.position[3 * g + 1], mesh.position[3 * g + 2]);
}

/// Which three gridpoints test 2 holds on the exact field: the mesher's
/// first three, all components of each (the lattice mesher's are corners
/// of the block, never in one line); or three boundary gridpoints a third
/// of the boundary apart, all components of the first, two of the second,
/// one of the third (gmsh's first ones may lie in one line).
enum class Hold
{
  first_three_whole,
  boundary_thirds
};

/// A unit cube cut by one oblique joint; `larger` is its larger block (7
/// faces), the one both patch tests mesh.
inline BlockModel cut_cube(unsigned int& larger)
{
  BlockGenerator generator(ConvexPolyhedron::box(Vec3::Zero(), Vec3::Ones()), {});
  generator.cut_plane(Plane::through(Vec3(0.5, 0.45, 0.55), normal_from_dip(35.0, 60.0)));
  BlockModel blocks;
  for (const ConvexPolyhedron& b : generator.blocks())
    blocks.add_block(b, 0);
  larger = blocks.volume[0] > blocks.volume[1] ? 0 : 1;
  return blocks;
}

/// Runs both tests on `zones`, the mesh of block `block` of `blocks` at
/// edge length `h` (m), and prints their verdicts.
inline void run(const BlockModel& blocks, unsigned int block, double h,
                const BlockTetrahedra& zones, Hold hold)
{
  const TetMesh mesh = talus_test::to_tet_mesh({zones}, {block});
  std::set<unsigned int> boundary;
  for (const auto& f : mesh.face_gridpoint)
    boundary.insert(f.begin(), f.end());
  std::fprintf(stderr, "block %u: %u zones, %u gridpoints, %zu on the boundary\n", block,
               mesh.n_zones(), mesh.n_gridpoints(), boundary.size());
  std::printf("block of %u faces meshed at h = %g m: interior gridpoints: %s\n",
              blocks.face_start[block + 1] - blocks.face_start[block], h,
              talus_test::verdict(boundary.size() < mesh.n_gridpoints()));

  ZoneMaterial rock;
  rock.set_young_poisson(1e10, 0.25);
  // 1. Linear displacement on the boundary, interior by the explicit solver.
  {
    SolverSettings settings;
    settings.gravity = Vec3::Zero();
    Eigen::Matrix3d G; // a general (non-symmetric) velocity gradient, 1/s
    G << 1.0, 0.3, -0.2, 0.5, -0.7, 0.4, 0.1, 0.6, 0.2;
    G *= 1e-9;
    DeformableSolver solver(mesh, {rock}, std::vector<unsigned int>(mesh.n_zones(), 0), settings);
    // Ten steps at the velocity G x0 on the boundary, then held while the
    // interior settles.
    for (unsigned int g : boundary)
      solver.hold_gridpoint(g, G * position(mesh, g));
    for (int k = 0; k < 10; ++k)
      solver.step();
    for (unsigned int g : boundary)
      solver.hold_gridpoint(g, Vec3::Zero());
    const unsigned long steps = solver.run_to_ratio(1e-12, 200000);
    const std::vector<double> u = solver.displacements();
    double error = 0.0, size = 0.0;
    for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
    {
      const Vec3 exact = 10.0 * solver.dt() * G * position(mesh, g);
      error = std::max(error, (Vec3(u[3 * g], u[3 * g + 1], u[3 * g + 2]) - exact).norm());
      size = std::max(size, exact.norm());
    }
    std::fprintf(stderr, "1. steps %lu, ratio %g, displacement error %g, stress spread %g\n", steps,
                 solver.unbalanced_ratio(), error / size,
                 talus_test::stress_spread(solver.stress()));
    std::printf("1. boundary-driven patch: equilibrium reached: %s\n",
                talus_test::verdict(solver.unbalanced_ratio() < 1e-12));
    std::printf("   interior on the linear field within 1e-6 of the largest displacement: %s\n",
                talus_test::verdict(error / size < 1e-6));
    std::printf("   zone stresses equal within 1e-7 (the geometry is updated: strain 1e-8): %s\n",
                talus_test::verdict(talus_test::stress_spread(solver.stress()) < 1e-7));
  }
  // 2. Uniform stress as tractions on the block's faces, implicit solver.
  {
    Eigen::Matrix3d sigma; // Pa
    sigma << -2e6, 0.5e6, -0.3e6, 0.5e6, -1e6, 0.8e6, -0.3e6, 0.8e6, -3e6;
    const double K = rock.young() / (3.0 * (1.0 - 2.0 * 0.25)),
                 mu = rock.young() / (2.0 * (1.0 + 0.25));
    const Eigen::Matrix3d strain =
        (sigma - sigma.trace() / 3.0 * Eigen::Matrix3d::Identity()) / (2.0 * mu) +
        sigma.trace() / (9.0 * K) * Eigen::Matrix3d::Identity();
    ImplicitElasticProblem problem;
    problem.mesh = &mesh;
    problem.zone_bulk.assign(mesh.n_zones(), K);
    problem.zone_shear.assign(mesh.n_zones(), mu);
    problem.nodal_force.assign(3 * mesh.n_gridpoints(), 0.0);
    problem.tolerance = 1e-13;
    for (const auto& f : mesh.face_gridpoint)
    {
      const Vec3 a = position(mesh, f[0]), b = position(mesh, f[1]), c = position(mesh, f[2]);
      const double area = 0.5 * (b - a).cross(c - a).norm();
      // The block face the triangle lies on: the one whose plane is nearest.
      unsigned int face = blocks.face_start[block];
      double nearest = 1e300;
      for (unsigned int k = blocks.face_start[block]; k < blocks.face_start[block + 1]; ++k)
      {
        const Vec3& n = blocks.face_normal[k];
        const Vec3& o = blocks.vertex[blocks.face_vertex[blocks.face_loop_start[k]]];
        const double d = std::abs(n.dot(a - o)) + std::abs(n.dot(b - o)) + std::abs(n.dot(c - o));
        if (d < nearest)
        {
          nearest = d;
          face = k;
        }
      }
      const Vec3 load = sigma * blocks.face_normal[face] * (area / 3.0);
      for (unsigned int g : f)
        for (int d = 0; d < 3; ++d)
          problem.nodal_force[3 * g + d] += load[d];
    }
    // Three gridpoints on the exact field (x exactly u = strain x), as
    // `hold` says.
    problem.fixed.assign(mesh.n_gridpoints(), 0);
    problem.prescribed.assign(3 * mesh.n_gridpoints(), 0.0);
    unsigned int held[3];
    unsigned char bits[3];
    if (hold == Hold::first_three_whole)
      for (unsigned int k = 0; k < 3; ++k)
      {
        held[k] = k;
        bits[k] = 7;
      }
    else
    {
      auto it = boundary.begin();
      const unsigned int at[3] = {0, static_cast<unsigned int>(boundary.size() / 3),
                                  static_cast<unsigned int>(2 * boundary.size() / 3)};
      const unsigned char some[3] = {7, 6, 4};
      for (unsigned int k = 0; k < 3; ++k)
      {
        held[k] = *std::next(it, at[k]);
        bits[k] = some[k];
      }
    }
    for (int k = 0; k < 3; ++k)
    {
      problem.fixed[held[k]] = bits[k];
      const Vec3 u = strain * position(mesh, held[k]);
      for (int d = 0; d < 3; ++d)
        problem.prescribed[3 * held[k] + d] = u[d];
    }
    const ImplicitElasticResult result = solve_implicit_elastic(problem);
    double error = 0.0, size = 0.0;
    for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
    {
      const Vec3 exact = strain * position(mesh, g);
      const Vec3 u(result.displacement[3 * g], result.displacement[3 * g + 1],
                   result.displacement[3 * g + 2]);
      error = std::max(error, (u - exact).norm());
      size = std::max(size, exact.norm());
    }
    std::fprintf(stderr, "2. CG iterations %u, displacement error %g\n", result.iterations,
                 error / size);
    std::printf("2. traction patch on the block's faces: displacement on the linear field within "
                "1e-8: %s\n",
                talus_test::verdict(error / size < 1e-8));
  }
}

} // namespace block_patch
