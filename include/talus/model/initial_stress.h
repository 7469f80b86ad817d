#pragma once

namespace talus
{

/// The in-situ stress of a scene: sigma = base + gradient (z - z0) for each
/// of the six components xx, yy, zz, xy, yz, zx (Pa, tension positive;
/// gradient in Pa/m). Zones start from it, and so do the joints that exist
/// at the start.
struct InitialStress
{
  double base[6] = {0, 0, 0, 0, 0, 0};
  double gradient[6] = {0, 0, 0, 0, 0, 0};
  double z0 = 0.0;

  /// The stress at height z (m), six components.
  void at(double z, double* sigma) const
  {
    for (int c = 0; c < 6; ++c)
      sigma[c] = base[c] + gradient[c] * (z - z0);
  }
};

} // namespace talus
