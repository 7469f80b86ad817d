#include <talus/base/gather.h>

#include <limits>
#include <stdexcept>

namespace talus
{

namespace
{
template <typename T>
std::vector<T> gathered(const std::vector<T>& mine, MPI_Comm comm, MPI_Datatype type)
{
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  if (mine.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw std::runtime_error("gathered_on_every_rank: a rank's share exceeds one MPI message");
  const int count = static_cast<int>(mine.size());
  std::vector<int> counts(ranks), starts(ranks, 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  long long total = counts[0];
  for (int r = 1; r < ranks; ++r)
  {
    starts[r] = starts[r - 1] + counts[r - 1];
    total += counts[r];
  }
  if (total > std::numeric_limits<int>::max())
    throw std::runtime_error("gathered_on_every_rank: the ranks' shares exceed one MPI message");
  std::vector<T> all(std::size_t(starts.back()) + std::size_t(counts.back()));
  MPI_Allgatherv(mine.data(), count, type, all.data(), counts.data(), starts.data(), type, comm);
  return all;
}
} // namespace

std::vector<double> gathered_on_every_rank(const std::vector<double>& mine, MPI_Comm comm)
{
  return gathered(mine, comm, MPI_DOUBLE);
}

std::vector<char> gathered_on_every_rank(const std::vector<char>& mine, MPI_Comm comm)
{
  return gathered(mine, comm, MPI_BYTE);
}

} // namespace talus
