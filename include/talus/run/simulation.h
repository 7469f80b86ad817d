#pragma once

#include <talus/model/block_model.h>
#include <talus/run/cycle.h>
#include <talus/scene/build_blocks.h>
#include <talus/scene/model_digest.h>
#include <talus/scene/scene.h>

#include <chrono>
#include <memory>
#include <string>

namespace talus
{

class RankShare;

/// One run of a scene (ASPECT's Simulator is the model): reads the
/// parameter file, builds the blocks, then the cycle the scene needs (a
/// model of blocks, or one deformable body alone) and the records (history
/// file, ParaView series, checkpoints, progress line) once, and runs the
/// stages in order through one loop. A scene without 'Stage N' is one
/// stage with the settings of 'Solver'.
class Simulation
{
public:
  /// `restart_from`: a checkpoint to continue from (empty: a new run).
  /// `check_only`: read, build and check, write nothing.
  Simulation(const std::string& parameter_file, std::string restart_from = "",
             bool check_only = false);
  /// A scene already read (and perhaps changed: tests run one scene in
  /// several modes); its output folder must exist.
  explicit Simulation(Scene scene);
  ~Simulation();

  /// Runs every stage; returns the exit code: 0, or 4 when a static stage
  /// with a target ratio stopped at its step limit above it.
  int run();

private:
  /// The summary's lines on the model as built.
  void print_model() const;
  /// `talus --check`: builds what the first step needs and prints it.
  void check_calculation();

  /// When the constructor began (reading the scene, building the blocks).
  std::chrono::steady_clock::time_point start_;
  std::string parameter_file_, restart_from_;
  bool check_only_;
  Scene scene_;
  BuildReport report_;
  /// The whole model; on ranks, when each rank builds only its region
  /// (share_), none of its blocks, only the groups.
  BlockModel model_;
  /// What the summary, checks and checkpoints need of the whole model.
  ModelDigest digest_;
  /// On ranks, for a new run of rigid blocks: this rank's share, built
  /// from the scene without the whole model (issue 24).
  std::unique_ptr<RankShare> share_;
  bool by_region_ = false;
  std::string prefix_; ///< output folder and base name
};

/// Exit code of a run whose static stage stopped at its step limit above
/// its target ratio: scripts must be able to tell it from an equilibrium.
constexpr int exit_not_in_equilibrium = 4;

} // namespace talus
