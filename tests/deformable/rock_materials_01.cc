// Rock materials per group: the column of five 1 m cubes of
// parameters/verification/stack_of_blocks.prm on its fixed floor, the two
// upper cubes made of a 'Rock material' of their own (1,500 kg/m^3, E = 1
// GPa), the three below of the scene's (2,650 kg/m^3, E = 10 GPa), settled
// by the static solver:
// 1. rigid blocks: each joint carries the weight above it, g sum(rho V);
// 2. deformable blocks (0.5 m zones): the same joint forces;
// 3. deformable blocks without gravity under 0.1 MPa on the top face: each
//    cube shortens by p / E over its height and each joint closes by p /
//    kn, so the top sinks by 5 p / kn + 3 p / E + 2 p / E_light (a uniform
//    stress, which 4-node zones represent exactly), to the order of the
//    largest strain, p / E_light = 1e-4, as the zones follow the deformed
//    geometry (3.7e-5 here, 3.7e-4 at 1 MPa). Poisson's ratio is 0:
//    otherwise the soft cubes would bulge more than the stiff ones and the
//    joints' shear springs would hold them in.

#include <talus/base/parallel_environment.h>
#include <talus/scene/build_blocks.h>
#include <talus/scene/block_system.h>
#include <talus/solver/deformable_solver.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "../tests.h"

using namespace talus;

void run(bool deformable, bool pressed)
{
  Scene scene = read_scene(
      std::string(SOURCE_DIR) + "/../../parameters/verification/stack_of_blocks.prm", false);
  scene.groups.push_back({"light", Box{Vec3(0, 0, 4), Vec3(1, 1, 6)}});
  std::swap(scene.groups.front(), scene.groups.back()); // first match wins: 'light' before 'floor'
  RockMaterialSpec light;
  light.name = "light_rock";
  light.groups = {"light"};
  light.density = 1500.0;
  scene.deformable.material.set_young_poisson(1e10, 0.0);
  scene.deformable.material.density = scene.density;
  light.zone = scene.deformable.material;
  light.zone.set_young_poisson(1e9, 0.0);
  light.zone.density = light.density;
  scene.rock_materials.push_back(light);
  if (deformable)
  {
    scene.deformable.groups = {"column", "light"};
    scene.deformable.edge_length = 0.5;
  }
  const double p = 1e5; // Pa
  if (pressed)
  {
    scene.solver.gravity = Vec3::Zero();
    scene.face_pressures.push_back({Box{Vec3(-1, -1, 6 - 1e-6), Vec3(2, 2, 6 + 1e-6)}, p});
  }
  BuildReport built;
  BlockModel model = build_blocks(scene, built);
  resolve_group_names(scene, model);
  BlockSystem system = build_block_system(scene, model);
  RigidSolver& solver = *system.solver;
  const double target = pressed ? 1e-9 : 1e-7; // the pressure alone: no weight to measure by
  unsigned long steps = 0;
  while ((steps < 20 || solver.unbalanced_ratio() >= target) && steps < 200000)
  {
    solver.step();
    ++steps;
  }
  const char* what = pressed      ? "deformable blocks under a pressure"
                     : deformable ? "deformable blocks"
                                  : "rigid blocks";
  std::fprintf(stderr, "%s: %lu steps\n", what, steps);
  std::printf("%s: static run %s\n", what,
              solver.unbalanced_ratio() < target ? "reached its ratio" : "NOT converged");
  const double g = 9.81, kn = scene.solver.joint.normal_stiffness;
  const auto rho = [](double z) { return z > 4.0 ? 1500.0 : 2650.0; }; // of the cube above z
  const auto weight_above = [&](double z)
  {
    double w = 0.0;
    for (double top = z + 0.5; top < 6.0; top += 1.0)
      w += rho(top) * g;
    return w;
  };
  if (!pressed)
  {
    std::map<long, double> joint_force;
    const ContactSet& c = solver.contacts();
    for (unsigned int i = 0; i < c.n_subcontacts(); ++i)
      joint_force[std::lround(c.sc_position[i].z())] += c.sc_fn[i];
    for (const auto& [z, fn] : joint_force)
    {
      std::printf("  joint at z = %ld: ", z);
      talus_test::check_within("normal force (N)", fn, weight_above(z), 1e-6);
    }
    return;
  }

  // The top face's mean settlement against the closed form.
  const double sink = 5.0 * p / kn + 3.0 * p / 1e10 + 2.0 * p / 1e9;
  const std::vector<double> u = system.zones->displacements();
  double top = 0.0;
  unsigned int n = 0;
  for (unsigned int gp = 0; gp < system.mesh.n_gridpoints(); ++gp)
    if (std::abs(system.mesh.position[3 * gp + 2] - 6.0) < 1e-9)
    {
      top += u[3 * gp + 2];
      ++n;
    }
  std::printf("  ");
  talus_test::check_within("settlement of the top (m)", -top / n, sink, 1e-4);
}

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  run(false, false);
  run(true, false);
  run(true, true);
}
