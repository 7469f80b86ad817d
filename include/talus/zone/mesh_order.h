#pragma once

#include <talus/zone/tet_mesh.h>

#include <cstdint>
#include <functional>
#include <vector>

namespace talus
{

/// The order of zones and gridpoints a mesher leaves.
enum class MeshOrder
{
  /// As the generator made them: deal.II's cells (the brick generator's
  /// hexahedra lexicographic, x fastest; refined blocks child by child; a
  /// gmsh file's elements), gridpoints in first use by those zones.
  generator,
  /// Slabs (the default): zones by the cells of a lattice of the zone size,
  /// lexicographic (z slowest, x fastest), so that the zones sweep the
  /// block in rows along x, rows in slabs of one z; gridpoints in first use
  /// by the zones so sorted. Keeps the brick generator's order (zones and
  /// gridpoints) and puts any other mesh (refined blocks, gmsh files) in
  /// the same kind of order.
  slabs,
  /// Zones along the 3D Hilbert curve through their centroids, gridpoints
  /// in first use. More compact than slabs, but the explicit cycle ran
  /// 10-15 % slower with it on the machine measured (gathers in a curve
  /// defeat the hardware prefetcher, which follows the slabs' long rows).
  hilbert,
  /// For nodal mixed discretization: the slabs' lattice cut across into
  /// columns of column_cells x column_cells cells that run along z. First
  /// the seam zones (those with a gridpoint that a zone of a later column
  /// also uses) in slab order, then the other zones column by column, each
  /// column in slabs. The sums of eq. 69 at a gridpoint away from the seams
  /// are then complete one slab of its column (some 5,000 zones) after they
  /// begin, instead of one slab of the whole block, so the zones can keep
  /// their strain increments between the two stages of nodal mixed
  /// discretization (DeformableSolver::plan_nodal_mixed); the seam zones,
  /// 6 % of a wide brick's, take them twice. A block no wider than one
  /// column is in slabs.
  columns
};

/// The order of each block's zones, given the block's number (as in
/// TetMesh::zone_block): talus puts the blocks with nodal mixed
/// discretization in columns and the others in slabs.
using BlockMeshOrder = std::function<MeshOrder(unsigned int block)>;

/// How a TetMesh was renumbered: new number -> old number.
struct MeshPermutation
{
  std::vector<unsigned int> old_zone, old_gridpoint;
};

/// Position of the point (x, y, z), each coordinate an integer below 2^21,
/// along the 3D Hilbert curve of order 21 (a 63-bit index): consecutive
/// indices are cells that share a face.
std::uint64_t hilbert_index(std::uint32_t x, std::uint32_t y, std::uint32_t z);

/// Puts zones and gridpoints in `order` (nothing to do for generator) for
/// memory locality in the explicit cycle, whose zone loop gathers its
/// gridpoints: zones that are neighbours in space become mostly neighbours
/// in memory, and so do the gridpoints they share. Block by block: blocks
/// keep their order, only zones within a run of one block move, and the
/// gridpoints are numbered in the order the zones, so sorted, first use
/// them (corners, then 10-node midpoints), which keeps each block's
/// gridpoints together.
///
/// A hexahedral zone (TetMesh::hex_first_zone) moves as one unit, its ten
/// tetrahedra together and in their order. Every array of the mesh is
/// renumbered alike (faces, face zones, 10-node midpoints, hexahedra and
/// the second overlay's faces); the order of faces is kept. Deterministic
/// (ties keep the old order); applying it twice changes nothing more.
/// Returns the permutations applied.
///
/// `column_cells`, for columns only: 32 measured best with 48 and 64 close
/// (benchmark_zone_cycle at 5 million zones, nodal mixed against plain
/// zones in slabs: 1.19-1.22 against 1.24 at 24 and 1.31 at 16).
MeshPermutation order_for_locality(TetMesh& mesh, MeshOrder order = MeshOrder::slabs,
                                   unsigned int column_cells = 32);

/// The same with an order for each block (generator: the block's zones
/// keep their order).
MeshPermutation order_for_locality(TetMesh& mesh, const BlockMeshOrder& order_of_block,
                                   unsigned int column_cells = 32);

} // namespace talus
