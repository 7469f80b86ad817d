#pragma once

#include <talus/joint/continuously_yielding.h>
#include <talus/joint/coulomb_slip.h>
#include <talus/joint/joint_properties.h>

#include <vector>

namespace talus
{

/// Applies the joint's constitutive model to a whole batch of sub-contacts:
/// the model is chosen here, once per batch, so the loop over sub-contacts
/// inside each model has no dispatch. Returns the frictional work of the
/// step (J), an exact sum.
inline ExactSum apply_joint_model(const JointProperties& joint, SubContactBatch& batch)
{
  switch (joint.model)
  {
  case JointModel::coulomb_slip:
    return coulomb_slip(joint, batch);
  case JointModel::continuously_yielding:
    return continuously_yielding(std::vector<JointProperties>{joint}, batch);
  }
  return ExactSum();
}

/// The same with a joint material per sub-contact (batch.material indexes
/// `joints`): each model takes its own sub-contacts in one pass over the
/// batch (and a model no material uses is not run at all).
inline ExactSum apply_joint_model(const std::vector<JointProperties>& joints,
                                  SubContactBatch& batch)
{
  bool coulomb = false, yielding = false;
  for (const JointProperties& j : joints)
  {
    coulomb |= j.model == JointModel::coulomb_slip;
    yielding |= j.model == JointModel::continuously_yielding;
  }
  ExactSum work;
  if (coulomb || !yielding)
    work = coulomb_slip(joints, batch);
  if (yielding)
    work += continuously_yielding(joints, batch);
  return work;
}

} // namespace talus
