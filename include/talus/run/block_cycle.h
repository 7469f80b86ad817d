#pragma once

#include <talus/base/parallel_environment.h>
#include <talus/io/block_vtu_writer.h>
#include <talus/io/contact_vtu_writer.h>
#include <talus/io/zone_vtu_writer.h>
#include <talus/run/cycle.h>
#include <talus/run/rank_share.h>
#include <talus/run/rank_zones.h>
#include <talus/run/run_summary.h>
#include <talus/scene/block_system.h>

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace talus
{

/// m: how far beyond a rank's blocks its ghosts reach: the contact
/// tolerance plus three more of motion until they are chosen again.
double contact_reach(const Scene& scene);

/// Whether a new run on ranks builds only each rank's region of the blocks
/// (RankShare from the scene): a scene of rigid blocks with steps to run,
/// without a factor of safety, in 'Mode' or in a stage
/// nor search a factor of safety (those build trials of the whole model).
bool builds_by_region(const Scene& scene);

/// The distinct element cycle of a model of blocks: rigid ones, and
/// deformable ones with their zones (BlockSystem); contacts between all.
class BlockCycle : public Cycle
{
public:
  /// Meshes the deformable blocks and builds the solvers (printing the
  /// summary's lines on zones and the time step); `prefix` is the output
  /// folder and base name. Started on several MPI ranks, each rank runs its
  /// share of the model (RankShare) and the summary, the history and the
  /// output are those of the whole model; `restart_from`: this rank's
  /// checkpoint file, whose blocks the rank holds (on ranks).
  /// `share` and `region_digest`: this rank's share built from the scene
  /// (builds_by_region), when `model` holds no block, and the whole
  /// model's digest.
  BlockCycle(Scene& scene, BlockModel& model, const std::string& prefix,
             const std::string& restart_from = "", std::unique_ptr<RankShare> share = nullptr,
             const ModelDigest* region_digest = nullptr);
  ~BlockCycle() override;

  void step() override;
  unsigned long steps_done() const override;
  double time() const override;
  double dt() const override { return system_.solver->dt(); }
  double ratio() const override;
  bool may_stop(unsigned long stage_steps) const override { return stage_steps > 10; }
  std::vector<std::string> history_columns() const override;
  std::vector<double> history_row() override;
  void write_frame(bool diverged) override;
  void register_checkpoint(Checkpoint& checkpoint) override;
  RigidSolver* rigid() override { return system_.solver.get(); }
  DeformableSolver* zones() override { return system_.zones.get(); }
  void begin_stage(const StageSpec& stage) override;
  void restore_stage(const StageSpec& stage) override;
  int factor_of_safety(const std::vector<StageSpec>& stages, unsigned int k) override;
  std::string displacement_text() const override;
  void print_end() override;
  std::string unbalanced_where() const override;

private:
  /// On ranks, with deformable blocks among others: every deformable block
  /// meshed, before the model is split; kept to split it again when
  /// deformable blocks change rank.
  std::unique_ptr<WholeZones> whole_zones_;
  /// On a restart on ranks: the surfaces the rank held (RankZones::surfaces).
  std::vector<unsigned int> saved_surfaces_;
  /// The rank's share of the model (null on one rank); declared before
  /// model_, which is its model.
  std::unique_ptr<RankShare> share_;
  /// When this rank built only its region: the whole model's digest, which
  /// gives the face loads' table of each stage.
  const ModelDigest* region_digest_ = nullptr;
  /// On ranks, the table of a stage's face loads (null when it changes no
  /// boundaries, or the blocks as built give it).
  std::optional<RigidFaceLoads> stage_face_loads(const StageSpec& stage) const;
  /// On ranks, with zones: what their split keeps (global blocks, history
  /// points reported here).
  RankZones rank_zones_;
  unsigned long migrations_seen_ = 0;
  /// On ranks, with zones: this rank's zones as its output piece shows
  /// them (blocks by their global numbers).
  TetMesh zone_piece_;
  /// On ranks, once deformable blocks changed rank: the mesh of the zones'
  /// split now (system_.mesh before), and the solver and mesh they left,
  /// kept until the migration that moved them has ended.
  std::unique_ptr<TetMesh> zone_mesh_, retired_mesh_;
  std::unique_ptr<DeformableSolver> retired_zones_;
  bool zones_moved_ = false;
  double zone_move_seconds_ = 0.0; ///< wall time of the new splits, rank 0's
  /// The stages begun, in order: their changes of the zones are set again
  /// on a new split.
  std::vector<StageSpec> stages_begun_;
  Scene& scene_;
  BlockModel& model_;
  std::string prefix_;
  std::unique_ptr<ParallelEnvironment> parallel_;
  /// The blocks as built (before the zones' surfaces replace the faces of
  /// deformable ones), where a stage's face loads are selected (as those of
  /// the file were) and a stage's factor of safety builds its trials; kept
  /// only when a stage needs it.
  std::unique_ptr<BlockModel> built_model_;
  double meshing_start_; ///< s, steady clock: when the zones began
  /// Built in place: its solvers hold references to its mesh.
  BlockSystem system_;
  PvdSeries block_series_, contact_series_, zone_series_;
  std::unique_ptr<ZoneWriter> zone_writer_;
  std::unique_ptr<PointHistory> points_;
  JointNumbers joint_numbers_;
  unsigned int frame_ = 0, zone_frame_ = 0;
  /// The blocks' centroids as built (m): where stage regions select them.
  std::vector<Vec3> built_centroid_;

  /// On ranks: this rank's largest unbalanced force at the last step (N;
  /// -1: none) and its block's global number.
  std::pair<double, unsigned int> unbalanced_{-1.0, 0};
  /// The global block that moved most (owned by any rank), and how far (m).
  std::pair<double, unsigned int> largest_displacement() const;
  /// Writes this rank's piece of a frame (`name` + "_<rank>.vtu") and, on
  /// rank 0, the .pvtu that joins the pieces; returns the file the series
  /// lists.
  std::string write_pieces(const std::string& name,
                           const std::function<void(const std::string&)>& write_piece) const;
  /// Writes the zones' frame (on ranks a piece per rank).
  void write_zones(bool with_stress);
  /// The zones' mesh now (on ranks it changes with deformable blocks' ranks).
  TetMesh& zone_mesh() { return zone_mesh_ ? *zone_mesh_ : system_.mesh; }
  /// On ranks, with zones: the writer of this rank's piece, for its zones now.
  void make_zone_piece();
  /// After a migration split the zones again: the stages' changes of the
  /// zones set again, the old solver freed, the output piece made anew.
  void finish_zone_move();
};

} // namespace talus
