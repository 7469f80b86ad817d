#pragma once

namespace talus
{

/// Properties of a Coulomb-slip joint (eqs. 24-43). SI units.
/// The joint constitutive models; one is chosen per batch of sub-contacts.
enum class JointModel
{
  coulomb_slip ///< eqs. 34-43
};

struct JointProperties
{
  JointModel model = JointModel::coulomb_slip;
  double normal_stiffness = 1e10; ///< kn, Pa/m
  double shear_stiffness = 1e10;  ///< ks, Pa/m
  double friction_angle = 30.0;   ///< phi, degrees (also the residual)
  double cohesion = 0.0;          ///< c, Pa (lost at failure, eq. 37)
  double tensile_strength = 0.0;  ///< T, Pa (lost at failure, eq. 36)
  double dilation_angle = 0.0;    ///< psi, degrees, only while slipping
  double dilation_limit = 0.0;    ///< U^s_lim, m: no dilation beyond it (0: none)
};

} // namespace talus
