#pragma once

#include <talus/io/block_vtu_writer.h>
#include <talus/zone/tet_mesh.h>

#include <string>
#include <vector>

namespace talus
{

/// A quantity to show in ParaView, per gridpoint or per zone: the same
/// shape as a block field (name, components per item, values).
using ZoneField = BlockField;

/// Writes the zones of deformable blocks as VTK tetrahedra (type 10) at the
/// gridpoints' current positions (3 per gridpoint, m), with block id as
/// cell data plus `point_fields` and `cell_fields`. A 10-node zone is written
/// as its eight sub-tetrahedra (tet10_subcell), so cell fields then hold 8
/// values per zone (tet10_subcell_values).
void write_zones_vtu(const std::string& path, const TetMesh& mesh,
                     const std::vector<double>& positions,
                     const std::vector<ZoneField>& point_fields,
                     const std::vector<ZoneField>& cell_fields);

/// Principal stresses of a symmetric stress (xx, yy, zz, xy, yz, zx), in
/// ascending order (most compressive first, tension positive), Pa.
void principal_stresses(const double* stress, double* principal);

} // namespace talus
