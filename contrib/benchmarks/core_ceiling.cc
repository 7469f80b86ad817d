// The machine's own ceiling for strong scaling (issue 24): how much faster
// P ranks do P times one rank's work than one rank does its share, for
// work that shares nothing, so that talus's speed-ups on ranks can be read
// against what these cores give at all.
//
// Two loops, each timed first on rank 0 alone (the other ranks sleep: they
// poll a barrier every millisecond instead of spinning in it) and then on
// every rank at once, the same work each:
// - arithmetic: chains of multiply-adds on 4,096 doubles held in the
//   first-level cache (no memory traffic);
// - memory: c = a + s b over three arrays of 128 MB each, far beyond the
//   last-level cache (as the zone cycle's arrays at a million zones).
// The ceiling is P t_1 / t_P: P for cores that share nothing. A VM's cores
// share their host's memory channels (and other guests use them too): on
// the 2-core AMD EPYC guest, 2026-11-27, five runs within an hour gave
// 1.95-2.03 for the arithmetic and 1.62-1.90 for the memory.
//   cmake --build build --target benchmark_core_ceiling
//   mpirun -np 2 build/contrib/benchmarks/benchmark_core_ceiling [seconds]
// Default: about 15 s per timing (4 timings).

#include "benchmark_arguments.h"
#include "rank_figures.h"

#include <mpi.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <thread>
#include <vector>

using rank_figures::seconds_since;
using rank_figures::wait_for_all;

namespace
{
/// The arrays of one loop, made before it is timed.
struct Arrays
{
  std::vector<double> a, b, c;
  explicit Arrays(std::size_t n) : a(n, 1.0), b(n, 2.0), c(n, 0.5)
  {
    for (std::size_t i = 0; i < n; ++i)
      a[i] = 1e-3 * double(1 + i % 7);
  }
};

/// `passes` passes of the arithmetic loop on 4,096 doubles; returns a
/// value that depends on all of it (so that none of it is optimised away).
double arithmetic(Arrays& x, unsigned long passes)
{
  for (unsigned long p = 0; p < passes; ++p)
    for (std::size_t i = 0; i < x.c.size(); ++i)
      x.c[i] = x.c[i] * 0.999999 + x.a[i];
  return x.c[17];
}

/// `passes` passes of the memory loop over three arrays of 128 MB.
double memory(Arrays& x, unsigned long passes)
{
  for (unsigned long p = 0; p < passes; ++p)
    for (std::size_t i = 0; i < x.c.size(); ++i)
      x.c[i] = x.a[i] + 1.0001 * x.b[i];
  return x.c[17];
}

/// P t_1 / t_P for `work`, whose pass count is chosen on rank 0 alone to
/// last about `seconds`.
double ceiling(double (*work)(Arrays&, unsigned long), std::size_t n, double seconds, MPI_Comm comm,
               double& t_one, double& t_all)
{
  Arrays x(n);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  unsigned long passes = 1;
  double sink = 0.0;
  if (rank == 0)
  {
    // The pass count: doubled until one timing takes a tenth of `seconds`.
    for (;;)
    {
      const auto start = std::chrono::steady_clock::now();
      sink += work(x, passes);
      const double t = seconds_since(start);
      if (t > 0.1 * seconds)
      {
        passes = static_cast<unsigned long>(double(passes) * seconds / t) + 1;
        break;
      }
      passes *= 2;
    }
    const auto start = std::chrono::steady_clock::now();
    sink += work(x, passes);
    t_one = seconds_since(start);
  }
  wait_for_all(comm);
  MPI_Bcast(&passes, 1, MPI_UNSIGNED_LONG, 0, comm);
  MPI_Barrier(comm);
  const auto start = std::chrono::steady_clock::now();
  sink += work(x, passes);
  const double mine = seconds_since(start);
  MPI_Allreduce(&mine, &t_all, 1, MPI_DOUBLE, MPI_MAX, comm);
  if (sink == 42.0) // never: keeps the work
    std::printf(" ");
  return ranks * t_one / t_all;
}
} // namespace

int main(int argc, char** argv)
{
  MPI_Init(&argc, &argv);
  const MPI_Comm comm = MPI_COMM_WORLD;
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  const double seconds =
      argc > 1 ? double(talus::whole_argument(argv[0], argv[1], "the seconds per timing", 1, 3600))
               : 15.0;
  double t1 = 0.0, tp = 0.0;
  const double arithmetic_ceiling = ceiling(arithmetic, 4096, seconds, comm, t1, tp);
  const double a1 = t1, ap = tp;
  const double memory_ceiling = ceiling(memory, std::size_t(16) << 20, seconds, comm, t1, tp);
  if (rank == 0)
  {
    const std::time_t now = std::time(nullptr);
    char date[32];
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
    std::printf("%s, %s; %d ranks\n", rank_figures::cpu_model().c_str(), date, ranks);
    std::printf(
        "arithmetic (L1):    one rank %.2f s, %d ranks at once %.2f s: ceiling %.2f of %d\n", a1,
        ranks, ap, arithmetic_ceiling, ranks);
    std::printf(
        "memory (3 x 128 MB): one rank %.2f s, %d ranks at once %.2f s: ceiling %.2f of %d\n", t1,
        ranks, tp, memory_ceiling, ranks);
  }
  MPI_Finalize();
  return 0;
}
