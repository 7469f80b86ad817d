#pragma once

#include <talus/geometry/convex_polyhedron.h>

namespace talus
{

/// Outcome of cutting a convex polyhedron by a plane.
struct PlaneCut
{
  /// True when vertices lie strictly on both sides of the plane (beyond the
  /// tolerance); only then are `above` and `below` filled.
  bool intersects = false;
  ConvexPolyhedron above; ///< part on the side the plane normal points to
  ConvexPolyhedron below; ///< part on the other side
};

/// Cuts `polyhedron` by `plane`. Vertices closer than `tolerance` (m) to the
/// plane count as lying on it: they belong to both pieces and never create a
/// sliver, so a plane through a vertex, an edge or a face leaves the block
/// whole. Both pieces are convex; the cap face is shared exactly. The
/// pieces' faces keep the face origins of the faces they came from, and
/// the cap takes `cap_origin`.
PlaneCut cut_by_plane(const ConvexPolyhedron& polyhedron, const Plane& plane, double tolerance,
                      int cap_origin = 0);

} // namespace talus
