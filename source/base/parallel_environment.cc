#include <talus/base/parallel_environment.h>

#include <deal.II/base/mpi.h>

#include <dlfcn.h>

namespace talus
{

struct ParallelEnvironment::Impl
{
  Impl(int& argc, char**& argv) : mpi(argc, argv, 1) {}
  dealii::Utilities::MPI::MPI_InitFinalize mpi; ///< one thread per rank: the cycle is ours to order
};

namespace
{

/// One thread in a threaded BLAS (OpenBLAS), if the one linked is: its
/// threads are not ours to order, and under an address-space limit (ulimit
/// -v) one of them was seen retrying a failed allocation forever after the
/// run had ended. Looked up at run time, so that any BLAS links.
void single_threaded_blas()
{
  using SetThreads = void (*)(int);
  for (const char* name : {"openblas_set_num_threads", "goto_set_num_threads"})
    if (void* f = dlsym(RTLD_DEFAULT, name))
      reinterpret_cast<SetThreads>(f)(1);
}

} // namespace

ParallelEnvironment::ParallelEnvironment(int& argc, char**& argv)
    : impl_((single_threaded_blas(), std::make_unique<Impl>(argc, argv)))
{
}

ParallelEnvironment::~ParallelEnvironment() = default;

std::unique_ptr<ParallelEnvironment> ParallelEnvironment::unless_running()
{
  int running = 0;
  MPI_Initialized(&running);
  if (running)
    return nullptr;
  int argc = 1;
  char name[] = "talus";
  char* args[] = {name, nullptr};
  char** argv = args;
  return std::make_unique<ParallelEnvironment>(argc, argv);
}

} // namespace talus

namespace talus
{

void abort_ranks(int code)
{
  int started = 0;
  MPI_Initialized(&started);
  if (started)
    MPI_Abort(MPI_COMM_WORLD, code);
}

} // namespace talus
