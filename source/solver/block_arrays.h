#pragma once

// Internal to source/solver: the per-block arrays of RigidSolver that a
// block carries between ranks (block_migration.cc) and into the whole
// model's state (whole_state.cc).

#include <talus/solver/block_migration.h>
#include <talus/solver/rigid_solver.h>

namespace talus
{

template <typename Visit>
void BlockMigration::visit_block_arrays(RigidSolver& s, Visit&& visit)
{
  visit(s.mass);
  visit(s.inertial_mass);
  visit(s.inertia);
  visit(s.velocity);
  visit(s.spin);
  visit(s.force);
  visit(s.moment);
  visit(s.displacement);
  visit(s.rotation);
  visit(s.fixed);
  visit(s.applied_force);
  visit(s.applied_force_rate);
  visit(s.prescribed);
  visit(s.moved);
  visit(s.path);
  visit(s.last_force_);
  visit(s.last_moment_);
  visit(s.motion_dx_);
  visit(s.motion_dtheta_);
  visit(s.damping_force_);
  visit(s.damping_moment_);
  visit(s.is_deformable_);
  visit(s.removed_);
  visit(s.true_inertia_);
  visit(s.envelopes_);
  if (s.s_.principal_inertia)
  {
    visit(s.principal_moments);
    visit(s.axes);
    visit(s.true_principal_);
  }
  if (!s.timed_force_.empty())
  {
    visit(s.timed_force_);
    visit(s.timed_velocity_);
    visit(s.timed_held_);
  }
}

} // namespace talus
