#include <talus/io/file_output.h>
#include <talus/io/zone_vtu_writer.h>
#include <talus/zone/hex_mixed.h>
#include <talus/zone/tet10_mesh.h>

#include <Eigen/Eigenvalues>

#include <charconv>
#include <cstdint>
#include <limits>
#include <ostream>
#include <stdexcept>

namespace talus
{

void principal_stresses(const double* s, double* p)
{
  Eigen::Matrix3d m;
  m << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(m, Eigen::EigenvaluesOnly);
  for (int d = 0; d < 3; ++d)
    p[d] = eigen.eigenvalues()[d]; // ascending
}

namespace
{
/// Which stored component (of 6: xx yy zz xy yz zx) is tensor entry (i, j),
/// row-major: a symmetric tensor is written as all 9 entries, so that
/// ParaView sees a tensor.
constexpr unsigned int voigt_of[9] = {0, 3, 5, 3, 1, 4, 5, 4, 2};

constexpr std::uint8_t vtk_tetra = 10;
} // namespace

std::vector<std::array<unsigned int, 4>> shown_tetrahedra(const TetMesh& mesh)
{
  if (mesh.quadratic())
  {
    std::vector<std::array<unsigned int, 4>> cells;
    cells.reserve(8 * mesh.n_zones());
    for (unsigned int z = 0; z < mesh.n_zones(); ++z)
    {
      unsigned int node[10];
      for (int k = 0; k < 4; ++k)
        node[k] = mesh.zone_gridpoint[z][k];
      for (int k = 0; k < 6; ++k)
        node[4 + k] = mesh.zone_edge_gridpoint[z][k];
      for (const auto& sub : tet10_subcell)
        cells.push_back({{node[sub[0]], node[sub[1]], node[sub[2]], node[sub[3]]}});
    }
    return cells;
  }
  const std::vector<char> in_hex = zones_in_hexes(mesh);
  std::vector<std::array<unsigned int, 4>> cells;
  cells.reserve(mesh.n_zones());
  for (unsigned int z = 0; z < mesh.n_zones(); ++z)
    if (!in_hex[z])
      cells.push_back(mesh.zone_gridpoint[z]);
  // Hexahedra after the plain zones: the first five tetrahedra of each.
  for (unsigned int h = 0; h < mesh.n_hexes(); ++h)
    for (unsigned int k = 0; k < TetMesh::tets_per_hex / 2; ++k)
      cells.push_back(mesh.zone_gridpoint[mesh.hex_first_zone[h] + k]);
  return cells;
}

void shown_zone_values(const TetMesh& mesh, const std::vector<double>& x,
                       const std::vector<double>& stress, const std::vector<unsigned char>& state,
                       std::vector<double>& cell_stress, std::vector<unsigned char>& cell_state)
{
  const std::vector<char> in_hex = zones_in_hexes(mesh);
  cell_stress.clear();
  cell_state.clear();
  for (unsigned int z = 0; z < mesh.n_zones(); ++z)
    if (!in_hex[z])
    {
      cell_stress.insert(cell_stress.end(), &stress[6 * z], &stress[6 * z + 6]);
      cell_state.push_back(state[z]);
    }
  const std::vector<double> hex_stress = hex_zone_stress(mesh, x, stress);
  for (unsigned int h = 0; h < mesh.n_hexes(); ++h)
  {
    unsigned char flags = 0;
    for (unsigned int k = 0; k < TetMesh::tets_per_hex; ++k)
      flags |= state[mesh.hex_first_zone[h] + k];
    for (unsigned int k = 0; k < TetMesh::tets_per_hex / 2; ++k)
    {
      cell_stress.insert(cell_stress.end(), &hex_stress[6 * h], &hex_stress[6 * h + 6]);
      cell_state.push_back(flags);
    }
  }
}

ZoneWriter::ZoneWriter(const TetMesh& mesh, VtuEncoding encoding) : mesh_(mesh), encoding_(encoding)
{
}

ZoneWriter::~ZoneWriter() = default;

template <typename Index>
void ZoneWriter::write_cells(std::ostream& out) const
{
  write_data_array<Index>(out, encoding_, "connectivity", 1, 4 * n_cells_,
                          [&](std::size_t first, std::size_t count, Index* to)
                          {
                            // `first` and `count` are whole cells: blocks
                            // hold a multiple of 4 values.
                            for (std::size_t i = first / 4; i < (first + count) / 4; ++i, to += 4)
                              if (mesh_.quadratic())
                              {
                                const std::size_t z = i / 8;
                                const auto& corner = mesh_.zone_gridpoint[z];
                                const auto& edge = mesh_.zone_edge_gridpoint[z];
                                for (int k = 0; k < 4; ++k)
                                {
                                  const unsigned int node = tet10_subcell[i % 8][k];
                                  to[k] =
                                      static_cast<Index>(node < 4 ? corner[node] : edge[node - 4]);
                                }
                              }
                              else
                                for (int k = 0; k < 4; ++k)
                                  to[k] =
                                      static_cast<Index>(mesh_.zone_gridpoint[shown_zone_[i]][k]);
                          });
  write_data_array<Index>(out, encoding_, "offsets", 1, n_cells_,
                          [](std::size_t first, std::size_t count, Index* to)
                          {
                            for (std::size_t i = 0; i < count; ++i)
                              to[i] = static_cast<Index>(4 * (first + i + 1));
                          });
  write_data_array<std::uint8_t>(out, encoding_, "types", 1, n_cells_,
                                 [](std::size_t, std::size_t count, std::uint8_t* to)
                                 { std::fill(to, to + count, vtk_tetra); });
}

void ZoneWriter::write(const std::string& path, const std::vector<double>& positions,
                       const std::vector<ZoneField>& point_fields,
                       const std::vector<ZoneField>& zone_fields, double time)
{
  if (!laid_out_)
  {
    laid_out_ = true;
    if (mesh_.quadratic())
      n_cells_ = 8 * std::size_t(mesh_.n_zones());
    else
    {
      // As shown_tetrahedra: plain zones, then the first five tetrahedra of
      // each hexahedral zone.
      const std::vector<char> in_hex = zones_in_hexes(mesh_);
      shown_zone_.clear();
      for (unsigned int z = 0; z < mesh_.n_zones(); ++z)
        if (!in_hex[z])
          shown_zone_.push_back(z);
      for (unsigned int h = 0; h < mesh_.n_hexes(); ++h)
        for (unsigned int k = 0; k < TetMesh::tets_per_hex / 2; ++k)
          shown_zone_.push_back(mesh_.hex_first_zone[h] + k);
      n_cells_ = shown_zone_.size();
    }
    for (const ZoneField& f : point_fields)
      point_components_.push_back(f.components);
    for (const ZoneField& f : zone_fields)
      zone_components_.push_back(f.components);
  }
  else
  {
    bool same = point_components_.size() == point_fields.size() &&
                zone_components_.size() == zone_fields.size();
    for (std::size_t k = 0; same && k < point_fields.size(); ++k)
      same = point_components_[k] == point_fields[k].components;
    for (std::size_t k = 0; same && k < zone_fields.size(); ++k)
      same = zone_components_[k] == zone_fields[k].components;
    if (!same)
      throw std::logic_error("ZoneWriter: the fields changed between frames");
  }
  const std::size_t n_points = mesh_.n_gridpoints();
  bool sizes = positions.size() == 3 * n_points;
  for (const ZoneField& f : point_fields)
    sizes &= f.values.size() == f.components * n_points;
  for (const ZoneField& f : zone_fields)
    sizes &= f.values.size() == f.components * n_cells_;
  if (!sizes)
    throw std::logic_error("ZoneWriter: a field has the wrong number of values");

  write_file_atomically(
      path,
      [&](std::ostream& out)
      {
        char time_text[32];
        *std::to_chars(time_text, time_text + sizeof time_text - 1, time).ptr = '\0';
        write_vtu_file_start(out, encoding_);
        out << "  <UnstructuredGrid>\n    <FieldData>\n"
            << "      <DataArray type=\"Float64\" Name=\"TIME\" NumberOfTuples=\"1\" "
               "format=\"ascii\">"
            << time_text << "</DataArray>\n    </FieldData>\n"
            << "    <Piece NumberOfPoints=\"" << n_points << "\" NumberOfCells=\"" << n_cells_
            << "\">\n      <Points>\n";
        write_data_array<double>(out, encoding_, "Points", 3, positions);
        out << "      </Points>\n      <Cells>\n";
        if (4 * n_cells_ <= std::size_t(std::numeric_limits<std::int32_t>::max()))
          write_cells<std::int32_t>(out);
        else
          write_cells<std::int64_t>(out);
        out << "      </Cells>\n      <PointData>\n";
        for (const ZoneField& f : point_fields)
          write_data_array<float>(out, encoding_, f.name, f.components, f.values);
        out << "      </PointData>\n      <CellData Scalars=\"block_id\">\n";
        for (const ZoneField& f : zone_fields)
          if (f.components == 6)
            write_data_array<float>(out, encoding_, f.name, 9, n_cells_,
                                    [&](std::size_t first, std::size_t count, float* to)
                                    {
                                      for (std::size_t z = first; z < first + count; ++z, to += 9)
                                        for (int c = 0; c < 9; ++c)
                                          to[c] = static_cast<float>(f.values[6 * z + voigt_of[c]]);
                                    });
          else
            write_data_array<float>(out, encoding_, f.name, f.components, f.values);
        write_data_array<std::int32_t>(
            out, encoding_, "block_id", 1, n_cells_,
            [&](std::size_t first, std::size_t count, std::int32_t* to)
            {
              for (std::size_t i = first; i < first + count; ++i)
                to[i - first] = static_cast<std::int32_t>(
                    mesh_.zone_block[mesh_.quadratic() ? i / 8 : shown_zone_[i]]);
            });
        out << "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
      });
}

} // namespace talus
