#pragma once

#include <talus/model/block_model.h>
#include <talus/zone/tet_mesh.h>

#include <vector>

namespace talus
{

/// Gives every deformable block (a block with zones in `mesh`) the surface
/// of its zones as its shape in `blocks`: its vertices become its surface
/// gridpoints and its faces the boundary triangles of its zones, so that
/// cell space, common plane and contact types work on deformable blocks as
/// they do on rigid ones. Volume and inertia keep the block's original
/// values; the centroid becomes the mean of the surface gridpoints. Returns, for every vertex of `blocks`, its gridpoint
/// (-1 for the vertices of rigid blocks).
std::vector<int> use_zone_surfaces(BlockModel& blocks, const TetMesh& mesh);

/// What made each boundary face of the zones (BlockModel::face_origin of
/// the block face it lies on; 0 for none): the mesh's boundary faces, then
/// its second overlay's. Call before use_zone_surfaces, on the blocks' own
/// faces.
std::vector<int> zone_face_origins(const BlockModel& blocks, const TetMesh& mesh);

/// Moves the vertices of deformable blocks to their gridpoints' positions
/// `x` (3 per gridpoint, m) and turns their face normals with them; adds
/// each block's largest vertex move to `moved[b]` (eq. 1 needs it).
void follow_gridpoints(BlockModel& blocks, const std::vector<int>& vertex_gridpoint,
                       const std::vector<unsigned int>& deformable_blocks, const double* x,
                       std::vector<double>& moved);

} // namespace talus
