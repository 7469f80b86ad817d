#pragma once

#include <talus/model/block_model.h>
#include <talus/scene/block_system.h>
#include <talus/scene/scene.h>
#include <talus/solver/strength_reduction.h>

#include <functional>
#include <string>
#include <vector>

namespace talus
{

/// Strength reduction on a scene (strength_reduction.h holds the search).
/// Every trial starts from the same state: the scene brought to equilibrium
/// once with its strengths multiplied by 1 / smallest_factor (100: the
/// joints hold elastically; they open where they have no tensile strength).
/// Each trial rebuilds the block system from a copy of the built model
/// with the strengths divided by its F, loads that state and runs the
/// static cycle to the target ratio or 'Steps'. Starting from equilibrium
/// matters: from the model at rest with gravity switched on, the joints'
/// forces overshoot their static values, and a cohesive sub-contact that
/// fails at the overshoot loses its cohesion (eq. 37) and the factor found
/// is too low.

/// Divides the strengths of `scene` by `factor`: for every joint material
/// ('Joint properties' and each 'Joint material N') tan(phi)/F, c/F and
/// T/F, the dilation angle capped at the reduced friction angle (a joint
/// cannot dilate more steeply than it slides); with
/// `strength_reduction.reduce_zone_strength`, the same for the Mohr-Coulomb
/// zones of 'Deformable' and of every 'Rock material N'.
void reduce_strengths(Scene& scene, double factor);

/// A trial as it runs, for its output.
struct TrialView
{
  double factor = 1.0;
  const BlockSystem& system;
  const BlockModel& model;
  unsigned long start_step = 0;                ///< the step of the initial state
  double start_time = 0.0;                     ///< s, its model time
  const std::vector<Vec3>& start_displacement; ///< m, of each block in the initial state
  const std::vector<double>& start_gridpoint_displacement; ///< m, 3 per gridpoint (zones)
  /// The largest displacement of a block or gridpoint since the initial state (m).
  double largest_displacement() const;
};

/// Calls made while a trial runs (both may be empty).
struct TrialHooks
{
  /// At the initial state and every 'History interval' steps after it.
  std::function<void(const TrialView&)> record;
  /// When the trial has been judged (its last state).
  std::function<void(const TrialView&, const StrengthReductionTrial&)> finished;
};

/// The trials of one scene: the initial state, made once, and trials from it.
class StrengthReductionTrials
{
public:
  /// Brings a copy of `model` (built, the scene's group names resolved) to
  /// the initial state.
  StrengthReductionTrials(const Scene& scene, const BlockModel& model);
  /// Trials from a state the run has reached (a stage's): `state` is the
  /// solvers' save_state, `model` the blocks as built. Each trial builds
  /// its system from a copy of `model` with the reduced strengths, loads
  /// the state, calls `prepare` on it (what the state does not hold: the
  /// stages' boundaries, rock materials and water, from the reduced scene
  /// it is given) and runs statically. initial() is stable.
  StrengthReductionTrials(const Scene& scene, const BlockModel& model, std::string state,
                          std::function<void(const Scene& reduced, BlockSystem& system)> prepare,
                          unsigned long start_step, double start_time,
                          std::vector<Vec3> start_displacement,
                          std::vector<double> start_gridpoint_displacement);

  /// How the initial equilibrium ended (as a trial at F = smallest_factor;
  /// unstable: no trial can be judged).
  const StrengthReductionTrial& initial() const { return initial_; }

  /// Runs one trial at `factor` from the initial state and judges it
  /// (judge_trial, displacements since the initial state). A run that
  /// diverges is unstable, with the message as its note.
  StrengthReductionTrial run(double factor, const TrialHooks& hooks = {}) const;

  /// Shows `show` the system of a trial at `factor` in `state` (its
  /// solvers' save_state at the trial's end, the RigidSolver's then the
  /// zones', made on another rank):
  /// the same view its `finished` hook had.
  void show(double factor, const std::string& state,
            const std::function<void(const TrialView&)>& show) const;

private:
  /// Builds the system of a trial at `factor` (reduced strengths, static),
  /// loads `state` (named `what` in a message if it is short), applies
  /// `prepare` and hands the trial to `use`: run() and show() alike.
  void in_trial(double factor, const std::string& state, const std::string& what,
                const std::function<void(const Scene& reduced, const TrialView& view)>& use) const;

  const Scene& scene_;
  const BlockModel& model_;
  StrengthReductionTrial initial_;
  std::string state_; ///< the initial state (RigidSolver and zones' save_state)
  std::function<void(const Scene&, BlockSystem&)> prepare_;
  unsigned long start_step_ = 0;
  double start_time_ = 0.0;
  std::vector<Vec3> start_displacement_;
  std::vector<double> start_gridpoint_displacement_;
};

/// The whole search on the scene (find_factor_of_safety with
/// StrengthReductionTrials); `trial_done` is called after each trial.
/// When the initial state is not an equilibrium, returns found = false
/// with the reason and no trial.
StrengthReductionResult
factor_of_safety(const Scene& scene, const BlockModel& model, const TrialHooks& hooks = {},
                 const std::function<void(const StrengthReductionTrial&)>& trial_done = {});

/// The same with another search on the trials (the search on ranks): the
/// initial state is made and checked, then `search` runs.
StrengthReductionResult factor_of_safety(
    const Scene& scene, const BlockModel& model,
    const std::function<StrengthReductionResult(const StrengthReductionTrials&)>& search);

} // namespace talus
