#pragma once

#include <mpi.h>

#include <functional>
#include <vector>

namespace talus
{

class DeformableSolver;

/// Deformable blocks that change rank (issue 24): the state of zones split
/// among the ranks of `comm` moves from `from`, this rank's solver before
/// (its local zones being the whole mesh's `from_zone`), to `to`, built on
/// a new split of the same whole mesh (local zones `to_zone`; gridpoints by
/// its GridpointShare). Each rank asks the rank that owned each gridpoint
/// and each zone it now holds before (`old_owner_of_gridpoint`,
/// `old_owner_of_zone`, by their numbers in the whole mesh) for its values,
/// ghost gridpoints included, and `to` takes them
/// (DeformableSolver::take_moved_state): the values are those the whole
/// model had, bit for bit. Two rounds of point-to-point messages between
/// the ranks that trade, sized by one MPI_Alltoall each. Collective.
void move_zone_state(const DeformableSolver& from, const std::vector<unsigned int>& from_zone,
                     DeformableSolver& to, const std::vector<unsigned int>& to_zone,
                     const std::function<int(unsigned int)>& old_owner_of_gridpoint,
                     const std::function<int(unsigned int)>& old_owner_of_zone, MPI_Comm comm);

/// A stage's factor of safety on ranks (whose trials are runs of the whole
/// model): `whole`, a solver of the whole mesh on every rank (as one run
/// meshes it), takes the state of the zones split among the ranks of
/// `comm` (`split`, this rank's, its local zones being the whole mesh's
/// `split_zone`) as one run would hold it now: every gridpoint's and zone's
/// values from its owner (one MPI_Allgatherv), and the energy account's
/// terms summed over the ranks. Collective.
void gather_whole_zones(const DeformableSolver& split, const std::vector<unsigned int>& split_zone,
                        DeformableSolver& whole, MPI_Comm comm);

} // namespace talus
