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
/// Sums over the whole mesh (the unbalanced ratio, the energy account, a
/// support's reaction) add each rank's owned gridpoints and counted zones
/// and are reduced; their order of addition is not the one of one run, so
/// they match it to rounding. Nodal mixed discretization carries the
/// owners' gridpoint averages to the ghosts (DeformableSolver).
struct GridpointShare
{
  MPI_Comm comm = MPI_COMM_WORLD;
  unsigned int n_owned = 0;
  std::vector<unsigned int> ghost_index;
  /// Per local gridpoint, its number in the whole mesh: what a summary
  /// names, and the order in which ties between ranks are broken (the
  /// lowest number, as a loop over the whole mesh keeps the first).
  std::vector<unsigned int> whole_gridpoint;

  /// Whether this rank counts a zone whose first corner is local gridpoint
  /// `first_corner` in a sum over the whole mesh: each zone once, by the
  /// owner of its first corner (which holds it).
  bool counts(unsigned int first_corner) const { return first_corner < n_owned; }
};

} // namespace talus
