#include <talus/base/exceptions.h>
#include <talus/geometry/convex_polyhedron.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace talus
{

ConvexPolyhedron::ConvexPolyhedron(std::vector<Vec3> vertices,
                                   const std::vector<std::vector<unsigned int>>& faces)
    : vertices_(std::move(vertices))
{
  for (const auto& loop : faces)
  {
    face_vertices_.insert(face_vertices_.end(), loop.begin(), loop.end());
    face_start_.push_back(static_cast<unsigned int>(face_vertices_.size()));
  }
  compute_planes();
}

ConvexPolyhedron::ConvexPolyhedron(std::vector<Vec3> vertices, std::vector<unsigned int> face_start,
                                   std::vector<unsigned int> face_vertices)
    : vertices_(std::move(vertices)), face_start_(std::move(face_start)),
      face_vertices_(std::move(face_vertices))
{
  compute_planes();
}

ConvexPolyhedron ConvexPolyhedron::box(const Vec3& lo, const Vec3& hi)
{
  std::vector<Vec3> v;
  for (unsigned int k = 0; k < 8; ++k)
    v.emplace_back((k & 1) ? hi[0] : lo[0], (k & 2) ? hi[1] : lo[1], (k & 4) ? hi[2] : lo[2]);
  // Loops counter-clockwise seen from outside.
  return ConvexPolyhedron(std::move(v), {{0, 2, 3, 1},
                                         {4, 5, 7, 6},
                                         {0, 1, 5, 4},
                                         {2, 6, 7, 3},
                                         {0, 4, 6, 2},
                                         {1, 3, 7, 5}});
}

ConvexPolyhedron ConvexPolyhedron::tetrahedron(const Vec3& a, const Vec3& b, const Vec3& c,
                                               const Vec3& d)
{
  // Orient so that d lies below the face (a, b, c) as seen from outside.
  const bool positive = (b - a).cross(c - a).dot(d - a) < 0.0;
  if (positive)
    return ConvexPolyhedron({a, b, c, d}, {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}});
  return ConvexPolyhedron({a, c, b, d}, {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}});
}

ConvexPolyhedron ConvexPolyhedron::prism(const std::vector<Vec3>& base, const Vec3& axis)
{
  const unsigned int n = static_cast<unsigned int>(base.size());
  std::vector<Vec3> v(base);
  for (const Vec3& p : base)
    v.push_back(p + axis);
  std::vector<std::vector<unsigned int>> faces;
  std::vector<unsigned int> bottom, top;
  for (unsigned int i = 0; i < n; ++i)
  {
    bottom.push_back(n - 1 - i); // reversed: its outward normal is -axis
    top.push_back(n + i);
    const unsigned int j = (i + 1) % n;
    faces.push_back({i, j, n + j, n + i});
  }
  faces.push_back(bottom);
  faces.push_back(top);
  return ConvexPolyhedron(std::move(v), faces);
}

void ConvexPolyhedron::compute_planes()
{
  face_planes_.resize(n_faces());
  for (unsigned int f = 0; f < n_faces(); ++f)
  {
    // Newell's method: robust for any planar (or nearly planar) loop.
    Vec3 normal = Vec3::Zero();
    Vec3 centre = Vec3::Zero();
    const unsigned int m = face_size(f);
    for (unsigned int k = 0; k < m; ++k)
    {
      const Vec3& p = vertices_[face_vertex(f, k)];
      const Vec3& q = vertices_[face_vertex(f, (k + 1) % m)];
      normal += p.cross(q);
      centre += p;
    }
    centre /= m;
    const double length = normal.norm();
    if (length > 0.0)
      normal /= length;
    face_planes_[f] = Plane(normal, normal.dot(centre));
  }
}

std::vector<std::pair<unsigned int, unsigned int>> ConvexPolyhedron::edges() const
{
  std::vector<std::pair<unsigned int, unsigned int>> result;
  for (unsigned int f = 0; f < n_faces(); ++f)
    for (unsigned int k = 0, m = face_size(f); k < m; ++k)
    {
      const unsigned int a = face_vertex(f, k), b = face_vertex(f, (k + 1) % m);
      if (a < b) // each edge is seen once in each direction
        result.emplace_back(a, b);
    }
  std::sort(result.begin(), result.end());
  return result;
}

Box ConvexPolyhedron::bounding_box() const
{
  Box b;
  if (vertices_.empty())
    return b;
  b.lo = b.hi = vertices_[0];
  for (const Vec3& v : vertices_)
  {
    b.lo = b.lo.cwiseMin(v);
    b.hi = b.hi.cwiseMax(v);
  }
  return b;
}

std::pair<double, double> ConvexPolyhedron::extent_along(const Plane& plane) const
{
  double lo = plane.signed_distance(vertices_[0]), hi = lo;
  for (const Vec3& v : vertices_)
  {
    const double d = plane.signed_distance(v);
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  return {lo, hi};
}

double ConvexPolyhedron::volume() const
{
  // Sum of signed tetrahedra from the vertex mean to each face fan triangle.
  const Vec3 o = vertex_mean();
  double six_v = 0.0;
  for (unsigned int f = 0; f < n_faces(); ++f)
  {
    const Vec3 a = vertices_[face_vertex(f, 0)] - o;
    for (unsigned int k = 1; k + 1 < face_size(f); ++k)
    {
      const Vec3 b = vertices_[face_vertex(f, k)] - o;
      const Vec3 c = vertices_[face_vertex(f, k + 1)] - o;
      six_v += a.dot(b.cross(c));
    }
  }
  return six_v / 6.0;
}

Vec3 ConvexPolyhedron::vertex_mean() const
{
  Vec3 sum = Vec3::Zero();
  for (const Vec3& v : vertices_)
    sum += v;
  return vertices_.empty() ? sum : Vec3(sum / static_cast<double>(vertices_.size()));
}

bool ConvexPolyhedron::contains(const Vec3& x, double tol) const
{
  for (const Plane& p : face_planes_)
    if (p.signed_distance(x) > tol)
      return false;
  return true;
}

void ConvexPolyhedron::validate(const std::string& what, double relative_tol) const
{
  const auto fail = [&](const std::string& problem) {
    throw GeometryError(what + " is not a valid convex polyhedron: " + problem);
  };
  if (n_vertices() < 4 || n_faces() < 4)
    fail("it has " + std::to_string(n_vertices()) + " vertices and " + std::to_string(n_faces()) +
         " faces (a closed polyhedron needs at least 4 of each)");
  const double tol = relative_tol * size();

  // Closed and consistently oriented: every directed edge appears exactly once
  // and its reverse appears exactly once.
  std::vector<std::pair<unsigned int, unsigned int>> directed;
  for (unsigned int f = 0; f < n_faces(); ++f)
  {
    if (face_size(f) < 3)
      fail("face " + std::to_string(f) + " has fewer than 3 vertices");
    for (unsigned int k = 0, m = face_size(f); k < m; ++k)
    {
      const unsigned int a = face_vertex(f, k), b = face_vertex(f, (k + 1) % m);
      if (a >= n_vertices() || b >= n_vertices())
        fail("face " + std::to_string(f) + " refers to a vertex that does not exist");
      if (a == b)
        fail("face " + std::to_string(f) + " repeats vertex " + std::to_string(a));
      directed.emplace_back(a, b);
    }
  }
  std::sort(directed.begin(), directed.end());
  for (std::size_t i = 0; i < directed.size(); ++i)
  {
    const auto& e = directed[i];
    if (i + 1 < directed.size() && directed[i + 1] == e)
      fail("edge " + std::to_string(e.first) + "-" + std::to_string(e.second) +
           " is used twice in the same direction (faces inconsistently oriented)");
    if (!std::binary_search(directed.begin(), directed.end(), std::make_pair(e.second, e.first)))
      fail("edge " + std::to_string(e.first) + "-" + std::to_string(e.second) +
           " belongs to one face only (the surface is not closed)");
  }
  const long euler = static_cast<long>(n_vertices()) - static_cast<long>(directed.size() / 2) +
                     static_cast<long>(n_faces());
  if (euler != 2)
    fail("Euler characteristic V - E + F is " + std::to_string(euler) + ", not 2");

  for (unsigned int f = 0; f < n_faces(); ++f)
    for (unsigned int k = 0; k < face_size(f); ++k)
      if (std::abs(face_planes_[f].signed_distance(vertices_[face_vertex(f, k)])) > tol)
        fail("face " + std::to_string(f) + " is not planar");

  if (!(volume() > 0.0))
    fail("its volume is not positive (faces oriented inward, or the polyhedron is flat)");

  for (unsigned int f = 0; f < n_faces(); ++f)
    for (unsigned int i = 0; i < n_vertices(); ++i)
      if (face_planes_[f].signed_distance(vertices_[i]) > tol)
      {
        std::ostringstream s;
        s << "vertex " << i << " lies " << face_planes_[f].signed_distance(vertices_[i])
          << " m outside the plane of face " << f << " (not convex)";
        fail(s.str());
      }
}

} // namespace talus
