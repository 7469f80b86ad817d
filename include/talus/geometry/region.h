#pragma once

#include <talus/geometry/plane.h>

#include <utility>
#include <vector>

namespace talus
{

/// A convex region of space as an intersection of half-spaces
/// {x : plane.signed_distance(x) <= 0}, with its bounding box. Excavations,
/// groups and fine-mesh regions: a box, a cylinder approximated by a
/// polygonal prism, a half-space, a polyhedron given by its planes, a
/// prism of a convex profile along an axis (a tunnel's section), or a
/// sphere approximated by tangent planes.
struct ConvexRegion
{
  std::vector<Plane> planes; ///< outward normals
  Box bounds;
  bool is_box = false; ///< made by box(): `bounds` is the region

  ConvexRegion() = default;
  /// The box (so that a Box stands wherever a region is asked for).
  ConvexRegion(const Box& b) { *this = box(b); }

  static ConvexRegion box(const Box& box);

  /// The half-space on the side `normal` points to from the plane through
  /// `point`, within `brick` (its bounds and volume are of that part).
  static ConvexRegion half_space(const Vec3& point, const Vec3& normal, const Box& brick);

  /// The intersection of half-spaces, each given by a point on its plane
  /// and its outward normal, within `brick` (bounds and volume of that part).
  static ConvexRegion polyhedron(const std::vector<std::pair<Vec3, Vec3>>& point_normals,
                                 const Box& brick);

  /// Right prism from `start` to `end` of a convex polygon given in the
  /// plane across the axis, counter-clockwise or clockwise: u to the right
  /// looking along the axis, v up (the component of +z across the axis;
  /// for a vertical axis, of +y), m from the axis. Throws std::invalid_argument
  /// for a polygon that is not convex or has no area.
  static ConvexRegion prism(const Vec3& start, const Vec3& end,
                            const std::vector<std::pair<double, double>>& profile);

  /// Right prism with `sides` faces inscribed in the circle of `radius` (m)
  /// about the axis from `start` to `end`: a tunnel. One side face is
  /// centred on the direction closest to -z (the invert is flat).
  static ConvexRegion cylinder(const Vec3& start, const Vec3& end, double radius,
                               unsigned int sides);

  /// The convex polyhedron of `facets` planes tangent to the sphere of
  /// `radius` (m) about `centre`, their normals spread evenly over it,
  /// within `brick`: a sphere as closely as `facets` allows, never inside
  /// it.
  static ConvexRegion sphere(const Vec3& centre, double radius, unsigned int facets,
                             const Box& brick);

  bool contains(const Vec3& x, double tol = 0.0) const
  {
    for (const Plane& p : planes)
      if (p.signed_distance(x) > tol)
        return false;
    return true;
  }

  /// Whether x is in the region, its boundary included: a box's exactly by
  /// its corners, another shape's to 1e-9 of its bounds' diagonal (a
  /// point on a face given as a plane through a point is not lost to
  /// round-off).
  bool holds(const Vec3& x) const
  {
    return is_box ? bounds.contains(x) : contains(x, 1e-9 * bounds.diagonal());
  }

  /// Exact volume of the region (m^3): box volume or prism area times length.
  double volume = 0.0;
};

} // namespace talus
