#include <talus/base/exceptions.h>
#include <talus/zone/meshing_on_ranks.h>

#include <algorithm>
#include <climits>
#include <cstdint>
#include <cstring>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <string>

namespace talus
{

namespace
{

/// Broadcasts `bytes` from `root` in pieces that fit MPI's int counts (a
/// rank's share of a large model's meshes can exceed 2 GB).
void broadcast_bytes(std::vector<char>& bytes, int root, MPI_Comm comm)
{
  std::uint64_t size = bytes.size();
  MPI_Bcast(&size, 1, MPI_UINT64_T, root, comm);
  bytes.resize(size);
  constexpr std::uint64_t piece = std::uint64_t(1) << 30;
  for (std::uint64_t first = 0; first < size; first += piece)
  {
    const int count = static_cast<int>(std::min(piece, size - first));
    if (MPI_Bcast(bytes.data() + first, count, MPI_BYTE, root, comm) != MPI_SUCCESS)
      throw std::runtime_error("mesh_convex_blocks_on_ranks: a message between ranks failed");
  }
}

template <typename T>
void put(std::vector<char>& out, const T* data, std::size_t n)
{
  const std::size_t at = out.size();
  out.resize(at + n * sizeof(T));
  if (n > 0)
    std::memcpy(out.data() + at, data, n * sizeof(T));
}

template <typename T>
void take(const std::vector<char>& in, std::size_t& at, T* data, std::size_t n)
{
  if (at + n * sizeof(T) > in.size())
    throw std::logic_error("mesh_convex_blocks_on_ranks: a rank's meshes end early");
  if (n > 0)
    std::memcpy(data, in.data() + at, n * sizeof(T));
  at += n * sizeof(T);
}

} // namespace

std::vector<int> meshing_ranks(const std::vector<double>& expected_zones, int ranks)
{
  // Largest first to the least loaded rank (ties: the lower block index,
  // the lower rank), the same on every rank.
  std::vector<std::size_t> order(expected_zones.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b)
                   { return expected_zones[a] > expected_zones[b]; });
  std::vector<double> load(static_cast<std::size_t>(std::max(ranks, 1)), 0.0);
  std::vector<int> rank_of(expected_zones.size(), 0);
  for (std::size_t i : order)
  {
    const auto least = std::min_element(load.begin(), load.end());
    rank_of[i] = static_cast<int>(least - load.begin());
    *least += std::max(expected_zones[i], 1.0);
  }
  return rank_of;
}

std::vector<BlockTetrahedra>
mesh_convex_blocks_on_ranks(const BlockModel& m, const std::vector<unsigned int>& which,
                            const EdgeLengthAt& size, ConvexMesher mesher,
                            const std::vector<double>& expected_zones, MPI_Comm comm)
{
  int ranks = 1, rank = 0;
  MPI_Comm_size(comm, &ranks);
  MPI_Comm_rank(comm, &rank);
  if (ranks < 2)
    return mesh_convex_blocks_with(m, which, size, mesher);
  if (expected_zones.size() != which.size())
    throw std::logic_error("mesh_convex_blocks_on_ranks: one expected zone count per block");
  const std::vector<int> rank_of = meshing_ranks(expected_zones, ranks);

  // This rank's blocks, in the order of `which`, within one gmsh session;
  // the first that fails stops it.
  std::vector<BlockTetrahedra> out(which.size());
  long long failed = LLONG_MAX;
  std::string message;
  {
    std::unique_ptr<GmshSession> session;
    if (mesher != ConvexMesher::lattice)
      session = std::make_unique<GmshSession>();
    for (std::size_t i = 0; i < which.size() && failed == LLONG_MAX; ++i)
      if (rank_of[i] == rank)
        try
        {
          out[i] = std::move(mesh_convex_blocks_with(m, {which[i]}, size, mesher)[0]);
        }
        catch (const InputError& e)
        {
          failed = static_cast<long long>(i);
          message = e.what();
        }
  }
  // Every rank learns the first block that failed, on any rank, and throws
  // its message.
  long long first = LLONG_MAX;
  MPI_Allreduce(&failed, &first, 1, MPI_LONG_LONG, MPI_MIN, comm);
  if (first != LLONG_MAX)
  {
    std::vector<char> text(message.begin(), message.end());
    broadcast_bytes(text, rank_of[static_cast<std::size_t>(first)], comm);
    throw InputError(std::string(text.begin(), text.end()));
  }

  // Each rank's meshes to every rank: per block its point and zone counts,
  // then its points and zones.
  for (int r = 0; r < ranks; ++r)
  {
    std::vector<char> bytes;
    if (r == rank)
      for (std::size_t i = 0; i < which.size(); ++i)
        if (rank_of[i] == r)
        {
          const std::uint64_t counts[2] = {out[i].point.size(), out[i].tet.size()};
          put(bytes, counts, 2);
          put(bytes, out[i].point.data(), out[i].point.size());
          put(bytes, out[i].tet.data(), out[i].tet.size());
        }
    broadcast_bytes(bytes, r, comm);
    if (r == rank)
      continue;
    std::size_t at = 0;
    for (std::size_t i = 0; i < which.size(); ++i)
      if (rank_of[i] == r)
      {
        std::uint64_t counts[2];
        take(bytes, at, counts, 2);
        out[i].point.resize(counts[0]);
        out[i].tet.resize(counts[1]);
        take(bytes, at, out[i].point.data(), out[i].point.size());
        take(bytes, at, out[i].tet.data(), out[i].tet.size());
      }
    if (at != bytes.size())
      throw std::logic_error("mesh_convex_blocks_on_ranks: a rank sent more than its meshes");
  }
  return out;
}

} // namespace talus
