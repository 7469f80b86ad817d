// The cell space cut for ranks from work spread over MPI processes
// (CellPartition with sum_over_processes, as RankBalance cuts it again):
// each process passes only its own points, the processes add their cell
// slabs' work level by level (sum_exactly_over_ranks), and every process
// must make the cuts one process makes from all the points: the same
// partition numbers (cuts, work per rank), bit for bit, and the same owner
// for every point; while the numbers added over the processes stay far
// fewer than the points (no process gathers them).
//
// The points: 100,000 crowded into a corner of a 100 m x 50 m x 20 m box
// (a half-normal cloud) on 1 m cells, each with a work that is a multiple
// of 2^-10 between 1/16 and 4, so that every sum is exact in either way of
// adding; process p holds the points i with i mod P = p. Cut for 2, 3, 7
// and 16 ranks (whatever the number of processes).

#include <talus/base/parallel_environment.h>
#include <talus/contact/cell_partition.h>
#include <talus/run/rank_balance.h>

#include <mpi.h>

#include <cstdio>
#include <random>
#include <vector>

#include "../tests.h"

using namespace talus;

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  int process = 0, processes = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &process);
  MPI_Comm_size(MPI_COMM_WORLD, &processes);

  const Box domain{Vec3::Zero(), Vec3(100.0, 50.0, 20.0)};
  std::mt19937_64 random(20261127);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_int_distribution<int> units(64, 4096);
  std::vector<Vec3> all_points, my_points;
  std::vector<double> all_work, my_work;
  for (int i = 0; i < 100000; ++i)
  {
    const Vec3 x(std::min(99.9, std::abs(normal(random)) * 15.0),
                 std::min(49.9, std::abs(normal(random)) * 8.0),
                 std::min(19.9, std::abs(normal(random)) * 5.0));
    const double w = units(random) / 1024.0;
    all_points.push_back(x);
    all_work.push_back(w);
    if (i % processes == process)
    {
      my_points.push_back(x);
      my_work.push_back(w);
    }
  }
  if (process == 0)
    std::printf("100000 points in a corner of the box, on %d processes\n", processes);
  for (unsigned int ranks : {2u, 3u, 7u, 16u})
  {
    const CellPartition whole(domain, domain.lo, Vec3::Ones(), all_points, all_work, ranks);
    std::size_t added = 0;
    unsigned int levels = 0;
    const CellPartition spread(domain, domain.lo, Vec3::Ones(), my_points, my_work, ranks,
                               [&](std::vector<double>& numbers)
                               {
                                 added += numbers.size();
                                 ++levels;
                                 sum_exactly_over_ranks(numbers, MPI_COMM_WORLD);
                               });
    int differing = whole.numbers() != spread.numbers();
    for (const Vec3& x : all_points)
      differing += whole.owner(x) != spread.owner(x);
    int all_differing = 0;
    MPI_Allreduce(&differing, &all_differing, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
    if (process == 0)
    {
      std::printf("%2u ranks: the one-process partition and owners, bit for bit: %s; imbalance "
                  "%.4f\n",
                  ranks, talus_test::verdict(all_differing == 0), spread.imbalance());
      std::printf("  numbers added over the processes in %u levels, below a tenth of the "
                  "points: %s\n",
                  levels, talus_test::verdict(added * 10 < all_points.size()));
      std::fprintf(stderr, "%u ranks: %zu numbers added, %d differing\n", ranks, added,
                   all_differing);
    }
  }
  return 0;
}
