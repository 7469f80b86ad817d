#include <talus/io/block_vtu_writer.h>
#include <talus/io/file_output.h>

#include <ostream>

namespace talus
{

namespace
{

template <typename Range, typename Write>
void data_array(std::ostream& out, const char* type, const std::string& name,
                unsigned int components, const Range& range, Write write)
{
  out << "        <DataArray type=\"" << type << "\" Name=\"" << name
      << "\" NumberOfComponents=\"" << components << "\" format=\"ascii\">\n";
  unsigned int column = 0;
  for (const auto& item : range)
  {
    write(out, item);
    out << (++column % 12 == 0 ? '\n' : ' ');
  }
  out << "\n        </DataArray>\n";
}

} // namespace

void write_blocks_vtu(const std::string& path, const BlockModel& m,
                      const std::vector<BlockField>& fields)
{
  write_file_atomically(path, [&](std::ostream& out) {
    out.precision(12);
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
           "header_type=\"UInt64\">\n"
        << "  <UnstructuredGrid>\n"
        << "    <Piece NumberOfPoints=\"" << m.n_vertices() << "\" NumberOfCells=\""
        << m.n_blocks() << "\">\n"
        << "      <Points>\n";
    data_array(out, "Float64", "Points", 3, m.vertex,
               [](std::ostream& o, const Vec3& v) { o << v[0] << ' ' << v[1] << ' ' << v[2]; });
    out << "      </Points>\n      <Cells>\n";

    std::vector<unsigned long> connectivity, offsets, faces, face_offsets;
    std::vector<int> types(m.n_blocks(), 42); // VTK_POLYHEDRON
    for (unsigned int b = 0; b < m.n_blocks(); ++b)
    {
      for (unsigned int v = m.vertex_start[b]; v < m.vertex_start[b + 1]; ++v)
        connectivity.push_back(v);
      offsets.push_back(connectivity.size());
      faces.push_back(m.face_start[b + 1] - m.face_start[b]);
      for (unsigned int f = m.face_start[b]; f < m.face_start[b + 1]; ++f)
      {
        faces.push_back(m.face_loop_start[f + 1] - m.face_loop_start[f]);
        for (unsigned int k = m.face_loop_start[f]; k < m.face_loop_start[f + 1]; ++k)
          faces.push_back(m.face_vertex[k]);
      }
      face_offsets.push_back(faces.size());
    }
    const auto plain = [](std::ostream& o, auto x) { o << x; };
    data_array(out, "Int64", "connectivity", 1, connectivity, plain);
    data_array(out, "Int64", "offsets", 1, offsets, plain);
    data_array(out, "UInt8", "types", 1, types, plain);
    data_array(out, "Int64", "faces", 1, faces, plain);
    data_array(out, "Int64", "faceoffsets", 1, face_offsets, plain);
    out << "      </Cells>\n      <CellData Scalars=\"block_id\">\n";

    std::vector<unsigned int> ids(m.n_blocks());
    for (unsigned int b = 0; b < m.n_blocks(); ++b)
      ids[b] = b;
    data_array(out, "Int32", "block_id", 1, ids, plain);
    data_array(out, "Int32", "group", 1, m.group, plain);
    data_array(out, "Float64", "volume", 1, m.volume, plain);
    for (const BlockField& f : fields)
      data_array(out, "Float64", f.name, f.components, f.values, plain);
    out << "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  });
}

void PvdSeries::add(double time, const std::string& vtu_file)
{
  entries_.emplace_back(time, vtu_file);
  rewrite();
}

void PvdSeries::rewrite() const
{
  if (entries_.empty()) // a series never added to has no file
    return;
  write_file_atomically(path_, [&](std::ostream& out) {
    out.precision(12);
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "  <Collection>\n";
    for (const auto& [t, file] : entries_)
      out << "    <DataSet timestep=\"" << t << "\" group=\"\" part=\"0\" file=\"" << file
          << "\"/>\n";
    out << "  </Collection>\n</VTKFile>\n";
  });
}

} // namespace talus
