#pragma once

#include <mpi.h>

#include <vector>

namespace talus
{

/// A rank's share of the gridpoints of a zone mesh split among MPI ranks
/// (issue 24). The rank's mesh holds every zone with a gridpoint it owns,
/// so that an owned gridpoint gathers the forces of all its zones, in the
/// whole mesh's zone order, and moves exactly as in one run. Its first
/// `n_owned` gridpoints are its own; the rest are ghosts, copies of
/// gridpoints that other ranks own, which it never moves: their positions
/// and velocities come from their owners after every motion.
///
/// The gridpoint vectors are PETSc vectors with ghost entries: rank r owns
/// the gridpoints numbered [offset_r, offset_r + n_owned) in the whole
/// model's vectors (offsets in rank order), and `ghost_index[k]` is that
/// number of the mesh's gridpoint n_owned + k, ascending.
///
/// Not split yet (DeformableSolver refuses or keeps a rank's part): nodal
/// mixed, 10-node and hexahedral zones and global adaptive damping are
/// refused; the unbalanced ratio and the energy account are this rank's.
struct GridpointShare
{
  MPI_Comm comm = MPI_COMM_WORLD;
  unsigned int n_owned = 0;
  std::vector<unsigned int> ghost_index;
};

} // namespace talus
