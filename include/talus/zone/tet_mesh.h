#pragma once

#include <array>
#include <vector>

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
  /// 10-node zones only (empty for 4-node zones): the gridpoints at the six
  /// edge midpoints of each zone, in deal.II's edge order (0-1, 1-2, 2-0,
  /// 0-3, 1-3, 2-3), so that zone_gridpoint then zone_edge_gridpoint are
  /// the nodes of FE_SimplexP<3>(2). Set by make_quadratic (tet10_mesh.h).
  std::vector<std::array<unsigned int, 6>> zone_edge_gridpoint;
  /// Set with the above by make_quadratic and kept by a rank's share of the
  /// mesh (mesh_share.h), so that a rank that holds no zone of a 10-node
  /// model still has a 10-node mesh, as its materials say.
  bool ten_node = false;

  /// Hexahedral zones of mixed discretization (eqs. 60-67; empty for a mesh
  /// of plain tetrahedra). Hexahedron h is the ten consecutive zones
  /// hex_first_zone[h] + [0, 10): five tetrahedra of one overlay, then the
  /// five of the mirror-image split, all on its eight corners hex_gridpoint[h]
  /// (corner i + 2j + 4k at (i, j, k) in the brick's axes). Each overlay
  /// counts half: in nodal forces, masses and stiffness.
  std::vector<std::array<unsigned int, 8>> hex_gridpoint;
  std::vector<unsigned int> hex_first_zone;
  /// The boundary triangles of the second overlay, which splits each
  /// boundary quadrilateral along its other diagonal (face_gridpoint holds
  /// the first overlay's, which contacts use). Face loads are taken half on
  /// each split, so that each corner of a quadrilateral gets a quarter of a
  /// uniform load, as the averaged overlays need.
  std::vector<std::array<unsigned int, 3>> second_overlay_face_gridpoint;

  unsigned int n_gridpoints() const { return static_cast<unsigned int>(position.size() / 3); }
  unsigned int n_zones() const { return static_cast<unsigned int>(zone_gridpoint.size()); }
  bool quadratic() const { return ten_node || !zone_edge_gridpoint.empty(); }
  unsigned int n_faces() const { return static_cast<unsigned int>(face_gridpoint.size()); }
  unsigned int n_hexes() const { return static_cast<unsigned int>(hex_gridpoint.size()); }
  static constexpr unsigned int tets_per_hex = 10;
};

} // namespace talus
