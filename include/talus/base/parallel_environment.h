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

  /// One for this process alone (talus is serial), or none when MPI runs
  /// already (a test that holds its own around several runs).
  static std::unique_ptr<ParallelEnvironment> unless_running();

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Stops every rank of a run under MPI with exit code `code` (a rank that
/// met an error the others cannot know of); returns at once without MPI.
void abort_ranks(int code);

} // namespace talus
