#pragma once

#include <talus/contact/block_decomposition.h>

#include <mpi.h>

#include <vector>

namespace talus
{

class RigidSolver;
struct RankReductions;

/// What RigidSolver::split_among_ranks needs of all ranks, by MPI
/// collectives over `comm` (every rank must call them alike).
RankReductions reductions_over(MPI_Comm comm);

/// The ghosts of a model split among ranks kept equal to their owners'
/// blocks: after every step each rank sends the state of its blocks that
/// are ghosts elsewhere (RigidSolver::pack_block) and writes what it
/// receives into its own ghosts, one message per neighbour rank each way.
class GhostExchange
{
public:
  GhostExchange(const RankBlocks& blocks, MPI_Comm comm) : blocks_(blocks), comm_(comm) {}

  /// Owners' state to the ghosts; returns after every message arrived.
  void refresh(RigidSolver& solver);

  /// Doubles sent by this rank in the last refresh (the exchange volume).
  std::size_t sent() const { return sent_; }

private:
  const RankBlocks& blocks_;
  MPI_Comm comm_;
  std::vector<std::vector<double>> out_, in_;
  std::size_t sent_ = 0;
};

} // namespace talus
