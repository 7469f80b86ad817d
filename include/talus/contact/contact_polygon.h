#pragma once

// The contact region of a face-to-face (or edge-to-face) contact on the
// common plane: convex polygons in plane coordinates, the overlap of the two
// blocks' facing sides, and the share of its area each vertex (one
// sub-contact) carries.
//
// In jointed rock most faces share edges with their neighbours' faces, so
// the two polygons clipped here often have coincident or collinear edges.
// Every test is made with a length tolerance (relative to the faces' size),
// and the region is cleared of coincident and collinear vertices, so that
// round-off neither adds vertices nor moves the sub-contacts' areas.

#include <Eigen/Core>

#include <vector>

namespace talus
{

using Point2 = Eigen::Vector2d;

/// Twice the signed area of the triangle (o, a, b): positive when it turns
/// counter-clockwise.
inline double cross2(const Point2& o, const Point2& a, const Point2& b)
{
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

/// Lengths below this fraction of the faces' size count as round-off in the
/// contact region: 1e-9 of a 10 m face is 10 nm, far below any joint
/// aperture, and far above the round-off of coordinates even a few km from
/// the origin.
constexpr double contact_polygon_relative_tolerance = 1e-9;

/// Convex hull, counter-clockwise, of a few points, cleared of coincident and
/// collinear vertices within `eps` (a length). Fewer than three points come
/// back as a segment or a point.
std::vector<Point2> convex_hull(std::vector<Point2> points, double eps);

/// Removes from a convex polygon (counter-clockwise) the vertices within
/// `eps` of the one before them and those within `eps` of the line through
/// their neighbours (collinear, or a notch made by round-off), until none
/// is left. What remains may be a segment or a point.
void remove_spurious_vertices(std::vector<Point2>& polygon, double eps);

/// The part of `subject` (a convex polygon, a segment or a point) inside the
/// convex polygon `clip` (counter-clockwise), by Sutherland-Hodgman with a
/// tolerance: a point within `eps` of a clip edge's line lies on it (kept,
/// and no crossing is made next to it), so edges that coincide with the
/// clip's give no spurious vertices; then remove_spurious_vertices().
std::vector<Point2> clip_convex(std::vector<Point2> subject, const std::vector<Point2>& clip,
                                double eps);

/// Size of two point sets: the diagonal of their common bounding box.
double polygon_size(const std::vector<Point2>& a, const std::vector<Point2>& b);

/// Signed area (positive counter-clockwise).
double polygon_area(const std::vector<Point2>& polygon);

/// Area centroid of a polygon of positive area.
Point2 polygon_centroid(const std::vector<Point2>& polygon);

/// The area each vertex of a convex polygon carries as a sub-contact: the
/// fan of triangles from the area centroid, each vertex taking half of the
/// two triangles beside it. The shares add up to the area and their centre
/// is the area centroid (so a uniform closure gives the force and moment of
/// a uniform pressure whatever the shape), and a vertex added on an edge
/// does not move that centre. Zeros when the area is not positive.
std::vector<double> vertex_areas(const std::vector<Point2>& polygon);

} // namespace talus
