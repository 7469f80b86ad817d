// The energy account of nodal mixed discretization (eqs. 68-76) with
// plastic zones: a 2 m cube of 5 * 6^3 zones (rho = 2650, E = 1e9 Pa, nu =
// 0.3), its base held, released unstressed under gravity in dynamic mode,
// undamped; Mohr-Coulomb with c = 5 kPa, phi = 20 deg, psi = 10 deg
// (dilation: the plastic pressure of eqs. 73-76 is traded), sigma_t = 2
// kPa, so that many zones yield as it sags and rings (rho g H = 52 kPa
// against a uniaxial strength of 2 c sqrt(N_phi) = 14 kPa). After 400
// steps the account must close within 1e-4 of its largest term, as it does
// for plain 4-node zones on the same mesh: the forces of nodal mixed zones
// act with each zone's own volumetric strain while their stresses follow
// the gridpoint average, and the account counts the work of the
// difference (before it did not, and was off by 3.8e-2 here).

#include <talus/base/parallel_environment.h>
#include <talus/solver/deformable_solver.h>
#include <talus/solver/energy_account.h>
#include <talus/zone/block_mesher.h>
#include <talus/zone/mesh_order.h>

#include <cmath>
#include <cstdio>

#include "../tests.h"

using namespace talus;

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  const double side = 2.0;
  BlockModel blocks;
  blocks.add_block(ConvexPolyhedron::box(Vec3::Zero(), Vec3::Constant(side)), 0);
  MeshReport report;
  const TetMesh mesh = mesh_blocks(blocks, {0}, side / 6, report);
  ZoneMaterial material;
  material.density = 2650.0;
  material.set_young_poisson(1e9, 0.3);
  material.model = ZoneModel::mohr_coulomb;
  material.cohesion = 5e3;
  material.friction_angle = 20.0;
  material.dilation_angle = 10.0;
  material.tensile_strength = 2e3;
  SolverSettings settings;
  settings.dynamic = true;
  settings.gravity = Vec3(0, 0, -9.81);
  GridpointCondition base;
  base.region = Box{Vec3(-1, -1, -1e-9), Vec3(side + 1, side + 1, 1e-9)};
  for (const bool mixed : {false, true})
  {
    material.nodal_mixed = mixed;
    DeformableSolver solver(mesh, {material}, std::vector<unsigned int>(mesh.n_zones(), 0),
                            settings, {base});
    double worst = 0.0;
    for (int k = 0; k < 400; ++k)
    {
      solver.step();
      EnergyAccount e;
      solver.add_energy(e);
      worst = std::max(worst, std::abs(e.error()) / e.scale());
    }
    EnergyAccount e;
    solver.add_energy(e);
    unsigned int yielded = 0;
    for (unsigned char s : solver.plastic_state())
      yielded += (s & (shear_past | tension_past)) != 0;
    const char* name = mixed ? "nodal mixed" : "plain 4-node";
    std::fprintf(stderr,
                 "%s: %u of %u zones yielded; account error at most %.3g of its largest term; "
                 "elastic %.6g J, plastic %.6g J, gravity %.6g J\n",
                 name, yielded, mesh.n_zones(), worst, e.zone_elastic, e.plastic, e.gravity_work);
    std::printf("%s: more than a tenth of the zones yielded: %s\n", name,
                talus_test::verdict(yielded > mesh.n_zones() / 10));
    std::printf("%s: plastic dissipation above a tenth of the elastic energy: %s\n", name,
                talus_test::verdict(e.plastic > 0.1 * e.zone_elastic));
    std::printf("%s: energy account error within 1e-4 of its largest term: %s\n", name,
                talus_test::verdict(worst <= 1e-4));
  }
}
