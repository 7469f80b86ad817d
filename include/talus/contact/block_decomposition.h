#pragma once

#include <talus/contact/cell_partition.h>
#include <talus/model/block_model.h>

#include <vector>

namespace talus
{

/// The blocks one rank holds when a model is split by a CellPartition: the
/// blocks it owns (their centroids lie in its region) and ghosts, copies of
/// other ranks' blocks that its own blocks can touch. Every contact of an
/// owned block then lies between two blocks the rank holds, so the rank
/// computes that block's contact forces alone, in the serial order (the
/// contacts sorted by block pair, ContactSet).
struct RankBlocks
{
  unsigned int rank = 0;
  /// Global block numbers, ascending: owned and ghost blocks together, so
  /// that local order is global order.
  std::vector<unsigned int> local;
  /// Per local block: owned by this rank (1) or a ghost (0).
  std::vector<char> owned;
  /// Per neighbour rank: the local indices of this rank's owned blocks that
  /// are ghosts there (sent after every move), ascending.
  std::vector<std::pair<unsigned int, std::vector<unsigned int>>> send;
  /// Per owner rank: the local indices of the ghosts it sends, ascending.
  std::vector<std::pair<unsigned int, std::vector<unsigned int>>> receive;

  unsigned int n_owned() const;

  /// Whether this rank computes the contact of held blocks a and b (local
  /// numbers, a < b): every contact of two owned blocks, none of two
  /// ghosts, and of a contact across ranks the one its computing block's
  /// owner computes (contact_computed_by_first).
  bool computes_contact(unsigned int a, unsigned int b) const
  {
    if (owned[a] == owned[b])
      return owned[a] != 0;
    return contact_computed_by_first(local[a], local[b]) ? owned[a] != 0 : owned[b] != 0;
  }

  /// Which block's owner computes a contact across ranks between blocks of
  /// global numbers ga < gb: the first's when ga + gb is even, the
  /// second's when odd, so that two neighbour ranks share the contacts
  /// between them about evenly (issue 24). Any rule that both ranks apply
  /// alike gives the same answer; the computing side only does the work.
  static bool contact_computed_by_first(unsigned int ga, unsigned int gb)
  {
    return ((ga + gb) & 1u) == 0;
  }
};

/// Rank `rank`'s blocks. A block is a ghost on this rank when it lies
/// within `layers` steps of contact reach of a block this rank owns: two
/// blocks are a step apart when their boxes, each grown by half of `reach`
/// (m: the contact tolerance plus the motion allowed until the ghosts are
/// chosen again), overlap. One layer holds every block an owned block can
/// touch; two also hold every block those ghosts can touch, so that a
/// ghost that becomes owned already has its contacts. Removed blocks
/// (`removed[b]`, may be empty) are neither owned nor ghosts.
RankBlocks decompose_blocks(const BlockModel& blocks, const CellPartition& partition,
                            unsigned int rank, double reach, unsigned int layers,
                            const std::vector<char>& removed = {});

/// The same from what every rank knows of the whole model when the
/// decomposition is chosen again during a run (BlockMigration): each
/// block's box (the bounds of its vertices, m) and the rank that owns it.
/// The box of a removed block is not read.
RankBlocks decompose_blocks(const std::vector<Box>& box, const std::vector<unsigned int>& owner,
                            unsigned int rank, double reach, unsigned int layers,
                            const std::vector<char>& removed = {});

} // namespace talus
