#pragma once

#include <talus/joint/coulomb_slip.h>
#include <talus/joint/joint_properties.h>

namespace talus
{

/// Applies the joint's constitutive model to a whole batch of sub-contacts:
/// the model is chosen here, once per batch, so the loop over sub-contacts
/// inside each model has no dispatch. A new model (continuously yielding)
/// adds a case. Returns the frictional work of the step (J).
inline double apply_joint_model(const JointProperties& joint, SubContactBatch& batch)
{
  switch (joint.model)
  {
  case JointModel::coulomb_slip:
    return coulomb_slip(joint, batch);
  }
  return 0.0;
}

/// The same with a joint material per sub-contact (batch.material indexes
/// `joints`). Every material is Coulomb slip today; when materials of
/// other models come, the sub-contacts are taken in one batch per model.
inline double apply_joint_model(const std::vector<JointProperties>& joints,
                                SubContactBatch& batch)
{
  return coulomb_slip(joints, batch);
}

} // namespace talus
