#pragma once

#include <talus/io/block_vtu_writer.h>
#include <talus/zone/tet_mesh.h>

#include <string>
#include <utility>
#include <vector>

namespace talus
{

/// A quantity to show in ParaView, per gridpoint or per zone: the same
/// shape as a block field (name, components per item, values).
using ZoneField = BlockField;

/// The cells shown in ParaView, in zone order: a zone as its tetrahedron,
/// a hexahedral zone of mixed discretization (ten tetrahedra) as one
/// hexahedron. For each cell: its first zone and its number of zones (1 or
/// 10).
std::vector<std::pair<unsigned int, unsigned int>> shown_zone_cells(const TetMesh& mesh);

/// Per shown cell: its stress (6, Pa; a hexahedral zone's is the
/// volume-weighted mean of its tetrahedra's at the positions `x`) and
/// plastic state (the union of its tetrahedra's flags).
void shown_zone_values(const TetMesh& mesh, const std::vector<double>& x,
                       const std::vector<double>& stress, const std::vector<unsigned char>& state,
                       std::vector<double>& cell_stress, std::vector<unsigned char>& cell_state);

/// Writes the zones of deformable blocks as VTK tetrahedra (type 10) and
/// hexahedra (type 12, the hexahedral zones) at the gridpoints' current
/// positions (3 per gridpoint, m), with block id as cell data plus
/// `point_fields` and `cell_fields` (per shown cell, shown_zone_cells).
void write_zones_vtu(const std::string& path, const TetMesh& mesh,
                     const std::vector<double>& positions,
                     const std::vector<ZoneField>& point_fields,
                     const std::vector<ZoneField>& cell_fields);

/// Principal stresses of a symmetric stress (xx, yy, zz, xy, yz, zx), in
/// ascending order (most compressive first, tension positive), Pa.
void principal_stresses(const double* stress, double* principal);

} // namespace talus
