// Rayleigh's stiffness-proportional forces in the nodal-force pass
// (tet4_nodal_forces_viscous, tet10_nodal_forces_viscous): on a unit cube
// of 5 * 3^3 zones (batches of 135 zones: whole groups of lanes and a short
// last one), 4-node and made 10-node, with random velocities and stresses,
// the fused pass must add bitwise the forces that viscous_stress and a
// second nodal-force pass add, to the stresses' forces, their sizes and the
// damping forces alike; and with no stress (nodal mixed discretization
// when zones yielded, its forces taken later) the damping forces alone.

#include <talus/base/parallel_environment.h>
#include <talus/zone/block_mesher.h>
#include <talus/zone/tet10_kernel.h>
#include <talus/zone/tet10_mesh.h>
#include <talus/zone/tet4_kernel.h>
#include <talus/zone/viscous_stress.h>

#include <cstdio>
#include <random>
#include <vector>

#include "../tests.h"

using namespace talus;

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  BlockModel blocks;
  blocks.add_block(ConvexPolyhedron::box(Vec3::Zero(), Vec3::Constant(1.0)), 0);
  MeshReport report;
  TetMesh linear = mesh_blocks(blocks, {0}, 1.0 / 3, report);
  TetMesh quadratic = linear;
  make_quadratic(quadratic);
  const double K = 8e9, G = 5e9, beta_over_dt = 0.37, dt = 1e-4;
  const ViscousModuli moduli(K, G, beta_over_dt);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (const TetMesh* mesh : {&linear, &quadratic})
  {
    const bool tet10 = mesh == &quadratic;
    const unsigned int nz = mesh->n_zones(), ng = mesh->n_gridpoints(), points = tet10 ? 4 : 1;
    std::vector<double> v(3 * ng), stress(6 * points * nz);
    for (double& x : v)
      x = uniform(random);
    for (double& s : stress)
      s = 1e6 * uniform(random);
    // Forces: [0] separate passes, [1] fused; force, size, damping.
    std::vector<double> f[2], size[2], damping[2], damping_alone(3 * ng, 0.0);
    for (int k = 0; k < 2; ++k)
    {
      f[k].assign(3 * ng, 0.0);
      size[k].assign(3 * ng, 0.0);
      damping[k].assign(3 * ng, 0.0);
    }
    std::vector<double> turned = stress, viscous(stress.size());
    if (tet10)
    {
      Tet10Scratch s;
      s.resize(nz);
      tet10_strain_increments(*mesh, 0, nz, mesh->position.data(), v.data(), dt, turned.data(), s);
      tet10_nodal_forces(*mesh, 0, nz, turned.data(), s, f[0].data(), size[0].data());
      viscous_stress(4 * nz, K, G, beta_over_dt, s.strain_increment.data(), viscous.data());
      tet10_nodal_forces(*mesh, 0, nz, viscous.data(), s, damping[0].data());
      tet10_nodal_forces_viscous(*mesh, 0, nz, turned.data(), s, moduli, f[1].data(),
                                 size[1].data(), damping[1].data());
      damping_alone = damping[0]; // (no stress-less form for 10-node zones)
    }
    else
    {
      Tet4Scratch s;
      s.resize(nz);
      tet4_strain_increments(*mesh, 0, nz, mesh->position.data(), v.data(), dt, turned.data(), s);
      tet4_nodal_forces(*mesh, 0, nz, turned.data(), s, f[0].data(), size[0].data());
      viscous_stress(nz, K, G, beta_over_dt, s.strain_increment.data(), viscous.data());
      tet4_nodal_forces(*mesh, 0, nz, viscous.data(), s, damping[0].data());
      tet4_nodal_forces_viscous(*mesh, 0, nz, turned.data(), s, moduli, f[1].data(), size[1].data(),
                                damping[1].data());
      tet4_nodal_forces_viscous(*mesh, 0, nz, nullptr, s, moduli, nullptr, nullptr,
                                damping_alone.data());
    }
    double largest = 0.0;
    for (double d : damping[0])
      largest = std::max(largest, std::abs(d));
    const char* name = tet10 ? "10-node" : "4-node";
    std::fprintf(stderr, "%s: %u zones, largest damping force %.3g N\n", name, nz, largest);
    std::printf("%s: damping forces not all zero: %s\n", name, talus_test::verdict(largest > 0.0));
    std::printf(
        "%s: fused pass bitwise as two passes (forces, sizes, damping): %s\n", name,
        talus_test::verdict(f[1] == f[0] && size[1] == size[0] && damping[1] == damping[0]));
    std::printf("%s: damping forces alone bitwise the same: %s\n", name,
                talus_test::verdict(damping_alone == damping[0]));
  }
}
