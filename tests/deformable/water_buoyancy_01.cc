// Water on a deformable block: the block of
// parameters/verification/deformable_on_incline.prm (1 x 2 x 1 m, 2650
// kg/m^3, zones of edge 0.5 m) resting on its fixed rigid base, under
// vertical gravity, settled by a static run. With the water level above
// the block (z_w = 3 m, the block from z = 1 to 2) every boundary face of
// its zones carries rho_w g (z_w - z), the faces on the joint too, and the
// joint's normal force drops from W = rho g V to the effective
// W - rho_w g V (buoyancy). With the level at mid-height (z_w = 1.5 m) it
// drops by half of that. For 4-node zones, hexahedral zones (the block is
// an axis-aligned brick) and 10-node zones. Without water (the before
// figure) the joint carries W.

#include <talus/base/parallel_environment.h>
#include <talus/scene/build_blocks.h>
#include <talus/scene/block_system.h>

#include <cmath>
#include <cstdio>

#include "../tests.h"

using namespace talus;

namespace
{
const double g = 9.81, V = 2.0, rho = 2650.0, rho_w = 1000.0;

/// The joint's normal force (N, compression positive) once settled.
double joint_force(ZoneElement element, double level, bool water)
{
  Scene scene = read_scene(
      std::string(SOURCE_DIR) + "/../../parameters/verification/deformable_on_incline.prm", false);
  scene.solver.gravity = Vec3(0, 0, -g);
  scene.solver.dynamic = false; // statics, as a 'Mode = static' file would read
  scene.solver.local_damping = 0.8;
  scene.solver.steps = 20000;
  scene.deformable.material.element = element;
  if (water)
    scene.solver.water.table = WaterTable::level(level);
  BuildReport built;
  BlockModel model = build_blocks(scene, built);
  resolve_group_names(scene, model);
  BlockSystem system = build_block_system(scene, model);
  RigidSolver& solver = *system.solver;
  unsigned long n = 0;
  while ((n < 20 || solver.unbalanced_ratio() >= 1e-6) && n < scene.solver.steps)
  {
    solver.step();
    ++n;
  }
  const ContactSet& cs = solver.contacts();
  double normal = 0.0;
  for (unsigned int i = 0; i < cs.n_subcontacts(); ++i)
    normal += cs.sc_fn[i];
  std::fprintf(stderr, "element %d, level %g, water %d: %lu steps, ratio %.3g, N %.9g N; %s\n",
               int(element), level, int(water), n, solver.unbalanced_ratio(), normal,
               solver.water_summary().c_str());
  return normal;
}
} // namespace

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  const double W = rho * g * V;
  const struct
  {
    ZoneElement element;
    const char* name;
  } elements[] = {{ZoneElement::tet4, "4-node zones"},
                  {ZoneElement::hex_mixed, "hexahedral zones"},
                  {ZoneElement::tet10, "10-node zones"}};
  for (const auto& e : elements)
  {
    std::printf("%s:\n", e.name);
    std::printf("  ");
    talus_test::check_within("joint force without water (N)", joint_force(e.element, 0, false), W,
                             1e-4);
    std::printf("  ");
    talus_test::check_within("joint force under 2 m of water, W - rho_w g V (N)",
                             joint_force(e.element, 3.0, true), W - rho_w * g * V, 1e-4);
    std::printf("  ");
    talus_test::check_within("joint force, level at mid-height, W - rho_w g V / 2 (N)",
                             joint_force(e.element, 1.5, true), W - rho_w * g * V / 2, 1e-4);
  }
}
