#pragma once

#include <array>
#include <memory>
#include <vector>

namespace dealii
{
template <int dim, int spacedim>
class Triangulation;
}

namespace talus
{

/// The zones of all deformable blocks as flat arrays: 4-node tetrahedra,
/// every block with its own gridpoints (blocks never share a gridpoint),
/// built once from a deal.II Triangulation<3> of simplices. The hot loops of
/// the explicit solver read only these arrays.
struct TetMesh
{
  /// Initial gridpoint positions, 3 per gridpoint, m.
  std::vector<double> position;
  /// The four gridpoints of each zone, positively oriented (positive volume).
  std::vector<std::array<unsigned int, 4>> zone_gridpoint;
  /// Deformable block of each zone and of each gridpoint (index in the
  /// block model).
  std::vector<unsigned int> zone_block, gridpoint_block;
  /// Boundary faces: three gridpoints ordered so that the normal points out
  /// of the block, and the zone they belong to.
  std::vector<std::array<unsigned int, 3>> face_gridpoint;
  std::vector<unsigned int> face_zone;
  /// The same zones as one deal.II triangulation (cell z = zone z, vertex
  /// g = gridpoint g, material_id = block), for deal.II's output tools;
  /// null until the mesher has finished the mesh.
  std::shared_ptr<dealii::Triangulation<3, 3>> triangulation;

  unsigned int n_gridpoints() const { return static_cast<unsigned int>(position.size() / 3); }
  unsigned int n_zones() const { return static_cast<unsigned int>(zone_gridpoint.size()); }
  unsigned int n_faces() const { return static_cast<unsigned int>(face_gridpoint.size()); }
};

} // namespace talus
