#include <talus/contact/contact_origin.h>
#include <talus/io/contact_vtu_writer.h>
#include <talus/io/file_output.h>

#include <ostream>

namespace talus
{

void write_contacts_vtu(const std::string& path, const ContactSet& cs, const BlockModel& model,
                        const JointNumbers& joints)
{
  // The joint of each contact slot, as the numbers of its subsections.
  std::vector<int> joint_set(cs.n_slots(), 0), joint(cs.n_slots(), 0);
  for (unsigned int c = 0; c < cs.n_slots(); ++c)
    if (cs.alive[c])
    {
      const int origin = contact_joint_origin(model, cs, c);
      if (origin > 0)
        joint_set[c] = joints.joint_set_number.at(static_cast<std::size_t>(origin - 1));
      else if (origin < 0)
        joint[c] = joints.joint_number.at(static_cast<std::size_t>(-origin - 1));
    }
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
    out << "      </Cells>\n      <PointData Scalars=\"normal_force\">\n";
    begin("Float64", "normal", 3);
    for (unsigned int i = 0; i < n; ++i)
    {
      const Vec3& nrm = cs.plane[cs.sc_contact[i]].normal;
      out << nrm[0] << ' ' << nrm[1] << ' ' << nrm[2] << '\n';
    }
    end();
    // Forces and their stresses (over the sub-contact's area).
    for (const double per : {0.0, 1.0})
    {
      begin("Float64", per == 0.0 ? "normal_force" : "normal_stress", 1);
      for (unsigned int i = 0; i < n; ++i)
        out << cs.sc_fn[i] / (per == 0.0 ? 1.0 : cs.sc_area[i]) << ' ';
      end();
      begin("Float64", per == 0.0 ? "shear_force" : "shear_stress", 3);
      for (unsigned int i = 0; i < n; ++i)
      {
        const double scale = per == 0.0 ? 1.0 : 1.0 / cs.sc_area[i];
        out << scale * cs.sc_fs[3 * i] << ' ' << scale * cs.sc_fs[3 * i + 1] << ' '
            << scale * cs.sc_fs[3 * i + 2] << '\n';
      }
      end();
    }
    begin("Float64", "shear_displacement", 3);
    for (unsigned int i = 0; i < n; ++i)
      out << cs.sc_us[3 * i] << ' ' << cs.sc_us[3 * i + 1] << ' ' << cs.sc_us[3 * i + 2] << '\n';
    end();
    begin("Float64", "area", 1);
    for (unsigned int i = 0; i < n; ++i)
      out << cs.sc_area[i] << ' ';
    end();
    begin("Int32", "state", 1);
    for (unsigned int i = 0; i < n; ++i)
      out << static_cast<int>(cs.sc_state[i]) << ' ';
    end();
    // Numbered from 1 in the order of ContactType.
    begin("Int32", "type", 1);
    for (unsigned int i = 0; i < n; ++i)
      out << static_cast<int>(cs.type[cs.sc_contact[i]]) + 1 << ' ';
    end();
    begin("Int32", "joint_set", 1);
    for (unsigned int i = 0; i < n; ++i)
      out << joint_set[cs.sc_contact[i]] << ' ';
    end();
    begin("Int32", "joint", 1);
    for (unsigned int i = 0; i < n; ++i)
      out << joint[cs.sc_contact[i]] << ' ';
    end();
    begin("Int32", "contact_id", 1);
    for (unsigned int i = 0; i < n; ++i)
      out << cs.sc_contact[i] << ' ';
    end();
    out << "      </PointData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  });
}

} // namespace talus
