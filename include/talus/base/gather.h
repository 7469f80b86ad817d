#pragma once

#include <mpi.h>

#include <vector>

namespace talus
{

/// Every rank's `mine`, one after another in rank order, on every rank of
/// `comm` (MPI_Allgather of the counts, then MPI_Allgatherv). Collective.
std::vector<double> gathered_on_every_rank(const std::vector<double>& mine, MPI_Comm comm);
/// The same for bytes.
std::vector<char> gathered_on_every_rank(const std::vector<char>& mine, MPI_Comm comm);

} // namespace talus
