#pragma once

namespace talus
{

/// The constitutive models of zones; one is chosen per batch of zones.
enum class ZoneModel
{
  elastic,     ///< isotropic, eq. 59
  mohr_coulomb ///< shear yield with tension cut-off, non-associated flow
};

/// The zone type of a deformable block.
enum class ZoneElement { tet4, tet10, hex_mixed };

/// Material of the zones of a deformable block. SI units; stresses are
/// positive in tension (compression negative), as in the manual.
struct ZoneMaterial
{
  ZoneModel model = ZoneModel::elastic;
  double density = 2650.0;        ///< kg/m^3
  double bulk_modulus = 3.333e10; ///< K, Pa
  double shear_modulus = 2.5e10;  ///< G, Pa
  double friction_angle = 30.0;   ///< phi, degrees (Mohr-Coulomb)
  double dilation_angle = 0.0;    ///< psi, degrees (Mohr-Coulomb, non-associated when psi < phi)
  double cohesion = 0.0;          ///< c, Pa (Mohr-Coulomb)
  double tensile_strength = 0.0;  ///< sigma_t, Pa (Mohr-Coulomb; capped at c / tan(phi))
  /// Nodal mixed discretization (eqs. 68-76) for the zones of this material:
  /// volumetric strain and plastic pressure averaged at the gridpoints, so
  /// that constant-strain tetrahedra do not lock in incompressible flow.
  bool nodal_mixed = false;
  ZoneElement element = ZoneElement::tet4; ///< zone type (tet10: 10-node zones, 4 Gauss points)

  /// Young's modulus and Poisson's ratio from K and G.
  double young() const
  {
    return 9.0 * bulk_modulus * shear_modulus / (3.0 * bulk_modulus + shear_modulus);
  }
  double poisson() const
  {
    return (3.0 * bulk_modulus - 2.0 * shear_modulus) /
           (2.0 * (3.0 * bulk_modulus + shear_modulus));
  }
  /// Sets K and G from Young's modulus E (Pa) and Poisson's ratio nu.
  void set_young_poisson(double E, double nu)
  {
    bulk_modulus = E / (3.0 * (1.0 - 2.0 * nu));
    shear_modulus = E / (2.0 * (1.0 + nu));
  }
};

} // namespace talus
