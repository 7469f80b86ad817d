#pragma once

#include <talus/geometry/plane.h>

#include <vector>

namespace talus
{

/// A convex region of space as an intersection of half-spaces
/// {x : plane.signed_distance(x) <= 0}, with its bounding box. Used for
/// excavations: a box, or a cylinder approximated by a polygonal prism.
struct ConvexRegion
{
  std::vector<Plane> planes; ///< outward normals
  Box bounds;

  static ConvexRegion box(const Box& box);

  /// Right prism with `sides` faces inscribed in the circle of `radius` (m)
  /// about the axis from `start` to `end`: a tunnel. One side face is
  /// centred on the direction closest to -z (the invert is flat).
  static ConvexRegion cylinder(const Vec3& start, const Vec3& end, double radius,
                               unsigned int sides);

  bool contains(const Vec3& x, double tol = 0.0) const
  {
    for (const Plane& p : planes)
      if (p.signed_distance(x) > tol)
        return false;
    return true;
  }

  /// Exact volume of the region (m^3): box volume or prism area times length.
  double volume = 0.0;
};

} // namespace talus
