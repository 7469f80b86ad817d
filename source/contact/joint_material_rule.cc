#include <talus/contact/contact_origin.h>
#include <talus/contact/joint_material_rule.h>

#include <algorithm>

namespace talus
{

bool JointMaterialRule::trivial() const
{
  const auto unset = [](unsigned char m) { return m == none || m == 0; };
  return std::all_of(of_joint_set.begin(), of_joint_set.end(), unset) &&
         std::all_of(of_joint.begin(), of_joint.end(), unset) &&
         std::all_of(of_group_pair.begin(), of_group_pair.end(), unset);
}

unsigned char JointMaterialRule::material(const BlockModel& m, const ContactSet& cs,
                                          unsigned int c) const
{
  const int origin = contact_joint_origin(m, cs, c);
  if (origin > 0 && std::size_t(origin) <= of_joint_set.size() && of_joint_set[origin - 1] != none)
    return of_joint_set[origin - 1];
  if (origin < 0 && std::size_t(-origin) <= of_joint.size() && of_joint[-origin - 1] != none)
    return of_joint[-origin - 1];
  const unsigned int ga = m.group[cs.block_a[c]], gb = m.group[cs.block_b[c]];
  if (ga < n_groups && gb < n_groups && of_group_pair[ga * n_groups + gb] != none)
    return of_group_pair[ga * n_groups + gb];
  return 0;
}

} // namespace talus
