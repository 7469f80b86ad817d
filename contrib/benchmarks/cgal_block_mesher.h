#pragma once

// For the meshing benchmark only: one convex block meshed with CGAL's 3D
// mesh generator (Mesh_3), into the same points + tetrahedra as talus's gmsh
// mesher, so that both are measured by the same figures. Kept in a
// translation unit of its own: Mesh_3's templates take about a minute to
// compile.

#include <talus/model/block_model.h>
#include <talus/zone/convex_block_mesher.h>

namespace talus
{

/// Mesh_3's criteria (its names). Sizes in m.
struct CgalCriteria
{
  double edge_size;                    ///< spacing of the protecting balls on the block's edges
  double facet_size;                   ///< largest surface Delaunay ball radius
  double cell_size;                    ///< largest circumradius of a tetrahedron
  double facet_angle = 25.0;           ///< degrees, smallest facet angle
  double facet_distance;               ///< facet centre to surface (flat faces: 0 anyway)
  double cell_radius_edge_ratio = 2.0; ///< circumradius over shortest edge
  bool optimise = true;                ///< Mesh_3's default perturb + exude (sliver removal)
  /// Edges between faces whose normals differ by at least this (degrees)
  /// are protected; a convex block's faces all differ, its triangulated
  /// faces' diagonals do not.
  double feature_angle = 0.1;
};

/// Criteria for a target edge length h: the edges' balls h apart, and
/// facet and cell radii those of an equilateral triangle (h/sqrt 3) and a
/// regular tetrahedron (h sqrt 6 / 4) of edge h, so that the count aims at
/// regular_tetrahedra_in as gmsh's does.
CgalCriteria cgal_criteria_for(double h);

/// The block's tetrahedra (positively oriented), or throws std::runtime_error
/// when CGAL fails or makes none.
BlockTetrahedra cgal_mesh_convex_block(const BlockModel& blocks, unsigned int block,
                                       const CgalCriteria& criteria);

} // namespace talus
