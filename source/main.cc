// talus: three-dimensional distinct element code for jointed rock.
// Usage: talus scene.prm, or talus --restart checkpoint [scene.prm]

#include <talus/base/exceptions.h>
#include <talus/base/memory.h>
#include <talus/base/parallel_environment.h>
#include <talus/io/checkpoint.h>
#include <talus/io/rank_checkpoint.h>
#include <talus/run/simulation.h>

#include <talus_revision.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <new>

namespace
{

constexpr const char* usage =
    "usage: talus SCENE.prm\n"
    "       talus --check SCENE.prm\n"
    "       talus --restart CHECKPOINT [SCENE.prm]\n"
    "       talus --version\n"
    "  Builds the block model the parameter file describes, writes it\n"
    "  for ParaView into the output folder it names, and prints a summary.\n"
    "  Shipped scenes are in the parameters/ folder.\n"
    "  --check reads, builds and checks the scene (blocks, zones, solvers)\n"
    "  and writes nothing: exit code 0 when it would run, 1 when not.\n"
    "  --restart continues a run from its checkpoint (<Base name>_checkpoint.bin,\n"
    "  written every 'Checkpoint interval' steps and on SIGINT/SIGTERM) with the\n"
    "  parameter file it was written for (or SCENE.prm, the same file moved);\n"
    "  a run on N ranks continues with mpirun -np N talus --restart CHECKPOINT.\n";

/// The number of ranks a launcher started this process among (Open MPI's
/// mpirun, or a PMI launcher), and this one's rank, read from the
/// environment: MPI itself starts only when deformable blocks need PETSc.
int launched_ranks(int& rank)
{
  const auto number = [](const char* name)
  {
    const char* value = std::getenv(name);
    return value != nullptr ? std::atoi(value) : -1;
  };
  rank = std::max({number("OMPI_COMM_WORLD_RANK"), number("PMI_RANK"), 0});
  return std::max({number("OMPI_COMM_WORLD_SIZE"), number("PMI_SIZE"), 1});
}

} // namespace

int main(int argc, char** argv)
{
  // Each summary line reaches a redirected standard output as it is
  // printed, not at the end of the run.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  if (argc == 2 && std::strcmp(argv[1], "--version") == 0)
  {
    std::printf("talus %s (git %s)\n", TALUS_VERSION, TALUS_GIT_REVISION);
    return 0;
  }
  const bool check = argc == 3 && std::strcmp(argv[1], "--check") == 0;
  const bool restart = (argc == 3 || argc == 4) && std::strcmp(argv[1], "--restart") == 0;
  if ((argc != 2 && !restart && !check) || std::strcmp(argv[1], "--help") == 0 ||
      std::strcmp(argv[1], "-h") == 0)
  {
    std::fputs(usage, argc == 2 ? stdout : stderr);
    return argc == 2 ? 0 : 1;
  }
  std::string scene_file = check ? argv[2] : argv[1];
  // Under 'mpirun -np N' every rank runs its share of the model (rigid
  // scenes; others are refused with a message). Rank 0 prints the summary
  // and writes the run's files; the other ranks print nothing.
  int rank = 0;
  const int ranks = launched_ranks(rank);
  std::unique_ptr<talus::ParallelEnvironment> mpi;
  if (ranks > 1)
  {
    mpi = std::make_unique<talus::ParallelEnvironment>(argc, argv);
    if (rank != 0 && std::freopen("/dev/null", "w", stdout) == nullptr)
      return 1;
  }
  // On ranks: an error of the input or the geometry is every rank's
  // (they read and build the same), so rank 0 says it; any other stops the
  // rank that met it, which says it and stops the others (MPI_Abort).
  const auto stop_ranks = [&](int code)
  {
    if (ranks > 1)
    {
      std::fflush(stderr);
      talus::abort_ranks(code);
    }
    return code;
  };
  const bool says = rank == 0;
  try
  {
    if (check)
      return talus::Simulation(scene_file, "", true).run();
    std::string restart_from;
    if (restart)
    {
      // On N ranks, this rank's file of the set (io/rank_checkpoint.h).
      restart_from = talus::checkpoint_of_this_rank(argv[2]);
      // The parameter file may be named (a moved project); else the checkpoint's.
      scene_file =
          argc == 4 ? std::string(argv[3]) : talus::checkpoint_parameter_file(restart_from);
    }
    const int code = talus::Simulation(scene_file, restart_from).run();
    // A summary that could not be written (a full disk) is a failed run.
    if (std::fflush(stdout) != 0 || std::ferror(stdout))
    {
      std::fprintf(stderr, "talus: error: standard output could not be written (%s)\n",
                   std::strerror(errno));
      return 1;
    }
    return code;
  }
  catch (const talus::RunInterrupted& e)
  {
    std::fflush(stdout); // the summary so far, then the message
    if (says)
      std::fprintf(stderr, "talus: %s\n", e.what());
    // On ranks every rank stopped at the same step, its file written.
    return e.exit_code();
  }
  catch (const talus::InputError& e)
  {
    std::fflush(stdout); // the summary so far, then the message
    if (says)
      std::fprintf(stderr, "talus: error: %s\n", e.what());
  }
  catch (const talus::DivergenceError& e)
  {
    std::fflush(stdout); // the summary so far, then the message
    if (ranks > 1)
      std::fprintf(stderr, "talus: error in %s (rank %d of %d): %s\n", scene_file.c_str(), rank,
                   ranks, e.what());
    else
      std::fprintf(stderr,
                   "talus: error in %s: %s (the state of the last good step is written to the "
                   "output folder)\n",
                   scene_file.c_str(), e.what());
    return stop_ranks(3);
  }
  catch (const talus::GeometryError& e)
  {
    std::fflush(stdout); // the summary so far, then the message
    if (says)
      std::fprintf(stderr, "talus: error in %s: %s\n", scene_file.c_str(), e.what());
  }
  catch (const std::bad_alloc&)
  {
    // The estimates of scene_checks.h let the model start; it needed more.
    std::fflush(stdout); // the summary so far, then the message
    std::fprintf(stderr,
                 "talus: error in %s: out of memory (this machine has %s left); make the model "
                 "smaller: a larger 'Edge length' or 'Spacing', fewer deformable groups\n",
                 scene_file.c_str(), talus::memory_text(talus::available_memory()).c_str());
    return stop_ranks(1);
  }
  catch (const std::exception& e)
  {
    std::fflush(stdout); // the summary so far, then the message
    std::fprintf(stderr, "talus: internal error (please report it): %s\n", e.what());
    return stop_ranks(2);
  }
  return 1;
}
