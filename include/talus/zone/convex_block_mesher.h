#pragma once

#include <talus/model/block_model.h>

#include <array>
#include <functional>
#include <string>
#include <vector>

namespace talus
{

/// The target zone edge length (m) at a point: uniform, or graded finer near
/// a region (zone_size_field.h).
using EdgeLengthAt = std::function<double(const Vec3&)>;

/// The tetrahedra of one block, with gridpoints of its own.
struct BlockTetrahedra
{
  std::vector<Vec3> point;                      ///< m
  std::vector<std::array<unsigned int, 4>> tet; ///< positively oriented
};

/// A closed polyhedral surface: the body a mesher fills with zones. Faces
/// are planar loops of vertex numbers, counter-clockwise seen from outside;
/// a face may be non-convex (a body need not be convex), but has no holes.
struct PolyhedralSurface
{
  std::vector<Vec3> vertex;                    ///< m
  std::vector<std::vector<unsigned int>> face; ///< vertex loops
  std::vector<Vec3> face_normal;               ///< outward unit normals
};

/// Block b's surface.
PolyhedralSurface block_surface(const BlockModel& blocks, unsigned int block);

/// Meshes any closed polyhedral body as mesh_convex_block does (for bodies
/// that are not blocks of a model: verification slabs with openings).
/// Throws InputError when gmsh cannot mesh it.
BlockTetrahedra mesh_polyhedron(const PolyhedralSurface& body, const EdgeLengthAt& edge_length);

/// Meshes one convex block of `blocks` into quality tetrahedra whose edges
/// are about `edge_length(x)` long, with gmsh's Delaunay mesher (through its
/// C++ API): its faces are triangulated by the frontal-Delaunay surface
/// mesher, its volume filled by 3D Delaunay with optimisation. The block's
/// faces and edges stay exact: every gridpoint gmsh puts on a corner is
/// that corner, on an edge it is moved onto the edge, on a face onto the
/// face's plane, so that the zones' surface is the block's surface and the
/// zones' volumes sum to the block's volume to round-off.
///
/// A block smaller than the edge length gets its smallest valid mesh (its
/// faces' fans and few interior points). Throws InputError naming the block
/// when gmsh cannot mesh it.
BlockTetrahedra mesh_convex_block(const BlockModel& blocks, unsigned int block,
                                  const EdgeLengthAt& edge_length);

/// Meshes the given blocks as mesh_convex_block does, `batch` blocks per
/// gmsh model. By default one: then a block's mesh does not depend on which
/// other blocks are deformable (gmsh's tolerances follow the size of the
/// whole model it meshes), and gmsh's Delaunay mesher is faster so (250
/// jointed blocks: 1.1 s one by one, 2.2 s in batches of 64). A batch gmsh
/// cannot mesh is meshed again block by block, so that the error names the
/// block.
std::vector<BlockTetrahedra> mesh_convex_blocks(const BlockModel& blocks,
                                                const std::vector<unsigned int>& which,
                                                const EdgeLengthAt& edge_length,
                                                std::size_t batch = 1);

/// The normalised radius ratio of a tetrahedron, 3 r_in / r_circ: 1 for a
/// regular one, 0 for a flat one.
double radius_ratio(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// The number of regular tetrahedra of edge `edge_length` (m) that fill
/// `volume` (m^3): V / (h^3 sqrt(2) / 12), the size a mesh should have.
double regular_tetrahedra_in(double volume, double edge_length);

/// Holds gmsh's global state for as long as it lives (gmsh::initialize and
/// finalize); meshing starts one when none is alive.
class GmshSession
{
public:
  GmshSession();
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

private:
  bool owner = false;
};

} // namespace talus
