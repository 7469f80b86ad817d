#pragma once

#include <talus/contact/contact_set.h>
#include <talus/model/block_model.h>

#include <vector>

namespace talus
{

/// Which joint material (an index into the solver's list; 0 is `Joint
/// properties`) a contact takes, decided once when the contact is made: the
/// material of the joint set or single joint whose plane it lies on
/// (contact_joint_origin), else that of the pair of its blocks' groups,
/// else 0. So joints cut at build time keep their set's material, and
/// contacts that motion makes later (or on excavation faces) take the
/// group pair's.
struct JointMaterialRule
{
  static constexpr unsigned char none = 255;
  std::vector<unsigned char> of_joint_set; ///< per joint set of the scene; none: no rule
  std::vector<unsigned char> of_joint;     ///< per single joint
  unsigned int n_groups = 0;
  std::vector<unsigned char> of_group_pair; ///< n_groups^2, symmetric; none: no rule

  /// True when every contact takes material 0.
  bool trivial() const;
  unsigned char material(const BlockModel& blocks, const ContactSet& contacts,
                         unsigned int c) const;
};

} // namespace talus
