#pragma once

namespace talus
{

/// The joint constitutive models; one is chosen per batch of sub-contacts.
enum class JointModel : unsigned char
{
  coulomb_slip,         ///< eqs. 34-43
  continuously_yielding ///< Cundall and Lemos (1990), continuously_yielding.h
};

/// Properties of a joint material. SI units. Coulomb slip uses the first
/// block (eqs. 24-43); continuously yielding takes its stiffness minima,
/// its intrinsic friction angle and the entries after them.
struct JointProperties
{
  JointModel model = JointModel::coulomb_slip;
  double normal_stiffness = 1e10; ///< kn, Pa/m (continuously yielding: the minimum)
  double shear_stiffness = 1e10;  ///< ks, Pa/m (continuously yielding: the minimum)
  double friction_angle = 30.0;   ///< phi, degrees (also the residual; continuously
                                  ///< yielding: the intrinsic angle phi_m decays to)
  double cohesion = 0.0;          ///< c, Pa (lost at failure, eq. 37)
  double tensile_strength = 0.0;  ///< T, Pa (lost at failure, eq. 36)
  double dilation_angle = 0.0;    ///< psi, degrees, only while slipping
  double dilation_limit = 0.0;    ///< U^s_lim, m: no dilation beyond it (0: none)

  // Continuously yielding (continuously_yielding.h).
  double normal_stiffness_factor =
      0.0; ///< a_n of kn = a_n sigma_n^e_n, Pa^(1-e_n)/m (0: kn constant)
  double normal_stiffness_exponent = 0.0; ///< e_n, from 0 to less than 1
  double shear_stiffness_factor =
      0.0; ///< a_s of ks = a_s sigma_n^e_s, Pa^(1-e_s)/m (0: ks constant)
  double shear_stiffness_exponent = 0.0; ///< e_s, from 0 to 1
  double maximum_stiffness = 0.0;        ///< cap of kn and ks, Pa/m (the time step's stiffness)
  double initial_friction_angle = 30.0;  ///< phi_i, degrees: phi_m before any plastic shear
  double roughness = 0.0; ///< R, m: plastic shear displacement scale of phi_m's decay

  /// The largest normal or shear stiffness the joint can take (Pa/m), for
  /// the time step (eq. 87).
  double stiffest() const
  {
    double k = normal_stiffness > shear_stiffness ? normal_stiffness : shear_stiffness;
    if (model == JointModel::continuously_yielding && maximum_stiffness > k &&
        (normal_stiffness_factor > 0.0 || shear_stiffness_factor > 0.0))
      k = maximum_stiffness;
    return k;
  }
};

} // namespace talus
