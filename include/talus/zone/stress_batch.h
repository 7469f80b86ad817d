#pragma once

namespace talus
{

/// Plastic state flags of a zone (or Gauss point).
enum ZonePlasticState : unsigned char
{
  zone_elastic = 0,
  shear_now = 1,   ///< at the shear yield surface this step
  tension_now = 2, ///< at the tension cut-off this step
  shear_past = 4,  ///< has yielded in shear before
  tension_past = 8 ///< has yielded in tension before
};

/// The arrays of one batch of zones (or Gauss points) that a zone model
/// reads and writes: structure of arrays, so the model is chosen once per
/// batch and its loop has no dispatch. Symmetric tensors are stored as six
/// numbers in the order xx, yy, zz, xy, yz, zx (tensor components, not
/// engineering shear strains).
struct StressBatch
{
  unsigned int size = 0;
  /// Strain increment of this step (eq. 58 times dt), 6 per zone, m/m.
  const double* strain_increment = nullptr;
  /// Stress, 6 per zone, Pa, tension positive. On entry the stress of the
  /// last step already turned with the zone (Jaumann correction); on exit
  /// the new stress.
  double* stress = nullptr;
  /// Plastic state flags, 1 per zone (may be nullptr for elastic models).
  unsigned char* state = nullptr;
  /// Plastic volumetric strain increment of this step, 1 per zone (for
  /// nodal mixed discretization); may be nullptr when not needed.
  double* plastic_volumetric = nullptr;
};

} // namespace talus
