#pragma once

#include <talus/base/fnv1a.h>

// Checkpoints: the whole state of a run in one binary file, so that a run
// stopped by a signal (or by the machine) can be continued with
// `talus --restart FILE` and give the same histories, bit for bit, as a run
// that was never stopped.
//
// File layout (little-endian, as written by the machine that ran):
//   8 bytes  magic "TALUSCKP"
//   u32      format version (checkpoint_format_version)
//   u64      payload size in bytes
//   u64      FNV-1a hash of the payload (truncation and corruption)
//   payload  tagged sections, see Checkpoint::write
// Classes whose private state is saved have save_state/load_state hooks,
// defined in source/io/checkpoint.cc (DeformableSolver's in its own file,
// which alone knows its PETSc vectors).

#include <talus/base/archive.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace talus
{

class BlockModel;
class DeformableSolver;
class HistoryFile;
class PvdSeries;
class RankShare;
class RigidSolver;
struct Scene;

/// 4: contacts keep their joint material; 5: stages (the loop's place,
/// removed blocks and zones, fixed blocks, mode, joint material rules);
/// 6: continuously yielding joints' state; 7: a fingerprint per stage and
/// the stages begun (a stage may be appended to a finished run); 8: the
/// work of nodal mixed discretization in the zones' energy account; 9: the
/// rank and the number of ranks after the first tag, and on several ranks
/// each rank's share (io/rank_checkpoint.h) after the step; 10: the
/// blocks' last motion (a deformable block's is not its velocity times the
/// step to the last bit); 11: on ranks, the regions as a rebalance last
/// cut them and the rebalance's counters; 12: whether the rebalance checks
/// at the next step (after a stage's excavation); 13: the deformable blocks
/// whose surfaces a rank holds, and the migration's count of the zones'
/// new splits (deformable blocks change rank); 14: the blocks' geometry
/// fingerprint taken one block at a time (ModelDigest), so that a rank
/// that builds only its region takes it too; 15: after the rank's share,
/// the zones' split when the run may change it (a body alone split again
/// after an excavation: the zones removed when it was last split).
constexpr std::uint32_t checkpoint_format_version = 15;

/// Thrown after a checkpoint was written because a signal asked the run to
/// stop; main() turns it into a message and exit code 128 + signal (130 for
/// SIGINT, 143 for SIGTERM), the shells' convention.
struct RunInterrupted : std::runtime_error
{
  /// `restart_with`: the command that continues the run (default: talus
  /// --restart `checkpoint`).
  RunInterrupted(int signal, unsigned long step, const std::string& checkpoint,
                 const std::string& restart_with = "");
  int signal;
  unsigned long step;
  std::string checkpoint;
  int exit_code() const { return 128 + signal; }
};

/// SIGINT and SIGTERM only set a flag; the cycle looks at it once a step.
/// A second signal ends the process at once (exit code 128 + signal).
void install_stop_signal_handlers();
/// SIGINT and SIGTERM end the process again (after the cycle).
void restore_default_signal_handlers();
/// The signal received since install_stop_signal_handlers() (0: none).
int stop_signal_received();

/// The payload of a checkpoint file, its header checked, read past its
/// first tag and the rank and number of ranks that wrote it (returned in
/// `rank` and `ranks` when given); throws InputError for a file that is not
/// a talus checkpoint of this format, or is truncated or corrupt.
CheckpointReader read_checkpoint(const std::string& file, unsigned int* rank = nullptr,
                                 unsigned int* ranks = nullptr);

/// The parameter file a checkpoint was written for (absolute path), read
/// from its header; throws InputError for a file that is not a talus
/// checkpoint of this format, or is truncated or corrupt.
std::string checkpoint_parameter_file(const std::string& checkpoint);

/// Fingerprints of the scene's parameters, leaving out the entries that do
/// not change the state at a step: the step limits (a run may be extended)
/// and the checkpoint interval. `base` is of everything but the 'Stage N';
/// `stages` has one per stage, in the order they run, so that the stages
/// a run has not begun may change, and stages may be appended.
struct SceneFingerprint
{
  std::uint64_t base = 0;
  std::vector<std::uint64_t> stages;
};
SceneFingerprint scene_fingerprint(const Scene& scene);

/// Refuses (InputError) to continue from `checkpoint` with a scene whose
/// parameters differ from the ones it was written with, outside the stages
/// the run had not begun. Called before anything is written, so that a
/// refused restart changes no file.
void check_checkpoint_scene(const std::string& checkpoint, const Scene& scene);

/// For talus --restart: check_checkpoint_scene (with 'Steps' not below the
/// checkpoint's step), and the output folder: 'Directory' if it holds the
/// run's history, else the checkpoint's folder if that does (a restart from
/// another working folder). Nothing is written.
void continue_in_checkpoint_folder(const std::string& checkpoint, Scene& scene);

/// The checkpoints of one run: what to save (the solvers, the model, the
/// histories, the VTU series and the counters of the output loop), when
/// (every `interval` steps, and on SIGINT/SIGTERM), and restoring it all.
/// Register everything, then call restore() (restarts) before the first
/// step and after_step() after every step.
class Checkpoint
{
public:
  /// `blocks_fingerprint`: that of the blocks as built
  /// (ModelDigest::geometry_fingerprint); it and the zones' gridpoints as
  /// built are kept so that a restart rebuilds the same model. With
  /// `restart_from`, checks at once that that checkpoint belongs to this
  /// scene and model (before any output file is opened, so that a refused
  /// restart leaves the old run's files as they were).
  Checkpoint(const Scene& scene, std::uint64_t blocks_fingerprint, RigidSolver* rigid,
             DeformableSolver* zones, const std::string& restart_from = "");

  /// Restores the default handling of SIGINT and SIGTERM.
  ~Checkpoint();
  Checkpoint(const Checkpoint&) = delete;
  Checkpoint& operator=(const Checkpoint&) = delete;

  void add(HistoryFile& history) { histories_.push_back(&history); }
  void add(PvdSeries& series) { series_.push_back(&series); }
  /// A counter of the output loop (frame numbers, step of the last output).
  void add(unsigned int& counter) { counters_.push_back(&counter); }
  void add(unsigned long& counter) { long_counters_.push_back(&counter); }
  /// A real number of the run loop (the model time a stage began at, s).
  void add(double& value) { real_values_.push_back(&value); }
  /// The run loop's count of stages begun: the stages whose parameters a
  /// restart must find unchanged.
  void set_stages_begun(const unsigned int* begun) { stages_begun_ = begun; }
  /// On several ranks: this rank's share of the model (its blocks, their
  /// owners and the migration's state), saved in this rank's file.
  void add(RankShare& share) { share_ = &share; }
  /// A split of the zones among the ranks that the run may change (a body
  /// alone split again after an excavation): `save` writes what makes it,
  /// and on a restart `load` makes it again before the zones' state is
  /// read into the solver `zones` then gives (the cycle's new one).
  void add_split(std::function<void(CheckpointWriter&)> save,
                 std::function<void(CheckpointReader&)> load,
                 std::function<DeformableSolver*()> zones)
  {
    save_split_ = std::move(save);
    load_split_ = std::move(load);
    zone_source_ = std::move(zones);
  }

  /// Where checkpoints go: `<Output directory>/<Base name>_checkpoint.bin`;
  /// on N ranks, rank R's file of the set: that name + `.rank-R-of-N`.
  const std::string& path() const { return path_; }

  /// Writes a checkpoint when one is due at `step` (the interval, or a stop
  /// signal); after a signal, throws RunInterrupted once it is written.
  /// Also the test hook: TALUS_TEST_SIGNAL_AT_STEP=k raises SIGTERM at step k.
  void after_step(unsigned long step);

  /// Writes a checkpoint of the state at `step` now (atomically).
  void write(unsigned long step) const;

  /// Restores everything registered from `file`; returns its step.
  unsigned long restore(const std::string& file);

private:
  /// Reads the scene and geometry fingerprints that follow the parameter
  /// file's name and refuses a checkpoint of another scene; returns its step.
  unsigned long check_fingerprints(CheckpointReader& in, const std::string& file) const;

  const Scene& scene_;
  RigidSolver* rigid_;
  DeformableSolver* zones_;
  std::function<void(CheckpointWriter&)> save_split_;
  std::function<void(CheckpointReader&)> load_split_;
  std::function<DeformableSolver*()> zone_source_;
  /// The zone solver now: the block solver's, the cycle's, or the first.
  DeformableSolver* zone_solver() const;
  SceneFingerprint scene_hash_;
  std::uint64_t geometry_hash_;
  const unsigned int* stages_begun_ = nullptr;
  unsigned long interval_;
  long signal_test_step_ = -1;
  unsigned int rank_ = 0, ranks_ = 1;
  RankShare* share_ = nullptr;
  std::string set_; ///< `<Output directory>/<Base name>_checkpoint.bin`
  std::string path_;
  std::vector<HistoryFile*> histories_;
  std::vector<PvdSeries*> series_;
  std::vector<unsigned int*> counters_;
  std::vector<unsigned long*> long_counters_;
  std::vector<double*> real_values_;
};

} // namespace talus
