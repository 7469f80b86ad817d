#pragma once

// The settling scene of the rigid benchmarks: n x n x n unit cubes stacked
// in columns on a fixed floor layer (z in [0, 1]), with the solver settings
// of a static settling run (local damping, no stop on the ratio).

#include <talus/geometry/block_generator.h>
#include <talus/model/block_model.h>
#include <talus/solver/rigid_solver.h>

inline talus::BlockModel settling_cubes(unsigned int n, unsigned long steps,
                                        talus::SolverSettings& s)
{
  using namespace talus;
  BlockGenerator g(ConvexPolyhedron::box(Vec3::Zero(), Vec3(n, n, n + 1)), {});
  g.cut_joint_set({0.0, 0.0, 1.0, Vec3::Zero(), 0, false, {}});
  g.cut_joint_set({90.0, 0.0, 1.0, Vec3::Zero(), 0, false, {}});
  g.cut_joint_set({90.0, 90.0, 1.0, Vec3::Zero(), 0, false, {}});
  BlockModel model;
  const unsigned int cubes = model.group_index("cubes"), floor = model.group_index("floor");
  for (const ConvexPolyhedron& b : g.blocks())
    model.add_block(b, b.vertex_mean()[2] < 1.0 ? floor : cubes);
  s = SolverSettings();
  s.dynamic = false;
  s.steps = steps;
  s.target_ratio = 0.0;
  s.contact.tolerance = 0.01;
  s.joint.normal_stiffness = s.joint.shear_stiffness = 1e9;
  s.fixed_groups = {floor};
  return model;
}
