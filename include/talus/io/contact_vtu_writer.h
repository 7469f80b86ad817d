#pragma once

#include <talus/contact/contact_set.h>
#include <talus/io/vtu_encoding.h>
#include <talus/model/block_model.h>
#include <talus/model/water_table.h>

#include <string>
#include <vector>

namespace talus
{

/// The subsection numbers that name the joints in the contact output:
/// `joint_set_number[i]` is N of 'Joint set N' for the scene's i-th joint
/// set, `joint_number[j]` N of 'Joint N' for its j-th single joint.
struct JointNumbers
{
  std::vector<int> joint_set_number, joint_number;
};

/// Writes every sub-contact as a point (VTK vertex cell) with: the plane's
/// `normal`; `normal_force` (N, compression positive) and `normal_stress`
/// (Pa, the force over the area); `shear_force` (N) and `shear_stress`
/// (Pa), vectors; `shear_displacement` (m, the total U^s, a vector);
/// `area` (m^2); `state` (0 elastic, 1 slipping, 2 open; +4 once failed);
/// the contact `type` (1 vertex-face, 2 edge-edge, 3 edge-face, 4
/// face-face, 5 vertex-edge, 6 vertex-vertex); `joint_set` and `joint` (N
/// of the 'Joint set N' or 'Joint N' whose plane the contact lies on, 0 for
/// none: contacts made by motion, or between faces of different joints);
/// and `contact_id` (the contact's slot, which it keeps while it lasts;
/// with `ids_in_pair_order`, its place among the live contacts ordered by
/// their blocks, which does not depend on how slots were reused: a single
/// frame, such as a mechanism, made alike from states of different slot
/// layouts). With `water` active, also `pore_pressure` (Pa): the water
/// pressure at the sub-contact's position. `subcontacts`: the sub-contacts
/// to write (a rank's share); null: all.
void write_contacts_vtu(const std::string& path, const ContactSet& contacts,
                        const BlockModel& model, const JointNumbers& joints,
                        VtuEncoding encoding = VtuEncoding::binary,
                        const WaterSpec* water = nullptr, double gravity = 0.0,
                        const std::vector<unsigned int>* subcontacts = nullptr,
                        bool ids_in_pair_order = false);

} // namespace talus
