#pragma once

#include <talus/io/scene.h>
#include <talus/model/block_model.h>
#include <talus/solver/block_system.h>
#include <talus/solver/strength_reduction.h>

#include <functional>

namespace talus
{

/// Strength reduction on a scene (strength_reduction.h holds the search):
/// every trial rebuilds the block system from a copy of the built model,
/// so that each starts from the same state, with the strengths divided by
/// its factor, and runs the static cycle to the target ratio or 'Steps'.

/// Divides the strengths of `scene` by `factor`: for every joint material
/// ('Joint properties' and each 'Joint material N') tan(phi)/F, c/F and
/// T/F, the dilation angle capped at the reduced friction angle (a joint
/// cannot dilate more steeply than it slides); with
/// `strength_reduction.reduce_zone_strength`, the same for the Mohr-Coulomb
/// zones of 'Deformable' and of every 'Rock material N'.
void reduce_strengths(Scene& scene, double factor);

/// Calls made while a trial runs, for its output (all may be empty).
struct TrialHooks
{
  /// After the first step's state and every 'History interval' steps.
  std::function<void(const BlockSystem&)> record;
  /// When the trial has been judged (its last state).
  std::function<void(const BlockSystem&, const BlockModel&, const StrengthReductionTrial&)>
      finished;
};

/// Runs one trial at `factor` on a copy of `model` (built, with the scene's
/// group names resolved) and judges it (judge_trial). A run that diverges
/// is unstable, with the message as its note.
StrengthReductionTrial run_strength_reduction_trial(const Scene& scene, const BlockModel& model,
                                                    double factor, const TrialHooks& hooks = {});

/// The whole search on the scene (find_factor_of_safety with
/// run_strength_reduction_trial); `trial_done` is called after each trial.
StrengthReductionResult
factor_of_safety(const Scene& scene, const BlockModel& model, const TrialHooks& hooks = {},
                 const std::function<void(const StrengthReductionTrial&)>& trial_done = {});

} // namespace talus
