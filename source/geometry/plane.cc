#include <talus/geometry/plane.h>

#include <cmath>

namespace talus
{

namespace
{
/// sin and cos of an angle in degrees, exact (0, 1 or -1) at the multiples
/// of 90 degrees: a vertical joint's normal then has no vertical part, and
/// a horizontal one none across (std::cos of pi/2 in radians is 6.1e-17),
/// so that cuts along the axes leave vertices on exact coordinates.
std::pair<double, double> sin_cos_degrees(double degrees)
{
  const double quarter = degrees / 90.0;
  if (quarter == std::floor(quarter) && std::abs(quarter) < 1e15)
  {
    static const double sine[4] = {0.0, 1.0, 0.0, -1.0};
    const long k = ((static_cast<long>(quarter) % 4) + 4) % 4;
    return {sine[k], sine[(k + 1) % 4]};
  }
  const double radians = degrees * (M_PI / 180.0);
  return {std::sin(radians), std::cos(radians)};
}
} // namespace

Vec3 normal_from_dip(double dip_degrees, double dip_direction_degrees)
{
  const auto [sin_dip, cos_dip] = sin_cos_degrees(dip_degrees);
  const auto [sin_azimuth, cos_azimuth] = sin_cos_degrees(dip_direction_degrees);
  // The horizontal part of the upward normal points down-dip: azimuth measured
  // clockwise from +y gives (sin a, cos a) in (x, y).
  return Vec3(sin_dip * sin_azimuth, sin_dip * cos_azimuth, cos_dip);
}

} // namespace talus
