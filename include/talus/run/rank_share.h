#pragma once

#include <talus/contact/block_decomposition.h>
#include <talus/contact/cell_partition.h>
#include <talus/model/block_model.h>
#include <talus/run/rank_balance.h>
#include <talus/scene/build_blocks.h>
#include <talus/scene/model_digest.h>
#include <talus/scene/scene.h>
#include <talus/solver/block_migration.h>
#include <talus/solver/ghost_exchange.h>
#include <talus/solver/subcontact_exchange.h>

#include <mpi.h>

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace talus
{

class CheckpointReader;
class CheckpointWriter;
class RigidSolver;

/// The number of ranks of MPI_COMM_WORLD, 1 when MPI has not been started
/// (talus scene.prm without mpirun).
int world_ranks();
/// This process's rank in MPI_COMM_WORLD, 0 without MPI.
int world_rank();

/// Runs `build` on every rank of MPI_COMM_WORLD. When it throws an
/// InputError on some ranks, every rank throws that of the lowest of them
/// (so that rank 0 prints it and no rank waits for the others); other
/// exceptions pass as they are.
void agree_on_input_errors(const std::function<void()>& build);

/// Refuses, with one message naming the entry, what talus cannot run
/// split among ranks: today only a bad TALUS_REBALANCE_THRESHOLD (every
/// scene runs on ranks).
void check_runs_on_ranks(const Scene& scene, int ranks);

/// This rank's share of a model of rigid blocks split among the ranks of
/// `comm` (issue 24): the blocks it owns, whose centroids lie in its region
/// of a CellPartition of the model's cell space balanced by blocks, and one
/// layer of ghosts, the blocks within reach of those (decompose_blocks;
/// contacts between two ghosts are not kept); the model of those blocks in global
/// order (BlockModel::subset); the exchange that keeps the ghosts equal to
/// their owners' blocks; and the reductions that make the summary, the
/// history and the output of the whole model from the shares.
class RankShare
{
public:
  /// Layers of ghosts: one holds every block an owned block can touch. No
  /// contact between two ghosts is kept; a ghost that becomes owned comes
  /// with its contacts from its old owner (BlockMigration).
  static constexpr unsigned int ghost_layers = 1;

  /// `reach` (m): the contact tolerance plus the motion allowed until the
  /// ghosts are chosen again. `saved`: the blocks this rank held at a
  /// checkpoint (read_rank_blocks), instead of those the partition gives.
  /// `zones_of_block`: per block, its zones (0 for a rigid one), work the
  /// regions balance besides the blocks.
  RankShare(const BlockModel& model, double reach, MPI_Comm comm, const RankBlocks* saved = nullptr,
            const std::vector<double>* zones_of_block = nullptr);

  /// The same share of the rigid blocks a scene describes, without any
  /// rank building the whole model (issue 24): every rank cuts the brick
  /// twice, one piece at a time (build_blocks_where). The first pass keeps
  /// no block: it finds the model's bounds and its largest block, and each
  /// rank takes the centroids of every ranks-th block, from which the
  /// ranks cut the cell space together, adding their counts exactly
  /// (CellPartition's sum over processes). The second keeps the blocks
  /// whose centroids lie in this rank's region and those that could touch
  /// them (within reach of the region grown by the largest block), and
  /// those are split into owned blocks and ghosts as above. The blocks,
  /// their numbers, the regions and the exchanges' lists are those the
  /// constructor above gives from the whole model, bit for bit; the memory
  /// is that of the blocks kept. `report`: the whole model's cutting.
  /// `digest` (optional) takes every block of the first pass in order, and
  /// `check` is called after it, before the ranks cut the cell space: a
  /// model it refuses stops every rank alike. `saved`: on a restart, the
  /// blocks this rank held at its checkpoint (read_rank_blocks), the only
  /// ones the second pass keeps. Defined in rank_region_setup.cc.
  RankShare(const Scene& scene, BuildReport& report, double reach, MPI_Comm comm,
            ModelDigest* digest = nullptr, const std::function<void()>& check = {},
            const RankBlocks* saved = nullptr);

  /// The number of blocks in the whole model.
  unsigned int n_blocks() const { return n_blocks_; }

  int rank() const { return rank_; }
  /// m: the contact tolerance plus the motion allowed between choices of the ghosts.
  double reach() const { return reach_; }
  int ranks() const { return ranks_; }
  MPI_Comm comm() const { return comm_; }
  const RankBlocks& blocks() const { return blocks_; }
  /// The model of the blocks this rank holds (owned and ghosts).
  BlockModel& local() { return local_; }
  const BlockModel& local() const { return local_; }
  /// Per local block: 1 for a ghost (RigidSolver::split_among_ranks).
  std::vector<char> ghost_flags() const;

  /// Local index of global block `global`, or -1 when this rank does not
  /// hold it.
  int local_of(unsigned int global) const;
  bool owns(unsigned int global) const;

  /// After a step: the ghosts refreshed from their owners, then the blocks
  /// handed to other ranks when they have moved far enough
  /// (BlockMigration), or when the regions were cut again because the
  /// ranks' work became uneven (RankBalance; local numbers may change:
  /// local() changes in place and blocks() gives the new map).
  void refresh(RigidSolver& solver);
  /// The regions' rebalances so far and the imbalances (largest work over
  /// the mean) of the last check and expected after the last rebalance.
  const RankBalance& balance() const { return *balance_; }
  /// The work is checked at the next refresh, whatever its step (a stage
  /// excavated blocks). Every rank calls it at the same point.
  void check_balance_soon() { balance_->check_soon(); }
  /// Migration events so far, and the blocks that changed owner in them.
  unsigned long migrations() const;
  unsigned long owner_changes() const;
  /// The sum of the steps of the migration events: when they happened, in
  /// one number (a restart that lost the migration's state moves them).
  unsigned long event_steps() const { return event_steps_; }
  /// Deformable blocks follow their regions (BlockMigration::let_zones_follow).
  void let_zones_follow(BlockMigration::ZoneRebuild rebuild);
  /// Migration events that split the zones again.
  unsigned long zone_moves() const;
  /// The deformable blocks of other ranks whose surfaces this rank holds
  /// (RankZones::surfaces), which its checkpoint keeps (read_rank_blocks).
  void set_zone_surfaces(std::vector<unsigned int> surfaces)
  {
    zone_surfaces_ = std::move(surfaces);
  }
  /// Doubles sent by this rank at the last refresh.
  std::size_t sent() const { return exchange_->sent(); }
  /// The exchange of the contacts across this rank's boundary, each
  /// computed by one rank (RigidSolver::share_subcontacts).
  SubContactExchange* subcontacts() { return subcontacts_.get(); }

  /// Element-wise sums over the ranks of `values` (in place).
  void sum(std::vector<double>& values) const;
  unsigned long sum(unsigned long value) const;
  /// The largest of the ranks' `value`, with the global block that has it
  /// (the lowest numbered one of equal values, as a serial loop that keeps
  /// the first largest finds).
  std::pair<double, unsigned int> largest(double value, unsigned int global) const;

  /// This rank's blocks and the migration's state, in a checkpoint; loading
  /// checks the blocks against those it was made with (`saved`) and makes
  /// the migration for `solver`. Defined in io/rank_checkpoint.cc.
  void save_state(CheckpointWriter& out) const;
  void load_state(CheckpointReader& in, const RigidSolver& solver);

  /// The global number of the model's block `local` (a local index).
  unsigned int global_of(unsigned int local) const { return blocks_.local[local]; }

private:
  MPI_Comm comm_;
  int rank_ = 0, ranks_ = 1;
  double reach_;
  std::unique_ptr<CellPartition> partition_;
  RankBlocks blocks_;
  BlockModel local_;
  std::unique_ptr<GhostExchange> exchange_;
  std::unique_ptr<SubContactExchange> subcontacts_;
  std::unique_ptr<BlockMigration> migration_; ///< made at the first refresh
  std::unique_ptr<RankBalance> balance_;
  std::vector<double> zones_of_block_; ///< per global block (empty: no zones)
  unsigned long event_steps_ = 0;
  BlockMigration::ZoneRebuild zone_rebuild_;
  std::vector<unsigned int> zone_surfaces_;
  unsigned int n_blocks_ = 0;
  void make_migration(const RigidSolver& solver);
  /// The ghosts' and the sub-contacts' exchanges of blocks_.
  void start_exchanges();
};

} // namespace talus
