#pragma once

#include <talus/io/block_vtu_writer.h>
#include <talus/zone/tet_mesh.h>

#include <memory>
#include <string>
#include <vector>

namespace talus
{

/// A quantity to show in ParaView, per gridpoint or per zone: the same
/// shape as a block field (name, components per item, values).
using ZoneField = BlockField;

/// Writes the zones of deformable blocks through deal.II's DataOut on the
/// mesh's triangulation (TetMesh::triangulation): gridpoint fields of 1 or
/// 3 components (linear in each zone), zone fields of 1, 3 or 6 components
/// (constant in each zone; 6 is a symmetric tensor xx, yy, zz, xy, yz, zx,
/// written as a full 3x3 tensor), and the block id. The field layout is
/// fixed by the first frame; the DoF numbering is built once.
class ZoneWriter
{
public:
  explicit ZoneWriter(const TetMesh& mesh);
  ~ZoneWriter();

  /// Writes one VTU file atomically, the cells at the gridpoints' current
  /// positions (3 per gridpoint, m); `time` (s) goes into the file.
  void write(const std::string& path, const std::vector<double>& positions,
             const std::vector<ZoneField>& point_fields,
             const std::vector<ZoneField>& zone_fields, double time);

private:
  struct Data;
  const TetMesh& mesh_;
  std::unique_ptr<Data> data_;
};

/// Principal stresses of a symmetric stress (xx, yy, zz, xy, yz, zx), in
/// ascending order (most compressive first, tension positive), Pa.
void principal_stresses(const double* stress, double* principal);

} // namespace talus
