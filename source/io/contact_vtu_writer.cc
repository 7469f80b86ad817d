#include <talus/io/contact_vtu_writer.h>
#include <talus/io/file_output.h>

#include <ostream>

namespace talus
{

void write_contacts_vtu(const std::string& path, const ContactSet& cs)
{
  write_file_atomically(path, [&](std::ostream& out) {
    const unsigned int n = cs.n_subcontacts();
    out.precision(10);
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
           "header_type=\"UInt64\">\n  <UnstructuredGrid>\n    <Piece NumberOfPoints=\""
        << n << "\" NumberOfCells=\"" << n << "\">\n      <Points>\n";
    const auto begin = [&](const char* type, const char* name, int components) {
      out << "        <DataArray type=\"" << type << "\" Name=\"" << name
          << "\" NumberOfComponents=\"" << components << "\" format=\"ascii\">\n";
    };
    const auto end = [&]() { out << "\n        </DataArray>\n"; };
    begin("Float64", "Points", 3);
    for (const Vec3& p : cs.sc_position)
      out << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
    end();
    out << "      </Points>\n      <Cells>\n";
    begin("Int64", "connectivity", 1);
    for (unsigned int i = 0; i < n; ++i)
      out << i << ' ';
    end();
    begin("Int64", "offsets", 1);
    for (unsigned int i = 0; i < n; ++i)
      out << i + 1 << ' ';
    end();
    begin("UInt8", "types", 1);
    for (unsigned int i = 0; i < n; ++i)
      out << "1 "; // VTK_VERTEX
    end();
    out << "      </Cells>\n      <PointData Scalars=\"normal force\">\n";
    begin("Float64", "normal", 3);
    for (unsigned int i = 0; i < n; ++i)
    {
      const Vec3& nrm = cs.plane[cs.sc_contact[i]].normal;
      out << nrm[0] << ' ' << nrm[1] << ' ' << nrm[2] << '\n';
    }
    end();
    begin("Float64", "normal force", 1);
    for (unsigned int i = 0; i < n; ++i)
      out << cs.sc_fn[i] << ' ';
    end();
    begin("Float64", "shear force", 3);
    for (unsigned int i = 0; i < n; ++i)
      out << cs.sc_fs[3 * i] << ' ' << cs.sc_fs[3 * i + 1] << ' ' << cs.sc_fs[3 * i + 2] << '\n';
    end();
    begin("Float64", "area", 1);
    for (unsigned int i = 0; i < n; ++i)
      out << cs.sc_area[i] << ' ';
    end();
    begin("Int32", "state", 1);
    for (unsigned int i = 0; i < n; ++i)
      out << static_cast<int>(cs.sc_state[i]) << ' ';
    end();
    begin("Int32", "contact type", 1);
    for (unsigned int i = 0; i < n; ++i)
      out << static_cast<int>(cs.type[cs.sc_contact[i]]) << ' ';
    end();
    begin("Int32", "contact", 1);
    for (unsigned int i = 0; i < n; ++i)
      out << cs.sc_contact[i] << ' ';
    end();
    out << "      </PointData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  });
}

} // namespace talus
