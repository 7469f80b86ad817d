// Strong scaling of the rigid engine split among ranks (issue 24): the
// settling scene of rigid_settling.cc (n x n x n unit cubes on a fixed
// floor layer, static with local damping), first whole on rank 0 alone
// while the other ranks wait, then split among all ranks by a CellPartition
// with two layers of ghosts refreshed after every step (GhostExchange) and
// owners that follow the blocks (BlockMigration's check after every step).
// Prints both rates, the speed-up measured in this one run, the blocks each
// rank holds and the exchange volume per step.
//   cmake --build build --target benchmark_rigid_ranks
//   mpirun -np 2 build/contrib/benchmarks/benchmark_rigid_ranks [n] [steps]

#include "benchmark_arguments.h"
#include "settling_cubes.h"

#include <talus/base/parallel_environment.h>
#include <talus/contact/block_decomposition.h>
#include <talus/geometry/block_generator.h>
#include <talus/model/block_model.h>
#include <talus/solver/block_migration.h>
#include <talus/solver/ghost_exchange.h>
#include <talus/solver/rigid_solver.h>

#include <mpi.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <string>

using namespace talus;

namespace
{

std::string cpu_model()
{
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0)
      return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

double seconds_since(std::chrono::steady_clock::time_point t)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

} // namespace

int main(int argc, char** argv)
{
  ParallelEnvironment mpi(argc, argv);
  const MPI_Comm comm = MPI_COMM_WORLD;
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  const unsigned int n =
      argc > 1 ? whole_argument(argv[0], argv[1], "the cubes per side (first argument)", 2, 100)
               : 30;
  const unsigned long steps =
      argc > 2 ? whole_argument(argv[0], argv[2], "the step count (second argument)", 1, 1000000)
               : 200;

  SolverSettings s;
  BlockModel model = settling_cubes(n, steps, s);

  // 1. Whole, on rank 0 alone.
  double serial_seconds = 0.0;
  if (rank == 0)
  {
    BlockModel whole = model;
    RigidSolver solver(whole, 2650.0, s);
    const auto start = std::chrono::steady_clock::now();
    for (unsigned long k = 0; k < steps; ++k)
      solver.step();
    serial_seconds = seconds_since(start);
  }
  MPI_Barrier(comm);

  // 2. Split among the ranks.
  Box domain{Vec3::Zero(), Vec3(n, n, n + 1)};
  const CellPartition partition(domain, domain.lo, Vec3::Ones(), model.centroid,
                                std::vector<double>(model.n_blocks(), 1.0),
                                static_cast<unsigned int>(ranks));
  const double reach = 4.0 * s.contact.tolerance;
  RankBlocks mine = decompose_blocks(model, partition, static_cast<unsigned int>(rank), reach, 2);
  BlockModel local = model.subset(mine.local);
  RigidSolver solver(local, 2650.0, s);
  std::vector<char> ghost(mine.local.size());
  for (std::size_t i = 0; i < ghost.size(); ++i)
    ghost[i] = !mine.owned[i];
  solver.split_among_ranks(ghost, reductions_over(comm));
  GhostExchange exchange(mine, comm);
  BlockMigration migration(solver, mine, partition, reach, 2, comm);
  MPI_Barrier(comm);
  const auto start = std::chrono::steady_clock::now();
  for (unsigned long k = 0; k < steps; ++k)
  {
    solver.step();
    exchange.refresh(solver);
    migration.update(solver, mine);
  }
  const double mine_seconds = seconds_since(start);
  // The cost of one migration event, forced: the boxes gathered, the
  // ghosts chosen again, the blocks traded.
  MPI_Barrier(comm);
  const auto event_start = std::chrono::steady_clock::now();
  const RankBlocks at_start = mine;
  migration.migrate(solver, mine);
  const double event_seconds = seconds_since(event_start);
  // The cubes settle far less than the reach: the event, which knows only
  // the boxes near this rank's region, must choose what the whole model
  // gave at the start.
  int same = at_start.local == mine.local && at_start.owned == mine.owned &&
             at_start.send == mine.send && at_start.receive == mine.receive;
  MPI_Allreduce(MPI_IN_PLACE, &same, 1, MPI_INT, MPI_LAND, comm);
  double split_seconds = 0.0;
  MPI_Reduce(&mine_seconds, &split_seconds, 1, MPI_DOUBLE, MPI_MAX, 0, comm);
  std::fprintf(stderr, "rank %d: %u owned, %zu held, %.0f doubles sent per step, %.3f s\n", rank,
               mine.n_owned(), mine.local.size(), double(exchange.sent()), mine_seconds);
  long held = static_cast<long>(mine.local.size()), held_all = 0;
  double sent = static_cast<double>(exchange.sent()) * 8.0, sent_all = 0.0;
  MPI_Reduce(&held, &held_all, 1, MPI_LONG, MPI_SUM, 0, comm);
  MPI_Reduce(&sent, &sent_all, 1, MPI_DOUBLE, MPI_SUM, 0, comm);
  if (rank == 0)
  {
    const std::time_t now = std::time(nullptr);
    char date[32];
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
    std::printf("%s, %s; %d ranks\n", cpu_model().c_str(), date, ranks);
    std::printf("n = %u: %u blocks, %lu steps\n", n, model.n_blocks(), steps);
    std::printf("whole on one rank: %.3f s, %.0f block-cycles/s\n", serial_seconds,
                double(model.n_blocks()) * steps / serial_seconds);
    std::printf("split on %d ranks: %.3f s, %.0f block-cycles/s; speed-up %.2f\n", ranks,
                split_seconds, double(model.n_blocks()) * steps / split_seconds,
                serial_seconds / split_seconds);
    std::printf("blocks held %.3f times the model (ghosts); exchange %.0f bytes per step in "
                "all, %.0f bytes per block-step\n",
                double(held_all) / model.n_blocks(), sent_all, sent_all / model.n_blocks());
    std::printf("migration events %lu, blocks that changed owner %lu; one event forced "
                "after the steps took %.3f s on rank 0 and chose %s\n",
                migration.events() - 1, migration.owner_changes(), event_seconds,
                same ? "the blocks and lists of the start" : "OTHER BLOCKS OR LISTS (wrong)");
  }
}
