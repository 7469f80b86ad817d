#pragma once

#include <talus/io/vtu_encoding.h>
#include <talus/model/block_model.h>

#include <string>
#include <utility>
#include <vector>

namespace talus
{

class CheckpointReader;
class CheckpointWriter;

/// A quantity to show in ParaView: `components` values per item (block,
/// gridpoint or zone).
struct BlockField
{
  std::string name;
  unsigned int components = 1;
  std::vector<double> values;
};

/// Writes every block as one VTK polyhedron cell (type 42) of an XML
/// unstructured grid, with block id, group and volume as cell data plus any
/// `fields` (Float64). ParaView shows each block as a solid it can colour
/// and select. Blocks with `(*gone)[b]` (removed by a stage, or another
/// rank's) are left out. `ids`: each block's number in the whole model (a
/// rank's share); null: its index.
void write_blocks_vtu(const std::string& path, const BlockModel& model,
                      const std::vector<BlockField>& fields = {},
                      VtuEncoding encoding = VtuEncoding::binary,
                      const std::vector<char>* gone = nullptr,
                      const std::vector<unsigned int>* ids = nullptr);

/// A parallel VTU file (.pvtu) at `path` that joins the `pieces` (file
/// names relative to its folder, one per rank); its arrays are declared as
/// those of the piece file `like` (any of them: all have the same arrays).
void write_pvtu(const std::string& path, const std::string& like,
                const std::vector<std::string>& pieces);

/// The list of VTU files of a run with their times, written as a PVD file so
/// that ParaView opens the run as one time series.
class PvdSeries
{
public:
  explicit PvdSeries(std::string pvd_path) : path_(std::move(pvd_path)) {}
  /// Records `vtu_file` (relative to the PVD's folder) at `time` (s) and
  /// rewrites the PVD file.
  void add(double time, const std::string& vtu_file);

  /// Checkpoints: the entries so far. Loading takes them and checks that
  /// their VTU files are in the PVD's folder; rewrite() writes the PVD file.
  void save_state(CheckpointWriter& out) const;
  void load_state(CheckpointReader& in);
  /// Writes the PVD file with the entries so far (none while there are none).
  void rewrite() const;

private:
  std::string path_;
  std::vector<std::pair<double, std::string>> entries_;
};

} // namespace talus
