#pragma once

#include <talus/model/block_model.h>
#include <talus/zone/tet_mesh.h>

#include <string>
#include <vector>

namespace talus
{

/// What meshing made, for the summary.
struct MeshReport
{
  unsigned int blocks = 0, zones = 0, gridpoints = 0, boundary_faces = 0;
  double zone_volume = 0.0;     ///< m^3, sum over zones (equals the blocks' volume)
  double smallest_height = 0.0; ///< m, smallest zone height (eq. 86)
  double largest_edge = 0.0;    ///< m, largest zone edge (eq. 86)
};

/// Meshes the given blocks into 4-node tetrahedra with edges no longer than
/// about `edge_length` (m), every block with its own gridpoints, all in one
/// deal.II Triangulation<3> of simplices (material id = block number) from
/// which the flat TetMesh is taken. Axis-aligned bricks are divided by
/// deal.II's generator into n_x n_y n_z hexahedra of five... six tetrahedra
/// each; any other convex block is split into tetrahedra from its centroid
/// over its triangulated faces, which are then refined until the edge
/// length is reached.
TetMesh mesh_blocks(const BlockModel& blocks, const std::vector<unsigned int>& which,
                    double edge_length, MeshReport& report);

} // namespace talus
