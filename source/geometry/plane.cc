#include <talus/geometry/plane.h>

#include <cmath>

namespace talus
{

Vec3 normal_from_dip(double dip_degrees, double dip_direction_degrees)
{
  const double deg = M_PI / 180.0;
  const double dip = dip_degrees * deg;
  const double azimuth = dip_direction_degrees * deg;
  // The horizontal part of the upward normal points down-dip: azimuth measured
  // clockwise from +y gives (sin a, cos a) in (x, y).
  return Vec3(std::sin(dip) * std::sin(azimuth), std::sin(dip) * std::cos(azimuth),
              std::cos(dip));
}

} // namespace talus
