// A stage's factor of safety ('Mode = factor of safety' in 'Stage N'): the
// strength reduction search from the state the stage starts in, on one
// rank or on the ranks of a split run.

#include <talus/io/checkpoint.h>
#include <talus/io/factor_of_safety_run.h>
#include <talus/io/scene_checks.h>
#include <talus/run/block_cycle.h>
#include <talus/scene/factor_of_safety.h>
#include <talus/solver/block_migration.h>
#include <talus/solver/strength_reduction.h>
#include <talus/solver/zone_migration.h>

#include "stage_changes.h"

#include <cstdio>
#include <string>
#include <vector>

namespace talus
{

int BlockCycle::factor_of_safety(const std::vector<StageSpec>& stages, unsigned int k)
{
  const StageSpec& stage = stages[k];
  const RigidSolver& solver = *system_.solver;
  // The state the stage starts in, and what it does not hold, set again on
  // each trial's system: every stage's changes up to this one, in order.
  // On ranks each trial is a serial run of the whole model (as 'Solver /
  // Mode = factor of safety' runs them): the state is gathered first, on
  // every rank, into a solver of the whole model.
  std::string state;
  std::vector<Vec3> start_displacement;
  std::vector<double> start_zone_displacement;
  if (share_)
  {
    // (With zones, the whole model's are meshed again here, as one run
    // meshes them: their gridpoints are numbered as the whole mesh's.)
    BlockModel whole_model = *built_model_;
    BlockSystem whole = build_block_system(scene_, whole_model);
    BlockMigration::gather_whole(solver, share_->blocks(), *whole.solver, share_->comm());
    CheckpointWriter out;
    whole.solver->save_state(out);
    if (system_.zones)
    {
      gather_whole_zones(*system_.zones, rank_zones_.zone, *whole.zones, share_->comm());
      whole.zones->save_state(out);
      start_zone_displacement = whole.zones->displacements();
    }
    state = out.bytes();
    start_displacement = whole.solver->displacement;
  }
  else
  {
    CheckpointWriter out;
    solver.save_state(out);
    if (system_.zones)
      system_.zones->save_state(out);
    state = out.bytes();
    start_displacement = solver.displacement;
    if (system_.zones)
      start_zone_displacement = system_.zones->displacements();
  }
  Scene scene = scene_;
  scene.solver.steps = stage.steps;
  scene.solver.target_ratio = stage.target_ratio;
  scene.stages.clear(); // the trials' scene: this stage's settings
  const std::vector<StageSpec> begun(stages.begin(), stages.begin() + k + 1);
  const BlockModel& built = *built_model_;
  const StrengthReductionTrials trials(
      scene, built, std::move(state),
      [&](const Scene& reduced, BlockSystem& system)
      {
        for (const StageSpec& s : begun)
          restore_changes(reduced, built, &built, system, s);
      },
      solver.steps_done(), solver.time(), std::move(start_displacement),
      std::move(start_zone_displacement));
  const std::string prefix = prefix_ + "_stage" + std::to_string(k + 1) + "_mechanism";
  double mechanism = 0.0;
  TrialHooks hooks;
  hooks.finished = [&](const TrialView& view, const StrengthReductionTrial& t)
  {
    if (t.stable)
      return;
    mechanism = t.factor;
    if (scene_.output.write_vtu)
      write_mechanism(scene, view, prefix);
  };
  std::printf("  Strength reduction from the stage's state: up to %lu steps a trial, stable "
              "below ratio %g\n",
              stage.steps, stage.target_ratio);
  const auto print_trial = [](const StrengthReductionTrial& t)
  { std::printf("  %s\n", trial_line(t).c_str()); };
  StrengthReductionResult r;
  if (!share_)
    r = find_factor_of_safety(
        [&](double factor)
        {
          const StrengthReductionTrial t = trials.run(factor, hooks);
          print_trial(t);
          return t;
        },
        scene_.strength_reduction);
  else
  {
    // Rank 0 runs each round's first trial, which the search takes, and
    // writes its mechanism itself; another rank's unstable trial, when
    // taken, sends its end state, from which rank 0 writes the same files.
    const bool first = share_->rank() == 0;
    std::vector<unsigned int> rounds;
    int unstable_by = -1;
    std::string payload;
    TrialHooks other;
    other.finished = [&](const TrialView& view, const StrengthReductionTrial& t)
    {
      if (t.stable || !scene_.output.write_vtu)
        return;
      CheckpointWriter out;
      view.system.solver->save_state(out);
      if (view.system.zones) // (as StrengthReductionTrials::show loads it)
        view.system.zones->save_state(out);
      payload = out.bytes();
    };
    r = find_factor_of_safety_on_ranks(
        [&](double factor)
        {
          payload.clear();
          const StrengthReductionTrial t = trials.run(factor, first ? hooks : other);
          return RankTrial{t, payload};
        },
        scene_.strength_reduction, share_->comm(),
        [&](const StrengthReductionTrial& t, int by, const std::string& bytes)
        {
          print_trial(t);
          if (!t.stable)
            unstable_by = by;
          if (t.stable || by == 0)
            return;
          mechanism = t.factor;
          if (first && scene_.output.write_vtu)
            trials.show(t.factor, bytes,
                        [&](const TrialView& view) { write_mechanism(scene, view, prefix); });
        },
        &rounds);
    if (first) // the search's figures, beside the summary
      std::fprintf(stderr,
                   "talus: stage %u's factor of safety on %d ranks: %zu trials in %zu rounds; "
                   "the last unstable trial (the mechanism) ran on rank %d\n",
                   k + 1, share_->ranks(), r.trials.size(), rounds.size(), unstable_by);
  }
  if (!r.found)
    throw scene_error(scene_, stage.section, "Mode", "factor of safety: " + r.failure,
                      "a model that is stable at some F and fails at a larger one");
  std::printf("  Factor of safety: %.4g (between %.6g and %.6g, %zu trials)\n", r.factor(),
              r.stable_factor, r.unstable_factor, r.trials.size());
  if (scene_.output.write_vtu)
    std::printf("  Mechanism:  the last unstable trial (F = %.6g): %s_blocks.pvd\n", mechanism,
                prefix.c_str());
  return 0;
}

} // namespace talus
