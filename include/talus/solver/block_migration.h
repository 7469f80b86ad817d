#pragma once

#include <talus/contact/block_decomposition.h>
#include <talus/contact/cell_partition.h>

#include <mpi.h>

#include <cstdint>
#include <functional>
#include <unordered_map>
#include <vector>

namespace talus
{

class CheckpointReader;
class ContactSet;
class CheckpointWriter;
class DeformableSolver;
class RigidSolver;

/// Ownership that follows the blocks of a rigid model split among ranks
/// (issue 24; the manual's "Data Structure": blocks are remapped to
/// neighbouring processors as they move). The decomposition of
/// decompose_blocks holds every contact of a rank's owned blocks only while
/// no block has moved more than the margin in its `reach`, and its owners
/// stay near their blocks only while the centroids stay in their regions.
/// When either fails on some rank, every block goes to the rank whose
/// region holds its centroid, the ghosts are chosen again around the
/// blocks as they are now, and each rank receives the blocks it newly holds
/// or newly owns (a ghost that becomes owned) from their old owners, with
/// everything the solver keeps of them
/// (geometry, group, masses, motion, the state of eq. 1 and of the damper's
/// last force) and their contacts' state (common plane, sub-contacts with
/// their normal and shear forces, shear displacements, slip state,
/// dilation, yield state), and drops the blocks it no longer needs and the
/// contacts between two of its ghosts (no rank keeps those). The
/// local order stays the global order, and the contacts are laid out again
/// in block-pair order, so that the run stays bit-identical to the serial
/// one.
///
/// Communication at a migration event (rare: the margin of `reach` is worth
/// many steps of motion), all of it between ranks whose regions are near,
/// point to point, with the sizes by MPI_Alltoall (one integer per pair of
/// ranks): each owner sends its blocks' boxes and centroids (10 numbers a
/// block) to the ranks whose regions come within (layers + 1) (reach + s)
/// of them (s: the longest side of any block's box), enough for each to
/// choose its blocks and lists as from the whole model; each rank asks the
/// old owners for the blocks it newly holds, and they send them. Besides,
/// one MPI_Allreduce for s and one for the count of owner changes.
///
/// After an event, update() places the face loads (from the solver's table
/// of the whole model, RigidSolver::set_face_load_table) and the water on
/// the blocks each rank owns now (RigidSolver::localize_loads). A solver
/// with face loads but no table is refused (std::logic_error) at the first
/// event.
///
/// With zones split among the ranks, a deformable block keeps its first
/// owner unless let_zones_follow() was given a rebuild: then it follows its
/// region as a rigid block does, and at an event where one changes owner,
/// or where a rank needs the surface of one it does not hold, the rebuild
/// splits the zones again (one MPI_Allreduce decides it). Sub-contacts'
/// gridpoints travel, and are kept, by their numbers in the whole mesh.
class BlockMigration
{
public:
  /// For `solver`, which holds `blocks` (decompose_blocks with `reach` and
  /// `layers`) of a model split by `partition` among the ranks of `comm`.
  /// `reach` must exceed twice the contact tolerance; the rest is twice the
  /// motion a block may make between two choices of the ghosts.
  /// `partition` must outlive this object.
  BlockMigration(const RigidSolver& solver, const RankBlocks& blocks,
                 const CellPartition& partition, double reach, unsigned int layers, MPI_Comm comm);

  /// Call after every step once the ghosts were refreshed
  /// (GhostExchange::refresh), on every rank alike. Migrates when due();
  /// then `blocks`, the solver's block model (the one it was built on,
  /// changed in place), its per-block state and contacts change, and a
  /// GhostExchange on `blocks` sends along the new lists. Returns whether
  /// it migrated.
  bool update(RigidSolver& solver, RankBlocks& blocks);

  /// Whether the decomposition must be chosen again, decided on all ranks
  /// alike (RankReductions::any): an owned block whose centroid has left
  /// this rank's region, or that has moved more than allowance() since the
  /// ghosts were chosen (its path, the sum of its vertices' largest moves
  /// per step along an axis, eq. 1's measure).
  bool due(const RigidSolver& solver, const RankBlocks& blocks) const;
  /// Chooses owners and ghosts again now and moves the blocks (collective).
  /// With `may_refuse`, a choice that would need a deformable block's
  /// surface on a rank that does not hold it changes nothing and returns
  /// false (on every rank); without, it is an InputError.
  bool migrate(RigidSolver& solver, RankBlocks& blocks, bool may_refuse = false);
  /// After the partition this migration was made with changed (a
  /// rebalance, RankBalance): migrate() now and place the loads as
  /// update() does. False, and nothing changed, when migrate() refused.
  bool migrate_to_new_regions(RigidSolver& solver, RankBlocks& blocks);

  /// What a rank holds of the zones once deformable blocks have changed
  /// owner: the solver of the new split, the local gridpoint of each vertex
  /// of the rank's new local model (-1 on rigid blocks), and the surfaces
  /// of the deformable blocks it holds (owned ones and others near), each
  /// with its vertices' local gridpoints.
  struct ZonesMoved
  {
    DeformableSolver* zones = nullptr;
    std::vector<int> vertex_gridpoint;
    std::unordered_map<unsigned int, std::vector<int>> held_surfaces;
  };
  /// Splits the zones again for the blocks as `next` holds them (the
  /// model's blocks `next_model`, their solver arrays laid out already),
  /// `before` being the blocks held until now, and moves the zones' state
  /// (move_zone_state). The solver it returns replaces the one the rigid
  /// solver had, which must live until migrate() returns. Collective.
  using ZoneRebuild = std::function<ZonesMoved(const RankBlocks& before, const RankBlocks& next,
                                               const BlockModel& next_model)>;
  /// From now on deformable blocks follow their regions as rigid ones do:
  /// at an event where one changes owner, or where a rank needs the
  /// surface of one it does not hold, `rebuild` splits the zones again.
  /// Without it, a deformable block keeps its first owner.
  void let_zones_follow(ZoneRebuild rebuild) { rebuild_ = std::move(rebuild); }
  /// Events at which the zones were split again.
  unsigned long zone_moves() const { return zone_moves_; }

  /// The motion (m) a block may make between two choices of the ghosts:
  /// two blocks whose boxes were more than `reach` apart then come within
  /// two contact tolerances (the envelopes' overlap that makes a candidate
  /// pair) only after moving together by reach - 2 CTOL.
  double allowance() const { return allowance_; }
  /// Migration events so far.
  unsigned long events() const { return events_; }
  /// Blocks that changed owner, over all ranks and events (equal on every rank).
  unsigned long owner_changes() const { return owner_changes_; }
  /// Blocks this rank received (began to hold) and dropped, over all events.
  unsigned long received() const { return received_; }
  unsigned long dropped() const { return dropped_; }

  /// A stage's factor of safety on ranks, whose trials are serial runs of
  /// the whole model: `whole`, a solver built on a copy of the whole model
  /// as built (on every rank), takes the state of every block and contact
  /// of the model split among the ranks of `comm` (`solver` holding
  /// `blocks`) as one rank's run would hold it now, blocks by their global
  /// numbers and contacts in block-pair order, so that its save_state is
  /// what the serial run's would load as. Each owner sends its blocks and
  /// the contacts whose first block it owns to every rank (one
  /// MPI_Allgatherv). With zones (both solvers, `whole`'s of the whole mesh
  /// as one run meshes it) the sub-contacts' gridpoints come by their
  /// numbers in the whole mesh; the zones' own state is gathered apart
  /// (gather_whole_zones).
  static void gather_whole(const RigidSolver& solver, const RankBlocks& blocks, RigidSolver& whole,
                           MPI_Comm comm);

  /// The paths at the last choice and the counters, in a checkpoint
  /// (defined in io/rank_checkpoint.cc).
  void save_state(CheckpointWriter& out) const;
  void load_state(CheckpointReader& in);

private:
  /// Every per-block array of the solver that outlives a step, in one
  /// fixed order: `visit(array)` for each (those of principal inertia and
  /// of loads in time only where the solver has them). An array added to
  /// RigidSolver per block must be added there, or a block that changes
  /// rank loses it.
  template <typename Visit>
  static void visit_block_arrays(RigidSolver& solver, Visit&& visit);

  const CellPartition& partition_;
  double reach_;
  unsigned int layers_;
  MPI_Comm comm_;
  double allowance_;
  std::vector<double> path_at_choice_; ///< per local block: its path when the ghosts were chosen
  unsigned long events_ = 0, owner_changes_ = 0, received_ = 0, dropped_ = 0;
  ZoneRebuild rebuild_;
  unsigned long zone_moves_ = 0;
};

} // namespace talus
