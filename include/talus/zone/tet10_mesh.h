#pragma once

#include <talus/zone/tet_mesh.h>

#include <array>
#include <vector>

namespace talus
{

/// Node numbering of a 10-node zone (as deal.II's FE_SimplexP<3>(2)):
/// vertices 0-3, then the midpoints of the edges in this order.
inline constexpr unsigned int tet10_edge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};

/// Turns every 4-node zone of `mesh` into a 10-node zone: a new gridpoint
/// at the midpoint of every zone edge, shared by the zones of one block
/// around that edge (blocks still share no gridpoint), and every boundary
/// face into its four flat sub-triangles (same outward orientation, same
/// zone), so that contact sees a surface of triangles as before.
/// Does nothing to a mesh that is already quadratic.
void make_quadratic(TetMesh& mesh);

/// For output: each 10-node zone as eight 4-node sub-tetrahedra (four
/// corner ones and the inner octahedron cut along the 2-0 / 1-3 midpoint
/// diagonal), as local node numbers 0-9, positively oriented.
inline constexpr unsigned int tet10_subcell[8][4] = {{0, 4, 6, 7}, {4, 1, 5, 8}, {6, 5, 2, 9},
                                                     {7, 8, 9, 3}, {6, 8, 4, 5}, {6, 8, 5, 9},
                                                     {6, 8, 9, 7}, {6, 8, 7, 4}};

/// Gauss-point values (4 per zone, `components` numbers each, zone-major)
/// to the eight output sub-tetrahedra of each zone: the linear field
/// through the four Gauss points, evaluated at each sub-tetrahedron's
/// centroid.
std::vector<double> tet10_subcell_values(const std::vector<double>& gauss_values,
                                         unsigned int components);

/// Gauss-point flags (4 per zone) to the eight sub-tetrahedra: the flags of
/// the Gauss point nearest each sub-tetrahedron's centroid.
std::vector<unsigned char> tet10_subcell_flags(const std::vector<unsigned char>& gauss_flags);

} // namespace talus
