#pragma once

// The continuously yielding joint model of Cundall and Lemos (1990), as
// 3DEC describes it ("Continuously Yielding" joint model): a joint that
// yields a little from the first shear on, whose strength falls with the
// plastic shear it has taken, and whose stiffnesses grow with the normal
// stress. What talus computes, sub-contact by sub-contact (SI units,
// sigma_n = F^n / A compression positive, tau = F^s / A):
//
//   Normal stiffness   kn(sigma_n) = a_n sigma_n^e_n, kept between the
//                      'Normal stiffness' kn_min and 'Maximum stiffness';
//                      the normal stress follows d sigma_n = kn(sigma_n) dc
//                      for a closure c (c = -U^n less the normal offset).
//                      Integrated in closed form, so that sigma_n is a
//                      function of the total closure (NormalStressLaw):
//                      no drift, and the joint unloads along the curve it
//                      loaded on. No tension: c <= 0 opens the joint.
//   Shear stiffness    ks(sigma_n) = a_s sigma_n^e_s between the 'Shear
//                      stiffness' and 'Maximum stiffness' (a_s = 0: ks is
//                      the 'Shear stiffness').
//   Bounding strength  tau_m = sigma_n tan(phi_m): what the joint would
//                      carry after long shear at this normal stress.
//   Its friction       phi_m = phi + (phi_i - phi) exp(-u_p / R): the
//                      solution of d phi_m = -(phi_m - phi) du_p / R, with
//                      phi_i the 'Initial friction angle', phi the
//                      intrinsic 'Friction angle', R the 'Roughness' (m),
//                      u_p the accumulated plastic shear displacement.
//   Shear increment    d tau = F ks du_s along the increment, with the
//                      tangent fraction F = (1 - tau/tau_m) / (1 - r),
//                      tau/tau_m taken with the sign of the increment
//                      (the stress component along it over tau_m), kept in
//                      [0, 1]; |tau| never exceeds tau_m.
//   Plastic part       du_p = (1 - F) |du_s|.
//   Reversal           r starts at 0; when the shear increment turns back
//                      (more than 90 degrees from the last one), r becomes
//                      tau/tau_m in the new direction, at most 0.75, so
//                      that F starts at 1 again (elastic unloading) and
//                      the joint yields again as tau nears tau_m.
// Cohesion, tensile strength and dilation do not enter. In three
// dimensions the loading direction is the unit vector of the last shear
// increment; for shear along one line the rules reduce to the model's
// one-dimensional form.

#include <talus/joint/coulomb_slip.h>
#include <talus/joint/joint_properties.h>

#include <vector>

namespace talus
{

/// State of a continuously yielding sub-contact: this many doubles each
/// in SubContactBatch::yield (ContactSet::sc_yield).
constexpr unsigned int yield_state_size = 5;
/// Their meaning, by offset.
enum YieldStateEntry : unsigned int
{
  plastic_shear_displacement = 0, ///< u_p, m
  reversal_ratio = 1,             ///< r
  loading_direction = 2           ///< unit vector of the last shear increment (3; zero: none yet)
};

/// sigma_n as a function of closure for kn = a_n sigma_n^e_n between
/// kn_min and kn_max: linear (kn_min) up to sigma_t where a_n sigma^e_n
/// reaches kn_min, then sigma^(1-e_n) = sigma_t^(1-e_n) + (1-e_n) a_n (c -
/// c_t) up to sigma_u where it reaches kn_max, then linear (kn_max).
struct NormalStressLaw
{
  double k_min = 1.0, a = 0.0, e = 0.0, k_max = 1.0;
  double sigma_t = 0.0, c_t = 0.0, sigma_u = 0.0, c_u = 0.0;

  static NormalStressLaw of(const JointProperties& joint);
  /// Normal stress (Pa) at closure c (m, > 0).
  double stress(double c) const;
  /// The closure (m) that carries sigma (Pa, >= 0).
  double closure(double sigma) const;
  /// Tangent stiffness (Pa/m) at sigma.
  double stiffness(double sigma) const;
  /// Elastic energy per unit area stored at sigma (J/m^2): the integral
  /// of sigma dc.
  double energy(double sigma) const;
};

/// Shear stiffness (Pa/m) of a continuously yielding joint at sigma_n.
double cy_shear_stiffness(const JointProperties& joint, double sigma_n);

/// The model above on the sub-contacts of the batch whose material
/// (batch.material, an index into `joints`) is continuously yielding;
/// the others are left alone. Needs batch.yield. Returns the work
/// dissipated by yielding this step (J), an exact sum.
ExactSum continuously_yielding(const std::vector<JointProperties>& joints, SubContactBatch& batch);

/// Elastic energy (J) a sub-contact of a continuously yielding joint
/// holds: normal force fn, squared shear force fs2, area.
double cy_stored_energy(const JointProperties& joint, double fn, double fs2, double area);

} // namespace talus
