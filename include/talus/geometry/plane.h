#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace talus
{

using Vec3 = Eigen::Vector3d;

/// An oriented plane {x : normal . x = offset} with a unit normal. The signed
/// distance is positive on the side the normal points to.
struct Plane
{
  Vec3 normal = Vec3::UnitZ();
  double offset = 0.0;

  Plane() = default;
  Plane(const Vec3& unit_normal, double offset_) : normal(unit_normal), offset(offset_) {}

  /// The plane through `point` with the given (not necessarily unit) normal.
  static Plane through(const Vec3& point, const Vec3& any_normal)
  {
    const Vec3 n = any_normal.normalized();
    return Plane(n, n.dot(point));
  }

  double signed_distance(const Vec3& x) const { return normal.dot(x) - offset; }

  Plane flipped() const { return Plane(-normal, -offset); }
};

/// Unit normal (pointing upward, z >= 0) of a geological plane given by dip and
/// dip direction in degrees. Convention: x east, y north, z up; the dip
/// direction is the azimuth of the down-dip line, clockwise from north (+y).
Vec3 normal_from_dip(double dip_degrees, double dip_direction_degrees);

/// Axis-aligned box, used for envelopes (bounding boxes) and regions.
struct Box
{
  Vec3 lo = Vec3::Constant(0.0);
  Vec3 hi = Vec3::Constant(0.0);

  bool contains(const Vec3& x, double tol = 0.0) const
  {
    return (x.array() >= lo.array() - tol).all() && (x.array() <= hi.array() + tol).all();
  }
  bool overlaps(const Box& other, double tol = 0.0) const
  {
    return (lo.array() <= other.hi.array() + tol).all() &&
           (other.lo.array() <= hi.array() + tol).all();
  }
  double volume() const { return (hi - lo).prod(); }
  double diagonal() const { return (hi - lo).norm(); }
};

} // namespace talus
