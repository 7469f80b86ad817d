#pragma once

// Runs a scene of parameters/stability/ and checks what must hold on an
// extreme scene: no NaN or infinity anywhere (block and gridpoint state,
// contact forces, zone stresses), kinetic energy never more than the
// sources supplied (energy at the start plus the work of gravity and
// boundaries), and an energy balance that closes within a stated tolerance
// (see talus::EnergyAccount). Prints what it checked, and what it
// measured to standard error (see tests.h).

#include <talus/base/parallel_environment.h>
#include <talus/scene/build_blocks.h>
#include <talus/scene/block_system.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "../tests.h"

struct StabilityRun
{
  talus::Scene scene;
  talus::BlockModel model;
  /// On the heap, built in place: the zone solver refers to the mesh.
  std::unique_ptr<talus::BlockSystem> system_;
  unsigned long steps = 0;
  double largest_kinetic = 0.0; ///< J, balance kinetic term
  double largest_error = 0.0;   ///< J
  double largest_scale = 0.0;   ///< J, largest energy term seen
  double largest_excess = 0.0;  ///< J, kinetic energy less the sources, largest
  double largest_gain = 0.0;    ///< J, energy created (minus the error), largest
  bool finite = true;
  std::string first_non_finite;

  /// Reads parameters/stability/<name>, applies `edit`, builds the system.
  template <typename Edit>
  StabilityRun(const std::string& name, Edit edit)
  {
    scene =
        talus::read_scene(std::string(SOURCE_DIR) + "/../../parameters/stability/" + name, false);
    edit(scene);
    talus::BuildReport built;
    model = talus::build_blocks(scene, built);
    talus::resolve_group_names(scene, model);
    system_.reset(new talus::BlockSystem(talus::build_block_system(scene, model)));
  }
  explicit StabilityRun(const std::string& name) : StabilityRun(name, [](talus::Scene&) {}) {}

  talus::RigidSolver& solver() { return *system_->solver; }

  /// The first block of a group.
  unsigned int block_of(const std::string& group) const
  {
    for (unsigned int b = 0; b < model.n_blocks(); ++b)
      if (model.group_names[model.group[b]] == group)
        return b;
    std::printf("no block in group %s\n", group.c_str());
    std::exit(1);
  }

  /// Every number of the state is finite: vertices, velocities, spins,
  /// contact forces, gridpoint positions and velocities, zone stresses.
  bool state_finite()
  {
    const talus::RigidSolver& s = *system_->solver;
    for (const talus::Vec3& v : model.vertex)
      if (!v.allFinite())
        return note("a vertex");
    for (unsigned int b = 0; b < model.n_blocks(); ++b)
      if (!s.velocity[b].allFinite() || !s.spin[b].allFinite())
        return note("block " + std::to_string(b));
    const talus::ContactSet& c = s.contacts();
    for (unsigned int i = 0; i < c.n_subcontacts(); ++i)
      if (!std::isfinite(c.sc_fn[i]) || !std::isfinite(c.sc_fs[3 * i]) ||
          !std::isfinite(c.sc_fs[3 * i + 1]) || !std::isfinite(c.sc_fs[3 * i + 2]))
        return note("sub-contact " + std::to_string(i));
    if (system_->zones)
    {
      for (double x : system_->zones->positions())
        if (!std::isfinite(x))
          return note("a gridpoint position");
      for (double x : system_->zones->velocities())
        if (!std::isfinite(x))
          return note("a gridpoint velocity");
      for (double x : system_->zones->stress())
        if (!std::isfinite(x))
          return note("a zone stress");
    }
    return true;
  }

  /// Checks the state and the energy account now.
  void check()
  {
    if (finite && !state_finite())
      finite = false;
    const talus::EnergyAccount e = system_->solver->energy_account();
    if (!std::isfinite(e.error()))
    {
      finite = finite && note("the energy account");
      return;
    }
    largest_kinetic = std::max(largest_kinetic, e.kinetic);
    largest_error = std::max(largest_error, std::abs(e.error()));
    largest_scale = std::max(largest_scale, e.scale());
    // Kinetic energy beyond what the sources gave (J).
    const double sources = e.initial_stored + e.gravity_work + e.boundary_work;
    largest_excess = std::max(largest_excess, e.kinetic - sources);
    largest_gain = std::max(largest_gain, -e.error());
  }

  /// Steps `n` times (statics: fewer when the target ratio is reached),
  /// checking every `every` steps and at the end.
  void run(unsigned long n, unsigned int every = 10)
  {
    talus::RigidSolver& s = *system_->solver;
    check();
    for (unsigned long k = 0; k < n; ++k)
    {
      s.step();
      ++steps;
      if (steps % every == 0)
        check();
      if (!scene.solver.dynamic && scene.solver.target_ratio > 0.0 && steps > 20 &&
          s.unbalanced_ratio() < scene.solver.target_ratio)
        break;
    }
    check();
  }
  void run() { run(scene.solver.steps); }

  /// Prints whether each thing holds: the balance error relative to the
  /// largest energy term within `tolerance` (or, with `loss_only`, no
  /// energy created beyond it: scenes where the sub-contact rebuilds lose
  /// energy), and the kinetic energy never beyond what the sources gave by
  /// more than `tolerance` of that term. A negative `tolerance` reports the
  /// balance without asserting it. The figures go to standard error: on
  /// scenes of many impacts they follow the CPU's rounding (another
  /// contact count, another largest kinetic energy with AVX2 than with
  /// AVX-512), the checks do not.
  void report(double tolerance, bool loss_only = false)
  {
    std::printf("%u blocks, %u zones\n", model.n_blocks(), system_->mesh.n_zones());
    std::fprintf(stderr, "steps: %lu, time step %.3g s, %u contacts\n", steps,
                 system_->solver->dt(), system_->solver->contacts().n_contacts());
    std::printf("no NaN or Inf anywhere: %s\n",
                finite ? "yes" : ("NO: " + first_non_finite).c_str());
    std::fprintf(stderr, "largest kinetic energy: %.3g J\n", largest_kinetic);
    const double scale = largest_scale > 0.0 ? largest_scale : 1.0;
    const double relative = largest_error / scale, gain = std::max(largest_gain, 0.0) / scale;
    std::fprintf(stderr,
                 "energy balance: largest |error| %.2g J, %.1e of the largest energy term %.3g J; "
                 "energy created at most %.1e of it\n",
                 largest_error, relative, largest_scale, gain);
    if (tolerance < 0.0)
      std::printf("energy balance: reported, not asserted\n");
    else if (loss_only)
      std::printf("energy balance: energy created within %.0e of the largest energy term: %s\n",
                  tolerance, gain <= tolerance ? "OK" : "WRONG");
    else
      std::printf("energy balance: largest |error| within %.0e of the largest energy term: %s\n",
                  tolerance, relative <= tolerance ? "OK" : "WRONG");
    tolerance = std::abs(tolerance);
    const double excess = std::max(largest_excess, 0.0) / scale;
    std::fprintf(stderr,
                 "kinetic energy beyond the energy supplied: at most %.1e of the largest "
                 "energy term\n",
                 excess);
    std::printf("kinetic energy beyond the energy supplied: within %.0e of the largest energy "
                "term: %s\n",
                tolerance, excess <= tolerance ? "OK" : "WRONG");
  }

private:
  bool note(const std::string& what)
  {
    if (first_non_finite.empty())
      first_non_finite = what + " after step " + std::to_string(steps);
    return false;
  }
};
