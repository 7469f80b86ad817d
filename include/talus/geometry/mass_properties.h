#pragma once

#include <talus/geometry/convex_polyhedron.h>

#include <Eigen/Core>

namespace talus
{

/// Volume, centroid and inertia of a polyhedron of unit density. Multiply the
/// inertia by the density (kg/m^3) to get kg m^2.
struct MassProperties
{
  double volume = 0.0;                                     ///< m^3
  Vec3 centroid = Vec3::Zero();                            ///< m
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();       ///< m^5, about the centroid
  Vec3 principal_moments = Vec3::Zero();                   ///< m^5, ascending
  Eigen::Matrix3d principal_axes = Eigen::Matrix3d::Zero(); ///< columns, right-handed
};

/// Exact mass properties: the polyhedron is split into tetrahedra from an
/// interior point to each face triangle and their exact first and second
/// moments are summed.
MassProperties compute_mass_properties(const ConvexPolyhedron& polyhedron);

} // namespace talus
