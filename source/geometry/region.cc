#include <talus/geometry/region.h>

#include <cmath>

namespace talus
{

ConvexRegion ConvexRegion::box(const Box& b)
{
  ConvexRegion r;
  for (unsigned int d = 0; d < 3; ++d)
  {
    Vec3 n = Vec3::Zero();
    n[d] = 1.0;
    r.planes.emplace_back(n, b.hi[d]);
    r.planes.emplace_back(-n, -b.lo[d]);
  }
  r.bounds = b;
  r.volume = b.volume();
  return r;
}

ConvexRegion ConvexRegion::cylinder(const Vec3& start, const Vec3& end, double radius,
                                    unsigned int sides)
{
  ConvexRegion r;
  const Vec3 axis = (end - start).normalized();
  const double length = (end - start).norm();
  // In-plane basis: `down` is the direction closest to -z, so that one flat side
  // forms the tunnel floor for a horizontal axis.
  Vec3 down = -Vec3::UnitZ() + axis.z() * axis;
  if (down.norm() < 1e-12)
    down = axis.unitOrthogonal();
  down.normalize();
  const Vec3 side = axis.cross(down);
  const double apothem = radius * std::cos(M_PI / sides);
  for (unsigned int k = 0; k < sides; ++k)
  {
    const double a = 2.0 * M_PI * k / sides;
    const Vec3 n = std::cos(a) * down + std::sin(a) * side;
    r.planes.emplace_back(n, n.dot(start) + apothem);
  }
  r.planes.emplace_back(axis, axis.dot(end));
  r.planes.emplace_back(-axis, -axis.dot(start));
  // Bounds from the prism corners (at the circumradius).
  r.bounds.lo = r.bounds.hi = start;
  for (unsigned int k = 0; k < sides; ++k)
  {
    const double a = 2.0 * M_PI * (k + 0.5) / sides;
    const Vec3 corner = radius * (std::cos(a) * down + std::sin(a) * side);
    for (const Vec3& p : {Vec3(start + corner), Vec3(end + corner)})
    {
      r.bounds.lo = r.bounds.lo.cwiseMin(p);
      r.bounds.hi = r.bounds.hi.cwiseMax(p);
    }
  }
  // Polygon of `sides` triangles with apex angle 2 pi / sides at the circumradius.
  r.volume = 0.5 * sides * radius * radius * std::sin(2.0 * M_PI / sides) * length;
  return r;
}

} // namespace talus
