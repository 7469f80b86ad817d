#pragma once

// Checkpoints of a run split among MPI ranks (issue 24): a set of files,
// one per rank, `<Base name>_checkpoint.bin.rank-R-of-N`, each a checkpoint
// of the serial layout (io/checkpoint.h) holding its rank and the number of
// ranks after the first tag, this rank's solver state (its owned blocks
// and ghosts, their contacts) and, after the step, its share: its blocks
// (RankBlocks: the local-to-global map, the owned flags, the lists of the
// ghost exchange) and the migration's state. Rank 0's file also holds the
// history. Every rank writes at the same step, and none goes on until all
// have written. A set restarts on the number of ranks it was written on,
// named by `<Base name>_checkpoint.bin` (or any file of it).

#include <talus/base/archive.h>
#include <talus/contact/block_decomposition.h>

#include <string>

namespace talus
{

/// Rank `rank`'s file of the set `set` (`<Base name>_checkpoint.bin`) of a
/// run on `ranks` ranks; rank -1 gives the set's pattern (`rank-*-of-N`).
std::string rank_checkpoint_path(const std::string& set, int rank, unsigned int ranks);

/// The command that continues the run whose checkpoint is `file`, written
/// on `ranks` ranks: "talus --restart SET" or "mpirun -np N talus --restart
/// SET" (SET: `file` less its `.rank-R-of-N`).
std::string restart_command(const std::string& file, unsigned int ranks);

/// For `talus --restart GIVEN` on this process's ranks (collective under
/// mpirun): the file this rank continues from. On one rank, GIVEN itself;
/// on N ranks, rank R's file of the set GIVEN names (`GIVEN.rank-R-of-N`,
/// or GIVEN is a file of the set). Refuses (InputError, on every rank
/// alike) a serial checkpoint on ranks, a set on one rank or on another
/// number of ranks than it was written on, a set that lacks a rank's file,
/// and a set whose files are of different steps.
std::string checkpoint_of_this_rank(const std::string& given);

/// The blocks a rank held at the checkpoint `file` (its share, read before
/// the solver is built on them). Defined in checkpoint.cc, which knows the
/// header before it. `zone_surfaces`: also the deformable blocks of other
/// ranks whose surfaces it held (RankZones::surfaces).
RankBlocks read_rank_blocks(const std::string& file,
                            std::vector<unsigned int>* zone_surfaces = nullptr);

/// RankBlocks in a checkpoint's section "ranks" (RankShare::save_state).
void put_rank_blocks(CheckpointWriter& out, const RankBlocks& blocks);
RankBlocks get_rank_blocks(CheckpointReader& in);

} // namespace talus
