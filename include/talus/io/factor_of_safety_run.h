#pragma once

#include <talus/model/block_model.h>
#include <talus/scene/scene.h>

#include <mpi.h>

#include <string>

namespace talus
{

/// 'Mode' = factor of safety: runs the strength-reduction search on the
/// built `model` (solver/factor_of_safety.h), prints one summary line per
/// trial and the factor of safety, and writes the failure mechanism (the
/// end of the last unstable trial) as the run's output under `prefix`
/// (<prefix>_blocks.pvd, _contacts.pvd, _zones.pvd with deformable blocks,
/// _history.csv of that trial). Returns the exit code (0); throws
/// InputError (exit code 1) when no bracket is found between F = 0.01 and
/// 100. With `comm` (MPI_COMM_NULL: one rank) the search runs on its ranks
/// (find_factor_of_safety_on_ranks), with the serial run's summary and
/// files: rank 0 prints and writes, the mechanism of a trial another rank
/// ran from the state that rank sends.
int run_factor_of_safety(Scene& scene, BlockModel& model, const std::string& prefix,
                         MPI_Comm comm = MPI_COMM_NULL);

struct TrialView;
/// The end of an unstable trial as one frame of each series under
/// `prefix`: blocks (displacement since the trial's start, velocity,
/// rotation), contacts and zones (displacement, velocity, plastic state).
void write_mechanism(const Scene& scene, const TrialView& view, const std::string& prefix);

} // namespace talus
