#pragma once

#include <talus/io/block_vtu_writer.h>
#include <talus/io/vtu_encoding.h>
#include <talus/zone/tet_mesh.h>

#include <array>
#include <ostream>
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

/// Writes the zones of deformable blocks as a VTU file straight from the
/// flat mesh arrays: the gridpoints are the points (at their current
/// positions, Float64), the shown tetrahedra the cells (VTK_TETRA).
/// Gridpoint fields (1 or 3 components) are point data, zone fields (per
/// shown tetrahedron; 1, 3 or 6 components, 6 a symmetric tensor xx, yy,
/// zz, xy, yz, zx written as the full 3x3 tensor) cell data, both Float32;
/// the block id (Int32) is added as cell data and the time as field data
/// TIME. Arrays are made and compressed a block at a time, so that a write
/// holds little more than one array's compressed bytes. The field layout is
/// fixed by the first frame.
class ZoneWriter
{
public:
  explicit ZoneWriter(const TetMesh& mesh, VtuEncoding encoding = VtuEncoding::binary);
  ~ZoneWriter();

  /// Writes one VTU file atomically, the cells at the gridpoints' current
  /// positions (3 per gridpoint, m); `time` (s) goes into the file.
  void write(const std::string& path, const std::vector<double>& positions,
             const std::vector<ZoneField>& point_fields, const std::vector<ZoneField>& zone_fields,
             double time);

private:
  template <typename Index>
  void write_cells(std::ostream& out) const;

  const TetMesh& mesh_;
  VtuEncoding encoding_;
  std::size_t n_cells_ = 0;
  /// The zone each shown tetrahedron comes from (4-node and hexahedral
  /// zones; a 10-node zone's eight follow from the index).
  std::vector<unsigned int> shown_zone_;
  bool laid_out_ = false; ///< the cells and the fields' layout are known (first frame)
  std::vector<unsigned int> point_components_, zone_components_; ///< of the first frame
};

/// Principal stresses of a symmetric stress (xx, yy, zz, xy, yz, zx), in
/// ascending order (most compressive first, tension positive), Pa.
void principal_stresses(const double* stress, double* principal);

} // namespace talus
