#include <talus/io/file_output.h>
#include <talus/io/zone_vtu_writer.h>
#include <talus/zone/hex_mixed.h>

#include <Eigen/Eigenvalues>

#include <ostream>

namespace talus
{

namespace
{
template <typename T>
void data_array(std::ostream& out, const char* type, const std::string& name,
                unsigned int components, const std::vector<T>& values)
{
  out << "        <DataArray type=\"" << type << "\" Name=\"" << name << "\" NumberOfComponents=\""
      << components << "\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < values.size(); ++i)
    out << +values[i] << ((i + 1) % 12 == 0 ? '\n' : ' ');
  out << "\n        </DataArray>\n";
}
} // namespace

void principal_stresses(const double* s, double* p)
{
  Eigen::Matrix3d m;
  m << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(m, Eigen::EigenvaluesOnly);
  for (int d = 0; d < 3; ++d)
    p[d] = eigen.eigenvalues()[d]; // ascending
}

std::vector<std::pair<unsigned int, unsigned int>> shown_zone_cells(const TetMesh& mesh)
{
  std::vector<std::pair<unsigned int, unsigned int>> cells;
  std::size_t next_hex = 0; // hex_first_zone is ascending
  for (unsigned int z = 0; z < mesh.n_zones();)
    if (next_hex < mesh.hex_first_zone.size() && mesh.hex_first_zone[next_hex] == z)
    {
      cells.emplace_back(z, TetMesh::tets_per_hex);
      z += TetMesh::tets_per_hex;
      ++next_hex;
    }
    else
      cells.emplace_back(z++, 1u);
  return cells;
}

void shown_zone_values(const TetMesh& mesh, const std::vector<double>& x,
                       const std::vector<double>& stress, const std::vector<unsigned char>& state,
                       std::vector<double>& cell_stress, std::vector<unsigned char>& cell_state)
{
  const std::vector<double> hex_stress = hex_zone_stress(mesh, x, stress);
  cell_stress.clear();
  cell_state.clear();
  unsigned int hex = 0;
  for (const auto& [first, count] : shown_zone_cells(mesh))
  {
    const double* s = count == 1 ? &stress[6 * first] : &hex_stress[6 * hex++];
    cell_stress.insert(cell_stress.end(), s, s + 6);
    unsigned char flags = 0;
    for (unsigned int z = first; z < first + count; ++z)
      flags |= state[z];
    cell_state.push_back(flags);
  }
}

void write_zones_vtu(const std::string& path, const TetMesh& mesh,
                     const std::vector<double>& positions,
                     const std::vector<ZoneField>& point_fields,
                     const std::vector<ZoneField>& cell_fields)
{
  const std::vector<std::pair<unsigned int, unsigned int>> cells = shown_zone_cells(mesh);
  write_file_atomically(
      path,
      [&](std::ostream& out)
      {
        out.precision(12);
        out << "<?xml version=\"1.0\"?>\n"
            << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
               "header_type=\"UInt64\">\n"
            << "  <UnstructuredGrid>\n"
            << "    <Piece NumberOfPoints=\"" << mesh.n_gridpoints() << "\" NumberOfCells=\""
            << cells.size() << "\">\n      <Points>\n";
        data_array(out, "Float64", "Points", 3, positions);
        out << "      </Points>\n      <Cells>\n";
        std::vector<unsigned long> connectivity, offsets;
        std::vector<unsigned char> types;
        std::vector<unsigned int> block;
        connectivity.reserve(4 * mesh.n_zones());
        unsigned int hex = 0;
        for (const auto& [first, count] : cells)
        {
          if (count == 1)
          {
            const auto& t = mesh.zone_gridpoint[first];
            connectivity.insert(connectivity.end(), t.begin(), t.end());
            types.push_back(10); // VTK_TETRA
          }
          else
          {
            // VTK_HEXAHEDRON: the bottom face counter-clockwise, then the top.
            static const int vtk_order[8] = {0, 1, 3, 2, 4, 5, 7, 6};
            for (int c : vtk_order)
              connectivity.push_back(mesh.hex_gridpoint[hex][c]);
            ++hex;
            types.push_back(12);
          }
          offsets.push_back(connectivity.size());
          block.push_back(mesh.zone_block[first]);
        }
        data_array(out, "Int64", "connectivity", 1, connectivity);
        data_array(out, "Int64", "offsets", 1, offsets);
        data_array(out, "UInt8", "types", 1, types);
        out << "      </Cells>\n      <PointData>\n";
        for (const ZoneField& f : point_fields)
          data_array(out, "Float64", f.name, f.components, f.values);
        out << "      </PointData>\n      <CellData Scalars=\"block_id\">\n";
        data_array(out, "Int32", "block_id", 1, block);
        for (const ZoneField& f : cell_fields)
          data_array(out, "Float64", f.name, f.components, f.values);
        out << "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
      });
}

} // namespace talus
