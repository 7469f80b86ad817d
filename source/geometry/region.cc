#include <talus/geometry/convex_polyhedron.h>
#include <talus/geometry/plane_cut.h>
#include <talus/geometry/region.h>

#include <cmath>
#include <stdexcept>

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
  r.is_box = true;
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

namespace
{
/// Bounds and volume of the part of `r` inside `brick`, by cutting the
/// brick with every plane of r (an empty part: zero volume, bounds of a
/// point at the brick's corner).
void clip_to_brick(ConvexRegion& r, const Box& brick)
{
  ConvexPolyhedron part = ConvexPolyhedron::box(brick.lo, brick.hi);
  const double tolerance = 1e-12 * (brick.hi - brick.lo).norm();
  for (const Plane& p : r.planes)
  {
    const PlaneCut cut = cut_by_plane(part, p, tolerance);
    if (cut.intersects)
      part = cut.below;
    else if (part.extent_along(p).first >= -tolerance)
    {
      // Wholly outside this plane: nothing of the brick is in the region.
      r.volume = 0.0;
      r.bounds = Box{brick.lo, brick.lo};
      return;
    }
  }
  r.volume = part.volume();
  r.bounds = part.bounding_box();
}
} // namespace

ConvexRegion ConvexRegion::half_space(const Vec3& point, const Vec3& normal, const Box& brick)
{
  // The region is where the normal points: its outward normal is -normal.
  return polyhedron({{point, -normal}}, brick);
}

ConvexRegion ConvexRegion::polyhedron(const std::vector<std::pair<Vec3, Vec3>>& point_normals,
                                      const Box& brick)
{
  ConvexRegion r;
  for (const auto& [point, normal] : point_normals)
  {
    const Vec3 n = normal.normalized();
    r.planes.emplace_back(n, n.dot(point));
  }
  clip_to_brick(r, brick);
  return r;
}

ConvexRegion ConvexRegion::sphere(const Vec3& centre, double radius, unsigned int facets,
                                  const Box& brick)
{
  // Normals on a Fibonacci lattice: equal steps in z, the golden angle in
  // longitude, so that the facets are about equal in size.
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  std::vector<std::pair<Vec3, Vec3>> planes;
  for (unsigned int k = 0; k < facets; ++k)
  {
    const double z = 1.0 - (2.0 * k + 1.0) / facets, rho = std::sqrt(1.0 - z * z);
    const Vec3 n(rho * std::cos(golden * k), rho * std::sin(golden * k), z);
    planes.emplace_back(centre + radius * n, n);
  }
  return polyhedron(planes, brick);
}

ConvexRegion ConvexRegion::prism(const Vec3& start, const Vec3& end,
                                 const std::vector<std::pair<double, double>>& profile)
{
  const Vec3 axis = (end - start).normalized();
  Vec3 up = Vec3::UnitZ() - axis.z() * axis;
  if (up.norm() < 1e-9)
    up = Vec3::UnitY() - axis.y() * axis;
  up.normalize();
  const Vec3 right = axis.cross(up);
  const std::size_t n = profile.size();
  if (n < 3)
    throw std::invalid_argument("has " + std::to_string(n) + " corners");
  double area = 0.0; // twice the signed area
  for (std::size_t i = 0; i < n; ++i)
    area += profile[i].first * profile[(i + 1) % n].second -
            profile[(i + 1) % n].first * profile[i].second;
  if (!(std::abs(area) > 0.0))
    throw std::invalid_argument("has no area");
  const double sign = area > 0.0 ? 1.0 : -1.0; // counter-clockwise: +1
  double size = 0.0;
  for (const auto& [u, v] : profile)
    size = std::max({size, std::abs(u), std::abs(v)});
  ConvexRegion r;
  for (std::size_t i = 0; i < n; ++i)
  {
    const auto& [u0, v0] = profile[i];
    const auto& [u1, v1] = profile[(i + 1) % n];
    const auto& [u2, v2] = profile[(i + 2) % n];
    // Every corner turns the same way as the whole polygon.
    if (sign * ((u1 - u0) * (v2 - v1) - (v1 - v0) * (u2 - u1)) < -1e-12 * size * size)
      throw std::invalid_argument("is not convex (at corner " + std::to_string((i + 1) % n + 1) +
                                  ")");
    // Outward normal of edge i, counter-clockwise: (dv, -du).
    const double du = sign * (u1 - u0), dv = sign * (v1 - v0);
    const double length = std::hypot(du, dv);
    if (!(length > 0.0))
      throw std::invalid_argument("has two equal corners");
    const Vec3 normal = (dv * right - du * up) / length;
    r.planes.emplace_back(normal, normal.dot(start + u0 * right + v0 * up));
  }
  r.planes.emplace_back(axis, axis.dot(end));
  r.planes.emplace_back(-axis, -axis.dot(start));
  r.bounds.lo = r.bounds.hi = start;
  for (const auto& [u, v] : profile)
    for (const Vec3& p : {Vec3(start + u * right + v * up), Vec3(end + u * right + v * up)})
    {
      r.bounds.lo = r.bounds.lo.cwiseMin(p);
      r.bounds.hi = r.bounds.hi.cwiseMax(p);
    }
  r.volume = 0.5 * std::abs(area) * (end - start).norm();
  return r;
}

} // namespace talus
