#pragma once

namespace talus
{

/// The moduli of Rayleigh's viscous stress (below), times beta / dt (Pa):
/// lambda and 2 G of eq. 59.
struct ViscousModuli
{
  double lambda = 0.0, two_g = 0.0;
  ViscousModuli() = default;
  ViscousModuli(double bulk_modulus, double shear_modulus, double beta_over_dt)
      : lambda(beta_over_dt * (bulk_modulus - 2.0 / 3.0 * shear_modulus)),
        two_g(2.0 * beta_over_dt * shear_modulus)
  {
  }
};

/// The stiffness-proportional stress of Rayleigh damping at n stress
/// points: beta times the elastic stress rate of their strain increments
/// `de` (eq. 58 times dt, 6 per point: xx, yy, zz, xy, yz, zx, tensor
/// components) over the step dt, that is (beta / dt) (lambda tr(de) I +
/// 2 G de) with the isotropic moduli of eq. 59 (plastic zones too: the
/// damping is of the elastic stiffness), into `stress` (6 per point, Pa).
/// The kernels' fused passes (tet4_nodal_forces_viscous) take it in the
/// same operations; compiled with them (in the library), it rounds as they
/// do.
void viscous_stress(unsigned int n, double bulk_modulus, double shear_modulus, double beta_over_dt,
                    const double* de, double* stress);

} // namespace talus
