// The contact path of deformable blocks for initial_velocity_shear_01
// (issue 23): the rigid 1 m cube (2650 kg, rotation held, no gravity,
// 'Initial velocity' v0 = 1e-3 m/s along x, 'Mode = dynamic') slides on a
// deformable floor (1 m cube of tet4 zones of 0.5 m, its base fixed) across
// a frictionless joint (no cohesion, no tension, phi = 0). Nothing pushes
// the floor, so it stays at rest and the cube slides at v0; the
// sub-contacts, which sit at the floor's gridpoints, must take the cube's
// displacement x as their shear displacement, within 1e-6 of v0 dt, over
// 200 steps. (A deformable block takes no initial velocity:
// bad_input/initial_velocity_deformable_01.) Before: the first step took
// v0 dt of shear although nothing had moved, 1.0 of v0 dt off.

#include <talus/base/parallel_environment.h>
#include <talus/scene/block_system.h>
#include <talus/scene/build_blocks.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "../tests.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  const double v0 = 1e-3;
  const std::string file = "initial_velocity_shear_02.prm";
  {
    std::FILE* f = std::fopen(file.c_str(), "w");
    std::fputs("subsection Model\n  set Brick min = 0, 0, 0\n  set Brick max = 1, 1, 2\nend\n"
               "subsection Material\n  set Density = 2650\nend\n"
               "subsection Joint 1\n  set Dip = 0\n  set Origin = 0, 0, 1\nend\n"
               "subsection Group 1\n  set Name = floor\n  set Corner min = 0, 0, 0\n"
               "  set Corner max = 1, 1, 1\nend\n"
               "subsection Group 2\n  set Name = cube\n  set Corner min = 0, 0, 1\n"
               "  set Corner max = 1, 1, 2\nend\n"
               "subsection Deformable\n  set Groups = floor\n  set Edge length = 0.5\n"
               "  set Young's modulus = 1e10\n  set Poisson's ratio = 0.25\nend\n"
               "subsection Boundary 1\n  set Corner min = -0.01, -0.01, -0.01\n"
               "  set Corner max = 1.01, 1.01, 0.01\nend\n"
               "subsection Load 1\n  set Group = cube\n  set Hold rotation = true\n"
               "  set Initial velocity = 1e-3, 0, 0\nend\n"
               "subsection Joint properties\n  set Normal stiffness = 1e10\n"
               "  set Shear stiffness = 4e9\n  set Cohesion = 0\n  set Tensile strength = 0\n"
               "  set Friction angle = 0\nend\n"
               "subsection Solver\n  set Mode = dynamic\n  set Gravity = 0, 0, 0\nend\n",
               f);
    std::fclose(f);
  }
  talus::Scene scene = talus::read_scene(file, false);
  talus::BuildReport built;
  talus::BlockModel model = talus::build_blocks(scene, built);
  talus::resolve_group_names(scene, model);
  talus::BlockSystem system = talus::build_block_system(scene, model);
  talus::RigidSolver& solver = *system.solver;
  unsigned int cube = 0;
  for (unsigned int b = 0; b < model.n_blocks(); ++b)
    if (model.centroid[b].z() > 1.0)
      cube = b;
  const talus::ContactSet& cs = solver.contacts();
  double worst = 0.0, floor_moved = 0.0;
  while (solver.steps_done() < 200)
  {
    const double x = solver.displacement[cube].x();
    solver.step();
    double us = 0.0;
    for (unsigned int i = 0; i < cs.n_subcontacts(); ++i)
      us += (cs.block_b[cs.sc_contact[i]] == cube ? 1.0 : -1.0) * cs.sc_us[3 * i];
    us /= std::max(cs.n_subcontacts(), 1u);
    worst = std::max(worst, std::abs(us - x) / (v0 * solver.dt()));
    for (double u : system.zones->displacements())
      floor_moved = std::max(floor_moved, std::abs(u));
  }
  std::fprintf(stderr,
               "%lu steps of %.4g s, %u zones, %u sub-contacts; shear displacement off the cube's "
               "by at most %.2e of v0 dt; the floor moved at most %.2e m; cube velocity %.9g m/s\n",
               solver.steps_done(), solver.dt(), system.mesh.n_zones(), cs.n_subcontacts(), worst,
               floor_moved, solver.velocity[cube].x());
  std::printf("rigid cube on a deformable floor, frictionless: shear displacement that of the "
              "cube within 1e-6 of v0 dt: %s; floor at rest (within 1e-6 of the cube's "
              "displacement) and cube at v0: %s\n",
              talus_test::verdict(cs.n_subcontacts() > 0 && worst <= 1e-6),
              talus_test::verdict(floor_moved <= 1e-6 * solver.displacement[cube].x() &&
                                  std::abs(solver.velocity[cube].x() / v0 - 1.0) <= 1e-12));
}
