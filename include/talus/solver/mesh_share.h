#pragma once

#include <talus/geometry/plane.h>
#include <talus/zone/gridpoint_share.h>
#include <talus/zone/tet_mesh.h>

#include <mpi.h>

#include <vector>

namespace talus
{

/// A rank's part of a zone mesh (4-node, 10-node or hexahedral zones) split among MPI ranks by its
/// gridpoints (issue 24): the zones with a gridpoint the rank owns, in the
/// whole mesh's zone order (so that an owned gridpoint sums its zones'
/// forces as in one run), on the rank's own gridpoints in the mesh's order
/// and then the ghosts, ordered by their numbers in the whole model's
/// vectors (GridpointShare: each rank's gridpoints numbered together, rank
/// by rank). Boundary faces of the zones held come along.
struct MeshShare
{
  TetMesh mesh;
  GridpointShare share;
  std::vector<unsigned int> gridpoint; ///< per local gridpoint: its number in the whole mesh
  std::vector<unsigned int> zone;      ///< per local zone: its number in the whole mesh
  /// Per local boundary face, then second-overlay face: its number in the
  /// whole mesh's list of the same kind.
  std::vector<unsigned int> face, second_overlay_face;
};

/// The rank of each gridpoint of `mesh` among `ranks`: the region of a
/// CellPartition of `domain` (cells of `cell_size`, m) that holds it,
/// balanced by the zones around the gridpoints (a quarter of a zone each;
/// none for the zones `removed` marks, per zone of `mesh`, when given:
/// excavated zones do no work).
std::vector<unsigned int> gridpoint_owners(const TetMesh& mesh, const Box& domain, double cell_size,
                                           unsigned int ranks,
                                           const std::vector<char>* removed = nullptr);

/// The part of `whole` that rank `rank` of `ranks` holds, with `owner[g]`
/// the rank of each gridpoint. Every rank must pass the same `owner`.
/// `also_ghosts` (per gridpoint of `whole`, optional): gridpoints held as
/// ghosts besides those of the zones held, without their zones (the
/// surfaces of other ranks' deformable blocks near this rank's blocks).
/// A zone is held when one of its nodes is owned; a hexahedral zone's ten
/// tetrahedra are held together, when one of its eight corners is owned.
MeshShare share_mesh(const TetMesh& whole, const std::vector<unsigned int>& owner,
                     unsigned int rank, unsigned int ranks, MPI_Comm comm,
                     const std::vector<char>* also_ghosts = nullptr);

} // namespace talus
