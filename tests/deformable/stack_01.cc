// Deformable blocks in contact with each other and with a rigid floor: the
// column of five 1 m cubes of parameters/verification/stack_of_blocks.prm,
// made deformable (E = 10 GPa, zones of 0.5 m), settled by the static
// solver. Each joint carries the weight above it, rho g h per unit area,
// through two sets of gridpoint springs (deformable on deformable) or one
// (deformable on the rigid floor); the floor carries the whole weight.

#include <talus/base/parallel_environment.h>
#include <talus/scene/build_blocks.h>
#include <talus/scene/block_system.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "../tests.h"

using namespace talus;

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  Scene scene = read_scene(
      std::string(SOURCE_DIR) + "/../../parameters/verification/stack_of_blocks.prm", false);
  scene.deformable.groups = {"column"};
  scene.deformable.edge_length = 0.5;
  scene.deformable.material.set_young_poisson(1e10, 0.25);
  scene.deformable.material.density = scene.density;
  BuildReport built;
  BlockModel model = build_blocks(scene, built);
  resolve_group_names(scene, model);
  BlockSystem system = build_block_system(scene, model);
  RigidSolver& solver = *system.solver;
  unsigned long steps = 0;
  while ((steps < 20 || solver.unbalanced_ratio() >= 1e-7) && steps < 100000)
  {
    solver.step();
    ++steps;
  }
  std::printf("%u deformable blocks, %u zones: static run %s\n", system.mesh_report.blocks,
              system.mesh_report.zones,
              solver.unbalanced_ratio() < 1e-7 ? "reached ratio 1e-7" : "NOT converged");
  const ContactSet& c = solver.contacts();
  // Normal force of each joint, by its height.
  std::map<long, double> joint_force;
  for (unsigned int i = 0; i < c.n_subcontacts(); ++i)
    joint_force[std::lround(c.sc_position[i].z())] += c.sc_fn[i];
  const double rho_g = scene.density * 9.81;
  for (const auto& [z, fn] : joint_force)
  {
    std::printf("joint at z = %ld: ", z);
    talus_test::check_within("normal force (N)", fn, rho_g * (6 - z), 1e-6);
  }
}
