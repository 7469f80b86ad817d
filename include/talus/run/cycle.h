#pragma once

#include <talus/scene/scene.h>

#include <string>
#include <vector>

namespace talus
{

class Checkpoint;
class DeformableSolver;
class RigidSolver;

/// How a stage ended: its unbalanced-force ratio, and where the force that
/// sets it acts (for the warning of a stage that did not settle).
struct RunEnd
{
  double ratio = 0.0;
  std::string where;
};

/// What the run loop of a Simulation drives, one step at a time: the block
/// cycle (rigid blocks, with the zones of deformable ones) or a deformable
/// body alone. Each kind owns its solvers, its history columns and its
/// ParaView series; the Simulation owns the loop, the stages, the history
/// file, the checkpoints and the progress line. One virtual call per step,
/// none per block or zone.
class Cycle
{
public:
  virtual ~Cycle() = default;

  virtual void step() = 0;
  virtual unsigned long steps_done() const = 0;
  virtual double time() const = 0; ///< s
  virtual double dt() const = 0;   ///< s
  virtual double ratio() const = 0;
  /// Whether a static stage that has taken `stage_steps` steps may stop at
  /// its target ratio now.
  virtual bool may_stop(unsigned long stage_steps) const = 0;

  /// The history's columns, and a row of them at the present step.
  virtual std::vector<std::string> history_columns() const = 0;
  virtual std::vector<double> history_row() = 0;
  /// One frame of each ParaView series at the present step; after a
  /// divergence (`diverged`), motion only.
  virtual void write_frame(bool diverged) = 0;
  /// Registers the series and frame counters with the checkpoints.
  virtual void register_checkpoint(Checkpoint& checkpoint) = 0;
  virtual RigidSolver* rigid() { return nullptr; }
  virtual DeformableSolver* zones() = 0;

  /// A stage's changes at its start (excavations, fixed groups, joint
  /// materials, mode, displacements); prints what it did.
  virtual void begin_stage(const StageSpec& stage) = 0;
  /// A stage of 'Mode = factor of safety' (stages[k], its changes made):
  /// the strength reduction search from the present state, on copies; the
  /// model goes on unchanged. Prints the trials and F, writes the
  /// mechanism; returns 0, or throws InputError when no F is found.
  virtual int factor_of_safety(const std::vector<StageSpec>& stages, unsigned int k) = 0;
  /// After a restart inside `stage` or after it: what a checkpoint does not
  /// hold of the stages' changes (the boundaries and loads in force).
  virtual void restore_stage(const StageSpec& stage) = 0;
  /// The largest displacement now (m) and where, for the stage's line.
  virtual std::string displacement_text() const = 0;
  /// The summary's lines at the end of the run.
  virtual void print_end() = 0;
  /// Where the largest unbalanced force acts.
  virtual std::string unbalanced_where() const = 0;
};

} // namespace talus
