#pragma once

#include <talus/model/block_model.h>
#include <talus/zone/convex_block_mesher.h>
#include <talus/zone/edge_length_field.h>
#include <talus/zone/lattice_block_mesher.h>
#include <talus/zone/mesh_order.h>
#include <talus/zone/meshing_on_ranks.h>
#include <talus/zone/tet_mesh.h>
#include <talus/zone/zone_material.h>

#include <string>
#include <vector>

namespace dealii
{
template <int dim, int spacedim>
class Triangulation;
}

namespace talus
{

/// What meshing made, for the summary.
struct MeshReport
{
  unsigned int blocks = 0, zones = 0, gridpoints = 0, boundary_faces = 0;
  unsigned int hexes = 0;       ///< hexahedral zones of mixed discretization (10 of `zones` each)
  double zone_volume = 0.0;     ///< m^3, sum over zones (equals the blocks' volume)
  double smallest_height = 0.0; ///< m, smallest zone height (eq. 86)
  double largest_edge = 0.0;    ///< m, largest zone edge (eq. 86)
  /// Normalised radius ratio of the zones (1 regular, 0 flat): the
  /// smallest, the 1st percentile and the median; zones below 0.1, and the
  /// worst zone with its block.
  double quality_min = 0.0, quality_1 = 0.0, quality_median = 0.0;
  unsigned int poor_zones = 0;
  unsigned int worst_zone = 0, worst_block = 0;
  /// Blocks holding zones below 0.1, with how many each (at most the 20
  /// with most), for the summary.
  std::vector<std::pair<unsigned int, unsigned int>> poor_blocks;
};

/// Appends one block's tetrahedra (from the mesher) as the zones of block
/// `block`, with gridpoints of its own, and its boundary faces.
void append_tetrahedra(TetMesh& mesh, const BlockTetrahedra& tetrahedra, unsigned int block);

/// Appends every cell of `tria` (tetrahedra only) as a zone of block
/// `block`, with gridpoints of its own, and the block's boundary faces.
void append_tetrahedra(TetMesh& mesh, const dealii::Triangulation<3, 3>& tria, unsigned int block);

/// Reads a gmsh .msh file (format 2.2 or 4.1) of linear tetrahedra as the
/// zones of block `block`; the file's nodes become the block's gridpoints.
/// Throws InputError naming the file when it cannot be read or holds
/// other cells. Zones and gridpoints are then put in `order`.
TetMesh read_gmsh_block(const std::string& path, unsigned int block,
                        MeshOrder order = MeshOrder::slabs);

/// Counts and sizes of a mesh (throws if a zone has no volume).
MeshReport measure_mesh(const TetMesh& mesh);

/// Meshes the given blocks into 4-node tetrahedra with edges of about
/// `edge_length` (m; uniform, or graded near a region), every block with
/// its own gridpoints. Axis-aligned bricks are divided by deal.II's
/// generator (n_x n_y n_z hexahedra of five tetrahedra each, at the
/// smallest edge length the field asks for over the brick); any other
/// convex block is meshed by `mesher` (lattice_block_mesher.h: by default
/// the lattice Delaunay mesher where the edge length is nearly uniform over
/// the block, gmsh's Delaunay mesher of convex_block_mesher.h elsewhere),
/// its faces and edges kept exact.
///
/// With `element` hex_mixed every block must be an axis-aligned brick: it
/// becomes hexahedral zones of two overlays of five tetrahedra
/// (append_hex_mixed_brick); any other block throws InputError naming the
/// entry 'Element'. 10-node zones are made from the 4-node ones
/// (make_quadratic); tet10 here throws.
///
/// Last, zones and gridpoints are put in `order` (by default slabs,
/// renumbered block by block for memory locality, mesh_order.h).
///
/// With a `comm` of several ranks, every rank of it must call this with the
/// same arguments: the blocks that are not bricks are meshed by one rank
/// each and exchanged (meshing_on_ranks.h), and every rank gets the mesh
/// one rank would make.
TetMesh mesh_blocks(const BlockModel& blocks, const std::vector<unsigned int>& which,
                    const EdgeLengthField& edge_length, MeshReport& report,
                    ZoneElement element = ZoneElement::tet4, MeshOrder order = MeshOrder::slabs,
                    ConvexMesher mesher = ConvexMesher::automatic, MPI_Comm comm = MPI_COMM_SELF);

/// The same with an order for each block.
TetMesh mesh_blocks(const BlockModel& blocks, const std::vector<unsigned int>& which,
                    const EdgeLengthField& edge_length, MeshReport& report, ZoneElement element,
                    const BlockMeshOrder& order, ConvexMesher mesher = ConvexMesher::automatic,
                    MPI_Comm comm = MPI_COMM_SELF);

/// The number of zones mesh_blocks would make, found without meshing (as a
/// double: a bad edge length can ask for more than any integer holds), so
/// that a scene too large for memory is refused before it is meshed: exact
/// for bricks; for other blocks the regular tetrahedra that fill the
/// volume at the local edge length (gmsh makes 0.55-1.0 of that on blocks
/// larger than the edge length, the lattice mesher 0.8-0.9 on jointed
/// blocks), and at least a fan of the block's faces.
double count_zones(const BlockModel& blocks, const std::vector<unsigned int>& which,
                   const EdgeLengthField& edge_length);

/// True when block b is an axis-aligned box (six faces, normals along the
/// axes; `box` is then its extent): such blocks are meshed by deal.II's
/// brick split, and only they can have hexahedral zones.
bool is_axis_aligned_box(const BlockModel& blocks, unsigned int b, Box& box);

} // namespace talus
