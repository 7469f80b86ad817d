#pragma once

#include <talus/model/block_model.h>
#include <talus/zone/convex_block_mesher.h>

#include <vector>

namespace talus
{

/// Which mesher fills a convex block that is not an axis-aligned brick.
enum class ConvexMesher
{
  automatic, ///< lattice where the edge length is (nearly) uniform over the block, else gmsh
  gmsh,      ///< gmsh's Delaunay mesher (convex_block_mesher.h)
  lattice    ///< the lattice Delaunay mesher, at the block's smallest edge length
};

/// Meshes a convex body into tetrahedra of edge about h (m) from a point
/// lattice: its corners; points along each edge at spacing ~h (the same
/// points for both faces that share the edge); a triangular lattice inside
/// each face, kept 0.5h from the face's edges; a body-centred cubic lattice
/// inside, kept about 0.6h from every face, its cube side h 2^(1/6) so that
/// its tetrahedra have the volume of regular ones of edge h. The Delaunay
/// tetrahedralisation of these points (CGAL) fills their convex hull, which
/// is the body: every point on the surface lies on the body's planes. Cells
/// whose four points lie on one face (flat, from rounding) are dropped;
/// then the gridpoints of poor zones are moved (interior ones freely, face
/// ones in their face's plane, edge ones along their edge) to the position
/// of a fixed set of trial moves that best raises the worst zone around
/// them. The mesh depends on the body only (the same every time).
///
/// Returns false, with `out` empty, when the mesh fails its own checks
/// (a zone of no volume, zone volumes not summing to the body's volume to
/// 1e-12): callers then mesh the body by gmsh.
bool mesh_convex_body_by_lattice(const PolyhedralSurface& body, double h, BlockTetrahedra& out);

/// Block b of `blocks` meshed by mesh_convex_body_by_lattice at the
/// smallest edge length the field asks for at its corners and centroid.
/// Throws InputError naming the block when the lattice mesh fails.
BlockTetrahedra mesh_convex_block_by_lattice(const BlockModel& blocks, unsigned int b,
                                             const EdgeLengthAt& edge_length);

/// The smallest and largest edge length the field asks for at block b's
/// corners and centroid (m).
std::pair<double, double> edge_length_range(const BlockModel& blocks, unsigned int b,
                                            const EdgeLengthAt& edge_length);

/// Meshes the given convex blocks by `mesher`. With `automatic`, a block on
/// which the edge length varies by at most 25 % (largest over smallest at
/// its corners and centroid) is meshed by the lattice mesher at its
/// smallest edge length, any other by gmsh (which follows the grading
/// within a block); a block the lattice mesher fails on goes to gmsh in
/// every mode. `lattice_blocks`, if given, counts the blocks meshed by the
/// lattice.
std::vector<BlockTetrahedra> mesh_convex_blocks_with(const BlockModel& blocks,
                                                     const std::vector<unsigned int>& which,
                                                     const EdgeLengthAt& edge_length,
                                                     ConvexMesher mesher,
                                                     unsigned int* lattice_blocks = nullptr);

} // namespace talus
