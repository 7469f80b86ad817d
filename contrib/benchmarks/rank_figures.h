#pragma once

// What the benchmarks of runs split among ranks print about the machine
// and its MPI: the CPU model, wall time, and MPI between ranks 0 and 1
// (latency, bandwidth, one MPI_Allreduce), the inputs of their models of
// larger runs.

#include <malloc.h>
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace rank_figures
{

/// Now, as "YYYY-MM-DD HH:MM UTC", for the benchmarks' tables.
inline std::string date_utc()
{
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  return date;
}

inline std::string cpu_model()
{
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0)
      return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

inline double seconds_since(std::chrono::steady_clock::time_point t)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

/// Returns when every rank has come here, sleeping between polls so that
/// a waiting rank leaves its core to the ones still working (a rank
/// spinning in MPI_Barrier would take a share of a core its host may
/// give to the one that works). Collective.
inline void wait_for_all(MPI_Comm comm)
{
  MPI_Request request;
  MPI_Ibarrier(comm, &request);
  for (int done = 0; !done;)
  {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (!done)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

/// Runs `steps` steps of `solver` on every rank at once (from a barrier)
/// and returns the slowest rank's time, s, on every rank. Collective.
template <class Solver>
double slowest_steps(Solver& solver, unsigned long steps, MPI_Comm comm)
{
  MPI_Barrier(comm);
  const auto start = std::chrono::steady_clock::now();
  for (unsigned long k = 0; k < steps; ++k)
    solver.step();
  double mine = seconds_since(start), slowest = 0.0;
  MPI_Allreduce(&mine, &slowest, 1, MPI_DOUBLE, MPI_MAX, comm);
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::fprintf(stderr, "rank %d, the same work on every rank at once: %.3f s\n", rank, mine);
  return slowest;
}

/// The median of `values` (0 when empty).
inline double median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  const std::size_t k = values.size();
  return k == 0 ? 0.0 : k % 2 == 1 ? values[k / 2] : 0.5 * (values[k / 2 - 1] + values[k / 2]);
}

/// Resident memory of this process now (bytes), after handing freed heap
/// back to the system.
inline double resident_bytes()
{
  malloc_trim(0);
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmRSS:", 0) == 0)
      return 1024.0 * std::strtod(line.c_str() + 6, nullptr);
  return 0.0;
}

/// Every rank's `mine`, one after the other in rank order, on rank 0
/// (empty elsewhere; collective).
inline std::vector<double> gather_on_rank_0(const std::vector<double>& mine, MPI_Comm comm)
{
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  int count = static_cast<int>(mine.size());
  std::vector<int> counts(ranks), starts(ranks, 0);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  for (int r = 1; r < ranks; ++r)
    starts[r] = starts[r - 1] + counts[r - 1];
  std::vector<double> all(rank == 0 ? starts.back() + counts.back() : 0);
  MPI_Gatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), starts.data(), MPI_DOUBLE,
              0, comm);
  return all;
}

struct MpiFigures
{
  double latency = 0.0;   ///< s, one way, 8 bytes
  double bandwidth = 0.0; ///< bytes/s, 1 MB messages
  double allreduce = 0.0; ///< s, one MPI_Allreduce of a double
};

/// Ping-pong between ranks 0 and 1 (8-byte and 1 MB messages) and a run of
/// MPI_Allreduce on all ranks of `comm` (collective).
inline MpiFigures measure_mpi(MPI_Comm comm)
{
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  const auto ping_pong = [&](std::size_t bytes, int trips)
  {
    std::vector<char> buffer(bytes);
    MPI_Barrier(comm);
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < trips && ranks > 1; ++k)
      if (rank == 0)
      {
        MPI_Send(buffer.data(), int(bytes), MPI_CHAR, 1, 7, comm);
        MPI_Recv(buffer.data(), int(bytes), MPI_CHAR, 1, 7, comm, MPI_STATUS_IGNORE);
      }
      else if (rank == 1)
      {
        MPI_Recv(buffer.data(), int(bytes), MPI_CHAR, 0, 7, comm, MPI_STATUS_IGNORE);
        MPI_Send(buffer.data(), int(bytes), MPI_CHAR, 0, 7, comm);
      }
    return seconds_since(t0) / (2.0 * trips); // one way
  };
  MpiFigures f;
  f.latency = ping_pong(8, 2000);
  f.bandwidth = 1e6 / (ping_pong(1000000, 200) - f.latency);
  double x = rank;
  MPI_Barrier(comm);
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < 2000; ++k)
    MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_DOUBLE, MPI_MAX, comm);
  f.allreduce = seconds_since(t0) / 2000.0;
  return f;
}

} // namespace rank_figures
