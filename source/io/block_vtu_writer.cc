#include <talus/io/block_vtu_writer.h>
#include <talus/io/file_output.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <ostream>
#include <stdexcept>

namespace talus
{

void write_blocks_vtu(const std::string& path, const BlockModel& m,
                      const std::vector<BlockField>& fields, VtuEncoding encoding,
                      const std::vector<char>* gone, const std::vector<unsigned int>* ids)
{
  // The blocks shown: all but those a stage removed.
  std::vector<unsigned int> shown;
  for (unsigned int b = 0; b < m.n_blocks(); ++b)
    if (gone == nullptr || !(*gone)[b])
      shown.push_back(b);
  const auto pick = [&](const auto& values, unsigned int components)
  {
    std::decay_t<decltype(values)> out;
    out.reserve(shown.size() * components);
    for (unsigned int b : shown)
      for (unsigned int c = 0; c < components; ++c)
        out.push_back(values[std::size_t(b) * components + c]);
    return out;
  };
  write_file_atomically(
      path,
      [&](std::ostream& out)
      {
        write_vtu_file_start(out, encoding);
        out << "  <UnstructuredGrid>\n"
            << "    <Piece NumberOfPoints=\"" << m.n_vertices() << "\" NumberOfCells=\""
            << shown.size() << "\">\n"
            << "      <Points>\n";
        write_data_array<double>(out, encoding, "Points", 3, m.vertex.size(),
                                 [&](std::size_t first, std::size_t count, double* to)
                                 {
                                   for (std::size_t v = first; v < first + count; ++v, to += 3)
                                     for (int d = 0; d < 3; ++d)
                                       to[d] = m.vertex[v][d];
                                 });
        out << "      </Points>\n      <Cells>\n";

        std::vector<std::int64_t> connectivity, offsets, faces, face_offsets;
        std::vector<std::uint8_t> types(shown.size(), 42); // VTK_POLYHEDRON
        for (unsigned int b : shown)
        {
          for (unsigned int v = m.vertex_start[b]; v < m.vertex_start[b + 1]; ++v)
            connectivity.push_back(v);
          offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
          faces.push_back(m.face_start[b + 1] - m.face_start[b]);
          for (unsigned int f = m.face_start[b]; f < m.face_start[b + 1]; ++f)
          {
            faces.push_back(m.face_loop_start[f + 1] - m.face_loop_start[f]);
            for (unsigned int k = m.face_loop_start[f]; k < m.face_loop_start[f + 1]; ++k)
              faces.push_back(m.face_vertex[k]);
          }
          face_offsets.push_back(static_cast<std::int64_t>(faces.size()));
        }
        write_data_array<std::int64_t>(out, encoding, "connectivity", 1, connectivity);
        write_data_array<std::int64_t>(out, encoding, "offsets", 1, offsets);
        write_data_array<std::uint8_t>(out, encoding, "types", 1, types);
        write_data_array<std::int64_t>(out, encoding, "faces", 1, faces);
        write_data_array<std::int64_t>(out, encoding, "faceoffsets", 1, face_offsets);
        out << "      </Cells>\n      <CellData Scalars=\"block_id\">\n";

        std::vector<std::int32_t> block_ids;
        for (unsigned int b : shown)
          block_ids.push_back(static_cast<std::int32_t>(ids ? (*ids)[b] : b));
        write_data_array<std::int32_t>(out, encoding, "block_id", 1, block_ids);
        std::vector<std::int32_t> groups;
        for (unsigned int b : shown)
          groups.push_back(static_cast<std::int32_t>(m.group[b]));
        write_data_array<std::int32_t>(out, encoding, "group", 1, groups);
        write_data_array<double>(out, encoding, "volume", 1, pick(m.volume, 1));
        for (const BlockField& f : fields)
          write_data_array<double>(out, encoding, f.name, f.components,
                                   pick(f.values, f.components));
        out << "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
      });
}

void write_pvtu(const std::string& path, const std::string& like,
                const std::vector<std::string>& pieces)
{
  // The piece's declarations: its data sections and their arrays (tags
  // before the first array's values; a DataArray tag is one line).
  std::ifstream in(like);
  if (!in)
    throw std::runtime_error("cannot read " + like + " to write " + path);
  std::string line, declared;
  const auto attribute = [](const std::string& tag, const std::string& name)
  {
    const std::size_t at = tag.find(" " + name + "=\"");
    if (at == std::string::npos)
      return std::string();
    const std::size_t from = at + name.size() + 3;
    return tag.substr(from, tag.find('"', from) - from);
  };
  std::string section;
  while (std::getline(in, line))
  {
    const std::size_t open = line.find('<');
    if (open == std::string::npos)
      continue;
    const std::string tag = line.substr(open);
    for (const char* s : {"Points", "PointData", "CellData"})
      if (tag.rfind(std::string("<") + s, 0) == 0 &&
          (tag[std::strlen(s) + 1] == '>' || tag[std::strlen(s) + 1] == ' '))
      {
        if (!section.empty() && section != "Cells")
          declared += "    </P" + section + ">\n";
        section = s;
        declared += "    <P" + tag.substr(1) + "\n";
      }
    if (tag.rfind("<Cells>", 0) == 0)
    {
      if (!section.empty() && section != "Cells")
        declared += "    </P" + section + ">\n";
      section = "Cells";
    }
    // (The time, a field of the whole file before the sections, is not
    // declared per piece.)
    if (tag.rfind("<DataArray", 0) == 0 && !section.empty() && section != "Cells")
      declared += "      <PDataArray type=\"" + attribute(tag, "type") + "\" Name=\"" +
                  attribute(tag, "Name") + "\" NumberOfComponents=\"" +
                  attribute(tag, "NumberOfComponents") + "\"/>\n";
    if (tag.rfind("</Piece>", 0) == 0)
      break;
  }
  if (!section.empty() && section != "Cells")
    declared += "    </P" + section + ">\n";
  write_file_atomically(path,
                        [&](std::ostream& out)
                        {
                          out << "<?xml version=\"1.0\"?>\n"
                              << "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" "
                                 "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
                              << "  <PUnstructuredGrid GhostLevel=\"0\">\n"
                              << declared;
                          for (const std::string& piece : pieces)
                            out << "    <Piece Source=\"" << piece << "\"/>\n";
                          out << "  </PUnstructuredGrid>\n</VTKFile>\n";
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
  write_file_atomically(
      path_,
      [&](std::ostream& out)
      {
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
