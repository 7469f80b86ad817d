#pragma once

#include <talus/io/block_vtu_writer.h>
#include <talus/zone/tet_mesh.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace talus
{

/// A quantity to show in ParaView, per gridpoint or per zone: the same
/// shape as a block field (name, components per item, values).
using ZoneField = BlockField;

/// The tetrahedra that show the zones in ParaView, four gridpoints each: a
/// 4-node zone as itself, a 10-node zone as its eight sub-tetrahedra
/// (tet10_subcell), a hexahedral zone of mixed discretization as the five
/// tetrahedra of its first overlay (which alone fill the block
/// conformingly).
std::vector<std::array<unsigned int, 4>> shown_tetrahedra(const TetMesh& mesh);

/// Per shown tetrahedron: its stress (6, Pa; a hexahedral zone's is the
/// volume-weighted mean of its ten tetrahedra's at the positions `x`) and
/// plastic state (for a hexahedral zone the union of its tetrahedra's
/// flags).
void shown_zone_values(const TetMesh& mesh, const std::vector<double>& x,
                       const std::vector<double>& stress, const std::vector<unsigned char>& state,
                       std::vector<double>& cell_stress, std::vector<unsigned char>& cell_state);

/// Writes the zones of deformable blocks through deal.II's DataOut. It
/// holds one deal.II triangulation of all deformable blocks, made of the
/// shown tetrahedra (material_id = block), built when output is first
/// asked for. Gridpoint fields have 1 or 3 components (linear in each
/// cell); cell fields (per shown tetrahedron) 1, 3 or 6 components
/// (constant in each cell; 6 is a symmetric tensor xx, yy, zz, xy, yz, zx,
/// written as a full 3x3 tensor); the block id is added. The field layout
/// is fixed by the first frame; the DoF numbering is built once.
class ZoneWriter
{
public:
  explicit ZoneWriter(const TetMesh& mesh);
  ~ZoneWriter();

  /// Writes one VTU file atomically, the cells at the gridpoints' current
  /// positions (3 per gridpoint, m); `time` (s) goes into the file.
  void write(const std::string& path, const std::vector<double>& positions,
             const std::vector<ZoneField>& point_fields, const std::vector<ZoneField>& zone_fields,
             double time);

private:
  struct Data;
  const TetMesh& mesh_;
  std::unique_ptr<Data> data_;
};

/// Principal stresses of a symmetric stress (xx, yy, zz, xy, yz, zx), in
/// ascending order (most compressive first, tension positive), Pa.
void principal_stresses(const double* stress, double* principal);

} // namespace talus
