#include <talus/io/file_output.h>
#include <talus/io/zone_vtu_writer.h>
#include <talus/zone/tet10_mesh.h>

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

void write_zones_vtu(const std::string& path, const TetMesh& mesh,
                     const std::vector<double>& positions,
                     const std::vector<ZoneField>& point_fields,
                     const std::vector<ZoneField>& cell_fields)
{
  write_file_atomically(
      path,
      [&](std::ostream& out)
      {
        out.precision(12);
        // 10-node zones as eight sub-tetrahedra each (tet10_mesh.h).
        const unsigned int per_zone = mesh.quadratic() ? 8 : 1;
        const std::size_t n_cells = std::size_t(per_zone) * mesh.n_zones();
        out << "<?xml version=\"1.0\"?>\n"
            << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
               "header_type=\"UInt64\">\n"
            << "  <UnstructuredGrid>\n"
            << "    <Piece NumberOfPoints=\"" << mesh.n_gridpoints() << "\" NumberOfCells=\""
            << n_cells << "\">\n      <Points>\n";
        data_array(out, "Float64", "Points", 3, positions);
        out << "      </Points>\n      <Cells>\n";
        std::vector<unsigned long> connectivity, offsets;
        connectivity.reserve(4 * n_cells);
        std::vector<int> cell_block;
        for (unsigned int z = 0; z < mesh.n_zones(); ++z)
        {
          const auto& t = mesh.zone_gridpoint[z];
          if (per_zone == 1)
          {
            connectivity.insert(connectivity.end(), t.begin(), t.end());
            offsets.push_back(connectivity.size());
            continue;
          }
          for (const auto& sub : tet10_subcell)
          {
            for (unsigned int node : sub)
              connectivity.push_back(node < 4 ? t[node] : mesh.zone_edge_gridpoint[z][node - 4]);
            offsets.push_back(connectivity.size());
            cell_block.push_back(static_cast<int>(mesh.zone_block[z]));
          }
        }
        data_array(out, "Int64", "connectivity", 1, connectivity);
        data_array(out, "Int64", "offsets", 1, offsets);
        data_array(out, "UInt8", "types", 1, std::vector<unsigned char>(n_cells, 10)); // VTK_TETRA
        out << "      </Cells>\n      <PointData>\n";
        for (const ZoneField& f : point_fields)
          data_array(out, "Float64", f.name, f.components, f.values);
        out << "      </PointData>\n      <CellData Scalars=\"block_id\">\n";
        if (per_zone == 1)
          data_array(out, "Int32", "block_id", 1, mesh.zone_block);
        else
          data_array(out, "Int32", "block_id", 1, cell_block);
        for (const ZoneField& f : cell_fields)
          data_array(out, "Float64", f.name, f.components, f.values);
        out << "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
      });
}

} // namespace talus
