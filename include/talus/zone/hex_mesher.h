#pragma once

#include <talus/geometry/plane.h>
#include <talus/zone/tet_mesh.h>

#include <array>

namespace talus
{

/// Appends an axis-aligned brick `box` (m) as n[0] x n[1] x n[2] hexahedral
/// zones of mixed discretization (eqs. 60-67) to `mesh`, as deformable
/// block `block` with gridpoints of its own. Each hexahedron is two
/// overlays of five tetrahedra on its eight corners: one with the central
/// tetrahedron on the corners of even parity, the mirror image with it on
/// the odd ones. Parity is counted over the whole brick (i + j + k of the
/// gridpoint), so the first overlay of every hexahedron takes the central
/// tetrahedron on globally even gridpoints: each overlay alone is then a
/// conforming mesh (its face diagonals match across hexahedra). The
/// block's boundary faces are the first overlay's triangles; the second
/// overlay's go to second_overlay_face_gridpoint.
void append_hex_mixed_brick(TetMesh& mesh, const Box& box, const std::array<unsigned int, 3>& n,
                            unsigned int block);

} // namespace talus
