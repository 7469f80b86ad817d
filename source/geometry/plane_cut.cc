#include <talus/geometry/plane_cut.h>

#include <algorithm>
#include <cmath>

namespace talus
{

namespace
{

/// One piece under construction: face loops that index the shared vertex
/// array (original vertices followed by the edge intersections).
struct PieceBuilder
{
  std::vector<unsigned int> face_start{0};
  std::vector<unsigned int> face_vertices;
  std::vector<int> face_origins;

  void add_face(const std::vector<unsigned int>& loop, int origin)
  {
    face_vertices.insert(face_vertices.end(), loop.begin(), loop.end());
    face_start.push_back(static_cast<unsigned int>(face_vertices.size()));
    face_origins.push_back(origin);
  }

  /// Keeps only referenced vertices, renumbered in order of first use.
  ConvexPolyhedron build(const std::vector<Vec3>& all_vertices)
  {
    std::vector<int> new_index(all_vertices.size(), -1);
    std::vector<Vec3> vertices;
    for (unsigned int& v : face_vertices)
    {
      if (new_index[v] < 0)
      {
        new_index[v] = static_cast<int>(vertices.size());
        vertices.push_back(all_vertices[v]);
      }
      v = static_cast<unsigned int>(new_index[v]);
    }
    ConvexPolyhedron piece(std::move(vertices), std::move(face_start), std::move(face_vertices));
    piece.set_face_origins(std::move(face_origins));
    return piece;
  }
};

/// Twice the area of a loop (Newell), used to discard faces that collapsed
/// onto the cutting plane.
double twice_area(const std::vector<Vec3>& vertices, const std::vector<unsigned int>& loop)
{
  Vec3 n = Vec3::Zero();
  for (std::size_t k = 0; k < loop.size(); ++k)
    n += vertices[loop[k]].cross(vertices[loop[(k + 1) % loop.size()]]);
  return n.norm();
}

} // namespace

PlaneCut cut_by_plane(const ConvexPolyhedron& p, const Plane& plane, double tolerance,
                      int cap_origin)
{
  PlaneCut result;
  const unsigned int nv = p.n_vertices();
  std::vector<double> distance(nv);
  std::vector<int> side(nv);
  bool any_above = false, any_below = false;
  for (unsigned int i = 0; i < nv; ++i)
  {
    distance[i] = plane.signed_distance(p.vertex(i));
    side[i] = distance[i] > tolerance ? 1 : (distance[i] < -tolerance ? -1 : 0);
    any_above |= side[i] > 0;
    any_below |= side[i] < 0;
  }
  if (!(any_above && any_below))
    return result;
  result.intersects = true;

  std::vector<Vec3> vertices = p.vertices();
  // Intersection vertex of each crossing edge, found again from the face on
  // the other side of the edge (few edges per block: a linear search is fastest).
  std::vector<std::pair<std::pair<unsigned int, unsigned int>, unsigned int>> crossing;
  const auto intersection = [&](unsigned int a, unsigned int b)
  {
    const auto key = std::make_pair(std::min(a, b), std::max(a, b));
    for (const auto& c : crossing)
      if (c.first == key)
        return c.second;
    const double t = distance[a] / (distance[a] - distance[b]);
    vertices.push_back(p.vertex(a) + t * (p.vertex(b) - p.vertex(a)));
    const unsigned int index = static_cast<unsigned int>(vertices.size()) - 1;
    crossing.emplace_back(key, index);
    return index;
  };

  PieceBuilder above, below;
  std::vector<unsigned int> loop_above, loop_below;
  const double area_tol = tolerance * p.size();
  for (unsigned int f = 0; f < p.n_faces(); ++f)
  {
    loop_above.clear();
    loop_below.clear();
    const unsigned int m = p.face_size(f);
    for (unsigned int k = 0; k < m; ++k)
    {
      const unsigned int a = p.face_vertex(f, k), b = p.face_vertex(f, (k + 1) % m);
      if (side[a] >= 0)
        loop_above.push_back(a);
      if (side[a] <= 0)
        loop_below.push_back(a);
      if (side[a] * side[b] < 0)
      {
        const unsigned int x = intersection(a, b);
        loop_above.push_back(x);
        loop_below.push_back(x);
      }
    }
    if (loop_above.size() >= 3 && twice_area(vertices, loop_above) > area_tol)
      above.add_face(loop_above, p.face_origin(f));
    if (loop_below.size() >= 3 && twice_area(vertices, loop_below) > area_tol)
      below.add_face(loop_below, p.face_origin(f));
  }

  // The cap: every vertex on the plane, ordered by angle about their mean.
  std::vector<unsigned int> cap;
  for (unsigned int i = 0; i < nv; ++i)
    if (side[i] == 0)
      cap.push_back(i);
  for (const auto& c : crossing)
    cap.push_back(c.second);
  Vec3 centre = Vec3::Zero();
  for (unsigned int i : cap)
    centre += vertices[i];
  centre /= static_cast<double>(cap.size());
  const Vec3 u = plane.normal.unitOrthogonal();
  const Vec3 v = plane.normal.cross(u);
  std::vector<std::pair<double, unsigned int>> angle;
  for (unsigned int i : cap)
  {
    const Vec3 r = vertices[i] - centre;
    angle.emplace_back(std::atan2(r.dot(v), r.dot(u)), i);
  }
  std::sort(angle.begin(), angle.end());
  std::vector<unsigned int> cap_loop;
  for (const auto& a : angle)
    cap_loop.push_back(a.second);
  // Counter-clockwise about +n: outward for the piece below.
  below.add_face(cap_loop, cap_origin);
  std::reverse(cap_loop.begin(), cap_loop.end());
  above.add_face(cap_loop, cap_origin);

  result.above = above.build(vertices);
  result.below = below.build(vertices);
  return result;
}

} // namespace talus
