#pragma once

#include <memory>

namespace talus
{

/// MPI and PETSc for the length of a program (deal.II's MPI_InitFinalize):
/// create one at the top of main before any deformable block is built.
class ParallelEnvironment
{
public:
  ParallelEnvironment(int& argc, char**& argv);
  ~ParallelEnvironment();

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace talus
