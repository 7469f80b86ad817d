#include <talus/contact/contact_origin.h>
#include <talus/io/contact_vtu_writer.h>
#include <talus/io/file_output.h>
#include <talus/joint/continuously_yielding.h>
#include <talus/solver/water_loads.h>

#include <algorithm>
#include <cstdint>
#include <ostream>

namespace talus
{

void write_contacts_vtu(const std::string& path, const ContactSet& cs, const BlockModel& model,
                        const JointNumbers& joints, VtuEncoding encoding, const WaterSpec* water,
                        double gravity, const std::vector<unsigned int>* subcontacts,
                        bool ids_in_pair_order)
{
  std::vector<unsigned int> id(cs.n_slots());
  for (unsigned int c = 0; c < cs.n_slots(); ++c)
    id[c] = c;
  if (ids_in_pair_order)
  {
    std::vector<std::pair<std::pair<unsigned int, unsigned int>, unsigned int>> live;
    for (unsigned int c = 0; c < cs.n_slots(); ++c)
      if (cs.alive[c])
        live.push_back({{cs.block_a[c], cs.block_b[c]}, c});
    std::sort(live.begin(), live.end());
    for (unsigned int k = 0; k < live.size(); ++k)
      id[live[k].second] = k;
  }
  // The joint of each contact slot, as the numbers of its subsections.
  std::vector<int> joint_set(cs.n_slots(), 0), joint(cs.n_slots(), 0), origin_of(cs.n_slots(), 0);
  for (unsigned int c = 0; c < cs.n_slots(); ++c)
    if (cs.alive[c])
    {
      const int origin = origin_of[c] = contact_joint_origin(model, cs, c);
      if (origin > 0)
        joint_set[c] = joints.joint_set_number.at(static_cast<std::size_t>(origin - 1));
      else if (origin < 0)
        joint[c] = joints.joint_number.at(static_cast<std::size_t>(-origin - 1));
    }
  const unsigned int n =
      subcontacts ? static_cast<unsigned int>(subcontacts->size()) : cs.n_subcontacts();
  // The k-th sub-contact written.
  const auto pick = [&](std::size_t k) -> std::size_t
  { return subcontacts ? (*subcontacts)[k] : k; };
  // A Float64 array of `components` values per sub-contact from `value(i, d)`.
  const auto reals = [&](std::ostream& out, const char* name, unsigned int components, auto value)
  {
    write_data_array<double>(out, encoding, name, components, n,
                             [&](std::size_t first, std::size_t count, double* to)
                             {
                               for (std::size_t i = first; i < first + count; ++i)
                                 for (unsigned int d = 0; d < components; ++d)
                                   *to++ = value(pick(i), d);
                             });
  };
  const auto integers = [&](std::ostream& out, const char* name, auto value)
  {
    write_data_array<std::int32_t>(out, encoding, name, 1, n,
                                   [&](std::size_t first, std::size_t count, std::int32_t* to)
                                   {
                                     for (std::size_t i = first; i < first + count; ++i)
                                       *to++ = static_cast<std::int32_t>(value(pick(i)));
                                   });
  };
  write_file_atomically(
      path,
      [&](std::ostream& out)
      {
        write_vtu_file_start(out, encoding);
        out << "  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\""
            << n << "\">\n      <Points>\n";
        reals(out, "Points", 3,
              [&](std::size_t i, unsigned int d) { return cs.sc_position[i][d]; });
        out << "      </Points>\n      <Cells>\n";
        write_data_array<std::int64_t>(out, encoding, "connectivity", 1, n,
                                       [](std::size_t first, std::size_t count, std::int64_t* to)
                                       {
                                         for (std::size_t i = 0; i < count; ++i)
                                           to[i] = static_cast<std::int64_t>(first + i);
                                       });
        write_data_array<std::int64_t>(out, encoding, "offsets", 1, n,
                                       [](std::size_t first, std::size_t count, std::int64_t* to)
                                       {
                                         for (std::size_t i = 0; i < count; ++i)
                                           to[i] = static_cast<std::int64_t>(first + i + 1);
                                       });
        write_data_array<std::uint8_t>(out, encoding, "types", 1, n,
                                       [](std::size_t, std::size_t count, std::uint8_t* to)
                                       {
                                         std::fill(to, to + count, 1); // VTK_VERTEX
                                       });
        out << "      </Cells>\n      <PointData Scalars=\"normal_force\">\n";
        reals(out, "normal", 3,
              [&](std::size_t i, unsigned int d) { return cs.plane[cs.sc_contact[i]].normal[d]; });
        // Forces and their stresses (over the sub-contact's area).
        reals(out, "normal_force", 1, [&](std::size_t i, unsigned int) { return cs.sc_fn[i]; });
        reals(out, "shear_force", 3,
              [&](std::size_t i, unsigned int d) { return cs.sc_fs[3 * i + d]; });
        reals(out, "normal_stress", 1,
              [&](std::size_t i, unsigned int) { return cs.sc_fn[i] / cs.sc_area[i]; });
        reals(out, "shear_stress", 3,
              [&](std::size_t i, unsigned int d)
              { return 1.0 / cs.sc_area[i] * cs.sc_fs[3 * i + d]; });
        reals(out, "shear_displacement", 3,
              [&](std::size_t i, unsigned int d) { return cs.sc_us[3 * i + d]; });
        if (!cs.sc_yield.empty()) // continuously yielding joints: u_p, m
          reals(out, "plastic_shear_displacement", 1,
                [&](std::size_t i, unsigned int)
                { return cs.sc_yield[yield_state_size * i + plastic_shear_displacement]; });
        reals(out, "area", 1, [&](std::size_t i, unsigned int) { return cs.sc_area[i]; });
        integers(out, "state", [&](std::size_t i) { return cs.sc_state[i]; });
        // Numbered from 1 in the order of ContactType.
        integers(out, "type",
                 [&](std::size_t i) { return static_cast<int>(cs.type[cs.sc_contact[i]]) + 1; });
        integers(out, "joint_set", [&](std::size_t i) { return joint_set[cs.sc_contact[i]]; });
        integers(out, "joint", [&](std::size_t i) { return joint[cs.sc_contact[i]]; });
        // 0: 'Joint properties'; k: the k-th 'Joint material N' of the file.
        integers(out, "material", [&](std::size_t i) { return cs.sc_material[i]; });
        integers(out, "contact_id", [&](std::size_t i) { return id[cs.sc_contact[i]]; });
        if (water != nullptr && water->active())
        {
          // The pressure the joint's water puts on both faces there: its
          // own, or that of the phreatic surface.
          const double gamma = water->density * gravity;
          reals(out, "pore_pressure", 1,
                [&](std::size_t i, unsigned int)
                {
                  const double fixed = water->fixed_pressure(origin_of[cs.sc_contact[i]]);
                  return fixed == fixed ? fixed
                                        : water_pressure(water->table, gamma, cs.sc_position[i]);
                });
        }
        out << "      </PointData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
      });
}

} // namespace talus
