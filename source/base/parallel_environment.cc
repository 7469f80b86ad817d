#include <talus/base/parallel_environment.h>

#include <deal.II/base/mpi.h>

namespace talus
{

struct ParallelEnvironment::Impl
{
  Impl(int& argc, char**& argv) : mpi(argc, argv, 1) {}
  dealii::Utilities::MPI::MPI_InitFinalize mpi; ///< one thread per rank: the cycle is ours to order
};

ParallelEnvironment::ParallelEnvironment(int& argc, char**& argv)
    : impl_(std::make_unique<Impl>(argc, argv))
{
}

ParallelEnvironment::~ParallelEnvironment() = default;

} // namespace talus
