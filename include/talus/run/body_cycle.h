#pragma once

#include <talus/base/parallel_environment.h>
#include <talus/io/block_vtu_writer.h>
#include <talus/io/zone_vtu_writer.h>
#include <talus/run/cycle.h>
#include <talus/run/run_summary.h>
#include <talus/solver/deformable_solver.h>
#include <talus/zone/block_mesher.h>
#include <talus/zone/gridpoint_share.h>

#include <memory>
#include <string>
#include <vector>

namespace talus
{

/// The zones of one deformable body alone (a scene of one deformable
/// block, meshed or read from a mesh file): no contacts. Started on several
/// MPI ranks, every rank meshes the body and keeps its share of it
/// (share_mesh: the zones around the gridpoints it owns, with ghosts); the
/// summary, the history and the output are the whole body's.
class BodyCycle : public Cycle
{
public:
  /// Meshes (or reads) the body and builds its solver, printing the
  /// summary's lines on the zones and the time step.
  BodyCycle(Scene& scene, BlockModel& model, const std::string& prefix);

  void step() override { solver_->step(); }
  unsigned long steps_done() const override { return solver_->steps_done(); }
  double time() const override { return solver_->time(); }
  double dt() const override { return solver_->dt(); }
  double ratio() const override { return solver_->unbalanced_ratio(); }
  /// A boundary moving at a velocity until a time must have stopped.
  bool may_stop(unsigned long stage_steps) const override
  {
    return stage_steps >= 20 && solver_->time() >= moving_until_;
  }
  std::vector<std::string> history_columns() const override;
  std::vector<double> history_row() override;
  void write_frame(bool diverged) override;
  void register_checkpoint(Checkpoint& checkpoint) override;
  DeformableSolver* zones() override { return solver_.get(); }
  void begin_stage(const StageSpec& stage) override;
  void restore_stage(const StageSpec& stage) override;
  int factor_of_safety(const std::vector<StageSpec>& stages, unsigned int k) override;
  std::string displacement_text() const override;
  void print_end() override;
  std::string unbalanced_where() const override;

  /// The zones of a scene of one deformable block: meshed, or read from its
  /// mesh file (then ordered and made quadratic as the scene asks).
  static TetMesh zones_of(const Scene& scene, const BlockModel& model, MeshReport& report);

private:
  /// On ranks: this rank's share of `whole` as the mesh the solver runs,
  /// and what the whole body's numbers need (owners, the zones counted);
  /// the zones `removed` marks (per zone of `whole`) do no work.
  void split_among_ranks(const TetMesh& whole, const std::vector<char>* removed = nullptr);
  /// The zone solver of the split (its materials as built).
  void make_solver();
  /// On ranks: the ranks' largest work (the zones not removed that each
  /// counts) over the mean. Collective.
  double work_ratio() const;
  /// On ranks, after a stage's excavation: when the ranks' work has become
  /// uneven (work_ratio above TALUS_REBALANCE_THRESHOLD, 1.15), the body's
  /// zones split again, balanced by the zones left, the state moving to
  /// the new owners (move_zone_state) and the earlier stages' changes set
  /// again. Collective.
  void rebalance_after_excavation();
  /// The split with the zones `removed` (whole-mesh numbers; empty: the
  /// first split) doing no work, from the whole mesh made again; with
  /// `move_state`, the state moves from the solver until now, else the new
  /// solver waits for a checkpoint's. Collective.
  void split_again(const std::vector<unsigned int>& removed, bool move_state);
  /// The implicit check of a body split among ranks: the gridpoints'
  /// displacements gathered on rank 0, which checks them with a solver of
  /// the whole mesh made for it (collective; rank 0 prints).
  void implicit_check_on_ranks();
  /// The zones this rank counts (each zone once over the ranks), of a
  /// stage's excavation and the summary.
  bool counts(unsigned int z) const
  {
    return !split_ || mesh_->zone_gridpoint[z][0] < solver_->owned_gridpoints();
  }
  /// The history points' values (PointHistory::add_values) of the whole
  /// body: each from the rank that holds its gridpoint or zone.
  void add_point_values(std::vector<double>& row) const;
  /// Sums over the ranks (one rank: the value itself).
  double sum_over_ranks(double value) const;
  /// The position now of gridpoint `g` of the whole mesh, from its owner (m).
  Vec3 whole_gridpoint_position(unsigned int g) const;

  /// What stage `stage` changed of the zones that a new solver does not
  /// hold (its rock materials, water, boundaries), set again without
  /// accounting: on a restart, and on a new split.
  void set_stage_again(const StageSpec& stage);
  /// A stage's 'Rock materials' into the solver; prints what changed
  /// unless restoring (`account` false).
  void change_rock_materials(const StageSpec& stage, bool account);
  /// The centroid of zone z's corners as built (m).
  Vec3 zone_centroid(unsigned int z) const;

  Scene& scene_;
  BlockModel& model_;
  std::string prefix_;
  MeshReport report_;
  /// The zones this rank runs (its own object: a solver keeps a reference).
  std::unique_ptr<TetMesh> mesh_;
  std::unique_ptr<ParallelEnvironment> parallel_;
  std::unique_ptr<DeformableSolver> solver_;
  PvdSeries series_;
  std::unique_ptr<ZoneWriter> writer_;
  std::unique_ptr<PointHistory> points_;
  /// On ranks (split_): the rank of each gridpoint of the whole mesh; per
  /// history point, its gridpoint's and zone's local index on the rank
  /// that reports it (-1 elsewhere); the zones of this rank's output piece
  /// (those it counts) and the mesh of that piece.
  bool split_ = false;
  GridpointShare share_;
  std::vector<unsigned int> owner_;
  std::vector<int> point_gridpoint_, point_zone_;
  /// Per local zone: its number in the whole mesh (ascending).
  std::vector<unsigned int> zone_whole_;
  /// The stages begun, in order: set again on a new split.
  std::vector<StageSpec> stages_begun_;
  /// The zones removed (whole-mesh numbers) when the zones were last split
  /// again (empty: the first split holds), kept by the checkpoints; the
  /// splits made again, and the work ratio before and after the last one.
  std::vector<unsigned int> split_removed_;
  unsigned long rebalances_ = 0;
  double ratio_before_ = 0.0, ratio_after_ = 0.0;
  std::vector<unsigned int> piece_zone_;
  TetMesh piece_;
  unsigned int whole_zones_ = 0;
  unsigned int frame_ = 0;
  double moving_until_ = 0.0; ///< s: the last end time of a boundary velocity
};

} // namespace talus
