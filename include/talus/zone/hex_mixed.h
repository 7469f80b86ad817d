#pragma once

#include <talus/zone/tet_mesh.h>

#include <vector>

namespace talus
{

// Mixed discretization of hexahedral zones (eqs. 60-67). A hexahedron is
// ten consecutive tetrahedra of the mesh, two overlays of five
// (TetMesh::hex_first_zone); the functions below work on a batch of whole
// hexahedra, n tetrahedra (a multiple of ten) from a hexahedron's first,
// between the two passes of the tet4 kernel. Volumes are those of the
// kernel's first pass (m^3), one per tetrahedron; tensors are six numbers
// per tetrahedron (xx, yy, zz, xy, yz, zx).
//
// The volumetric part is averaged over the whole hexahedron, both overlays
// together (the manual carries the averaging out over the combination of
// the two overlays): with each overlay's forces weighted 1/2, this is the
// average of eq. 62 over the ten tetrahedra, and gives each hexahedron one
// volumetric constraint.

/// Eqs. 60-63: each tetrahedron keeps the deviatoric part of its strain
/// increment and takes the volume-weighted mean of the volumetric
/// increments of its hexahedron's ten tetrahedra.
void hex_mixed_average_strain(unsigned int n, double* strain_increment, const double* volume);

/// Eqs. 64-67: after the zone model, each tetrahedron keeps its deviatoric
/// stress and takes the volume-weighted mean stress of its hexahedron
/// (stress: Pa, from the batch's first tetrahedron).
void hex_mixed_average_mean_stress(unsigned int n, double* stress, const double* volume);

/// Halves the volumes, so that the kernel's nodal forces (proportional to
/// the volume) count each overlay half: the nodal forces of the
/// hexahedron are the mean of its two overlays'.
void hex_mixed_overlay_weight(unsigned int n, double* volume);

/// Per tetrahedron: true when it belongs to a hexahedral zone.
std::vector<char> zones_in_hexes(const TetMesh& mesh);

/// For output: the stress of each hexahedral zone, the volume-weighted mean
/// of its ten tetrahedra's at the gridpoint positions `x` (3 per gridpoint,
/// m), 6 per hexahedron (Pa).
std::vector<double> hex_zone_stress(const TetMesh& mesh, const std::vector<double>& x,
                                    const std::vector<double>& stress);

} // namespace talus
