#include <talus/base/exceptions.h>
#include <talus/zone/lattice_block_mesher.h>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>

namespace talus
{

namespace
{
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<unsigned int, Kernel>;
using CellBase = CGAL::Delaunay_triangulation_cell_base_3<Kernel>;
using Tds = CGAL::Triangulation_data_structure_3<VertexBase, CellBase>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, Tds>;

// Interior points stay this far (times h) inside every face, face points this
// far from their face's edges: closer, the zones between them and the
// surface points flatten.
constexpr double interior_margin = 0.6;
constexpr double face_margin = 0.5;
// Gridpoints of zones below this radius ratio are moved (trial moves).
constexpr double poor_quality = 0.3;

double signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

/// The points to triangulate, each with the faces it lies on (none for an
/// interior point, one for a face point, two for an edge point, three or
/// more for a corner) and, for an edge point, its edge's direction.
struct LatticePoints
{
  std::vector<Vec3> x;
  std::vector<unsigned int> face_start{0}; // faces of point i: face[face_start[i]..]
  std::vector<unsigned int> face;
  std::vector<Vec3> edge_direction; // unit, for edge points (zero otherwise)
  std::vector<Vec3> face_normal;    // of the body's faces

  void add(const Vec3& p, std::initializer_list<unsigned int> on, const Vec3& along = Vec3::Zero())
  {
    x.push_back(p);
    face.insert(face.end(), on.begin(), on.end());
    face_start.push_back(static_cast<unsigned int>(face.size()));
    edge_direction.push_back(along);
  }
  unsigned int n_faces(unsigned int i) const { return face_start[i + 1] - face_start[i]; }
  bool on_face(unsigned int i, unsigned int f) const
  {
    for (unsigned int k = face_start[i]; k < face_start[i + 1]; ++k)
      if (face[k] == f)
        return true;
    return false;
  }
  /// Whether the four points lie on one face of the body (a flat cell).
  bool on_one_face(const std::array<unsigned int, 4>& t) const
  {
    for (unsigned int k = face_start[t[0]]; k < face_start[t[0] + 1]; ++k)
      if (on_face(t[1], face[k]) && on_face(t[2], face[k]) && on_face(t[3], face[k]))
        return true;
    return false;
  }
};

/// Body volume by the divergence theorem over the faces' fans (m^3).
double body_volume(const PolyhedralSurface& body)
{
  const Vec3& o = body.vertex[0];
  double v = 0.0;
  for (const auto& loop : body.face)
    for (std::size_t k = 1; k + 1 < loop.size(); ++k)
      v += signed_volume(o, body.vertex[loop[0]], body.vertex[loop[k]], body.vertex[loop[k + 1]]);
  return v;
}

/// Corners, edge points, face lattices and the interior lattice of a body.
LatticePoints lattice_points(const PolyhedralSurface& body, double h)
{
  LatticePoints pts;
  pts.face_normal = body.face_normal;
  const std::size_t n_faces = body.face.size();
  std::vector<double> offset(n_faces); // plane: n . x = offset
  for (std::size_t f = 0; f < n_faces; ++f)
    offset[f] = body.face_normal[f].dot(body.vertex[body.face[f][0]]);

  // Corners, with every face that names them.
  std::vector<std::vector<unsigned int>> faces_at(body.vertex.size());
  for (std::size_t f = 0; f < n_faces; ++f)
    for (unsigned int v : body.face[f])
      faces_at[v].push_back(static_cast<unsigned int>(f));
  for (std::size_t v = 0; v < body.vertex.size(); ++v)
  {
    pts.x.push_back(body.vertex[v]);
    pts.face.insert(pts.face.end(), faces_at[v].begin(), faces_at[v].end());
    pts.face_start.push_back(static_cast<unsigned int>(pts.face.size()));
    pts.edge_direction.push_back(Vec3::Zero());
  }

  // Edges, in the order the faces' loops first meet them; each divided
  // uniformly, so both of its faces see the same points.
  std::map<std::pair<unsigned int, unsigned int>, std::size_t> edge_of;
  struct Edge
  {
    unsigned int a, b, f0, f1;
  };
  std::vector<Edge> edges;
  for (std::size_t f = 0; f < n_faces; ++f)
  {
    const auto& loop = body.face[f];
    for (std::size_t k = 0; k < loop.size(); ++k)
    {
      const auto key = std::minmax(loop[k], loop[(k + 1) % loop.size()]);
      const auto [it, fresh] = edge_of.emplace(key, edges.size());
      if (fresh)
        edges.push_back({key.first, key.second, static_cast<unsigned int>(f), 0u});
      else
        edges[it->second].f1 = static_cast<unsigned int>(f);
    }
  }
  for (const Edge& e : edges)
  {
    const Vec3 &a = body.vertex[e.a], &b = body.vertex[e.b];
    const double length = (b - a).norm();
    const long n = std::max(1L, std::lround(length / h));
    const Vec3 along = (b - a) / length;
    for (long k = 1; k < n; ++k)
      pts.add(a + (b - a) * (static_cast<double>(k) / n), {e.f0, e.f1}, along);
  }

  // Faces: a triangular lattice aligned with the face's longest edge, its
  // first row between that edge's points, kept face_margin h from the
  // face's edges.
  for (std::size_t f = 0; f < n_faces; ++f)
  {
    const auto& loop = body.face[f];
    const std::size_t m = loop.size();
    std::size_t longest = 0;
    double longest_length = 0.0;
    for (std::size_t k = 0; k < m; ++k)
    {
      const double l = (body.vertex[loop[(k + 1) % m]] - body.vertex[loop[k]]).norm();
      if (l > longest_length)
      {
        longest_length = l;
        longest = k;
      }
    }
    const Vec3& o = body.vertex[loop[longest]];
    const Vec3 u = (body.vertex[loop[(longest + 1) % m]] - o) / longest_length;
    const Vec3 v = body.face_normal[f].cross(u); // into the face from that edge
    std::vector<std::array<double, 2>> corner(m);
    double u_lo = 0.0, u_hi = 0.0, v_hi = 0.0;
    for (std::size_t k = 0; k < m; ++k)
    {
      const Vec3 d = body.vertex[loop[k]] - o;
      corner[k] = {{d.dot(u), d.dot(v)}};
      u_lo = std::min(u_lo, corner[k][0]);
      u_hi = std::max(u_hi, corner[k][0]);
      v_hi = std::max(v_hi, corner[k][1]);
    }
    const double s = longest_length / std::max(1L, std::lround(longest_length / h));
    const double row = s * std::sqrt(3.0) / 2.0;
    const double keep = face_margin * h;
    for (long j = 1; j * row < v_hi; ++j)
    {
      const double shift = (j % 2) * 0.5 * s;
      for (long i = static_cast<long>(std::floor((u_lo - shift) / s)); i * s + shift <= u_hi; ++i)
      {
        const double pu = i * s + shift, pv = j * row;
        bool inside = true;
        for (std::size_t k = 0; k < m && inside; ++k)
        {
          const auto &p = corner[k], &q = corner[(k + 1) % m];
          const double eu = q[0] - p[0], ev = q[1] - p[1];
          inside = (eu * (pv - p[1]) - ev * (pu - p[0])) >= keep * std::hypot(eu, ev);
        }
        if (inside)
        {
          const Vec3 x = o + pu * u + pv * v;
          // Exactly on the plane, up to rounding.
          pts.add(x - body.face_normal[f] * (body.face_normal[f].dot(x) - offset[f]),
                  {static_cast<unsigned int>(f)});
        }
      }
    }
  }

  // Interior: a body-centred cubic lattice about the corners' mean, cube
  // side a = h 2^(1/6) (12 tetrahedra of a^3 / 12 per cube, the volume of a
  // regular tetrahedron of edge h).
  const double a = h * std::pow(2.0, 1.0 / 6.0);
  Vec3 lo = body.vertex[0], hi = body.vertex[0], centre = Vec3::Zero();
  for (const Vec3& p : body.vertex)
  {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
    centre += p;
  }
  centre /= static_cast<double>(body.vertex.size());
  std::array<long, 3> first, last;
  for (int d = 0; d < 3; ++d)
  {
    first[d] = static_cast<long>(std::floor((lo[d] - centre[d]) / a)) - 1;
    last[d] = static_cast<long>(std::ceil((hi[d] - centre[d]) / a)) + 1;
  }
  const double deep = interior_margin * h;
  for (long i = first[0]; i <= last[0]; ++i)
    for (long j = first[1]; j <= last[1]; ++j)
      for (long k = first[2]; k <= last[2]; ++k)
        for (double half : {0.0, 0.5})
        {
          const Vec3 x = centre + a * Vec3(i + half, j + half, k + half);
          bool inside = true;
          for (std::size_t f = 0; f < n_faces && inside; ++f)
            inside = body.face_normal[f].dot(x) - offset[f] <= -deep;
          if (inside)
            pts.add(x, {});
        }
  return pts;
}

/// Moves the gridpoints of poor zones where a fixed set of trial moves
/// raises the worst zone around them most: interior points in any
/// direction, face points within their face's plane, edge points along
/// their edge; corners stay. Every zone stays of positive volume.
void improve_poor_zones(const LatticePoints& pts, std::vector<Vec3>& x,
                        const std::vector<std::array<unsigned int, 4>>& tets, double h)
{
  const unsigned int n = static_cast<unsigned int>(x.size());
  // Zones around each point (compressed rows).
  std::vector<unsigned int> start(n + 1, 0), around(4 * tets.size());
  for (const auto& t : tets)
    for (unsigned int g : t)
      ++start[g + 1];
  for (unsigned int g = 0; g < n; ++g)
    start[g + 1] += start[g];
  {
    std::vector<unsigned int> fill(start.begin(), start.end() - 1);
    for (unsigned int z = 0; z < tets.size(); ++z)
      for (unsigned int g : tets[z])
        around[fill[g]++] = z;
  }
  const auto quality = [&](unsigned int z)
  {
    const auto& t = tets[z];
    return radius_ratio(x[t[0]], x[t[1]], x[t[2]], x[t[3]]);
  };
  // The worst zone around g (0 if one is inverted).
  const auto worst_around = [&](unsigned int g)
  {
    double worst = 1.0;
    for (unsigned int k = start[g]; k < start[g + 1]; ++k)
    {
      const auto& t = tets[around[k]];
      if (!(signed_volume(x[t[0]], x[t[1]], x[t[2]], x[t[3]]) > 0.0))
        return 0.0;
      worst = std::min(worst, quality(around[k]));
    }
    return worst;
  };
  // Trial directions: the 26 of a cube's neighbours, at two distances.
  std::vector<Vec3> directions;
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      for (int k = -1; k <= 1; ++k)
        if (i != 0 || j != 0 || k != 0)
          directions.push_back(Vec3(i, j, k).normalized());
  std::vector<char> poor(n);
  for (int pass = 0; pass < 3; ++pass)
  {
    std::fill(poor.begin(), poor.end(), 0);
    bool any = false;
    for (unsigned int z = 0; z < tets.size(); ++z)
      if (quality(z) < poor_quality)
        for (unsigned int g : tets[z])
          if (pts.n_faces(g) < 3)
          {
            poor[g] = 1;
            any = true;
          }
    if (!any)
      return;
    for (unsigned int g = 0; g < n; ++g)
    {
      if (!poor[g])
        continue;
      const Vec3 home = x[g];
      double best = worst_around(g);
      Vec3 best_x = home;
      const unsigned int faces = pts.n_faces(g);
      for (double step : {0.1 * h, 0.2 * h})
        for (const Vec3& d0 : directions)
        {
          Vec3 d = d0;
          if (faces == 2)
          {
            const Vec3& e = pts.edge_direction[g];
            if (std::abs(d.dot(e)) < 0.5)
              continue;
            d = e * (d.dot(e) > 0.0 ? 1.0 : -1.0);
          }
          else if (faces == 1)
          {
            // Within the face's plane.
            const Vec3& normal = pts.face_normal[pts.face[pts.face_start[g]]];
            d -= normal * normal.dot(d);
            if (d.squaredNorm() < 0.25)
              continue;
            d.normalize();
          }
          x[g] = home + step * d;
          const double q = worst_around(g);
          if (q > best + 1e-12)
          {
            best = q;
            best_x = x[g];
          }
        }
      x[g] = best_x;
    }
  }
}
} // namespace

bool mesh_convex_body_by_lattice(const PolyhedralSurface& body, double h, BlockTetrahedra& out)
{
  out = BlockTetrahedra();
  if (body.vertex.size() < 4 || !(h > 0.0))
    return false;
  LatticePoints pts = lattice_points(body, h);
  const unsigned int n = static_cast<unsigned int>(pts.x.size());
  std::vector<std::pair<Delaunay::Point, unsigned int>> input;
  input.reserve(n);
  for (unsigned int i = 0; i < n; ++i)
    input.emplace_back(Delaunay::Point(pts.x[i].x(), pts.x[i].y(), pts.x[i].z()), i);
  Delaunay delaunay(input.begin(), input.end());
  if (delaunay.dimension() != 3 || delaunay.number_of_vertices() != n)
    return false;

  // The cells, less the flat ones on a face, each sorted by its points'
  // numbers, then in order: the mesh does not depend on CGAL's memory.
  std::vector<std::array<unsigned int, 4>> tets;
  tets.reserve(delaunay.number_of_finite_cells());
  for (auto c = delaunay.finite_cells_begin(); c != delaunay.finite_cells_end(); ++c)
  {
    std::array<unsigned int, 4> t{
        {c->vertex(0)->info(), c->vertex(1)->info(), c->vertex(2)->info(), c->vertex(3)->info()}};
    std::sort(t.begin(), t.end());
    if (!pts.on_one_face(t))
      tets.push_back(t);
  }
  std::sort(tets.begin(), tets.end());
  for (auto& t : tets)
    if (signed_volume(pts.x[t[0]], pts.x[t[1]], pts.x[t[2]], pts.x[t[3]]) < 0.0)
      std::swap(t[2], t[3]);

  std::vector<Vec3> x = pts.x;
  improve_poor_zones(pts, x, tets, h);

  const double volume = body_volume(body);
  double filled = 0.0;
  for (const auto& t : tets)
  {
    const double v = signed_volume(x[t[0]], x[t[1]], x[t[2]], x[t[3]]);
    if (!(v > 0.0))
      return false;
    filled += v;
  }
  if (!(std::abs(filled - volume) <= 1e-12 * volume))
    return false;
  out.point = std::move(x);
  out.tet = std::move(tets);
  return true;
}

std::pair<double, double> edge_length_range(const BlockModel& m, unsigned int b,
                                            const EdgeLengthAt& size)
{
  double lo = size(m.centroid[b]), hi = lo;
  for (unsigned int v = m.vertex_start[b]; v < m.vertex_start[b + 1]; ++v)
  {
    const double h = size(m.vertex[v]);
    lo = std::min(lo, h);
    hi = std::max(hi, h);
  }
  return {lo, hi};
}

BlockTetrahedra mesh_convex_block_by_lattice(const BlockModel& m, unsigned int b,
                                             const EdgeLengthAt& size)
{
  BlockTetrahedra out;
  if (!mesh_convex_body_by_lattice(block_surface(m, b), edge_length_range(m, b, size).first, out))
    throw InputError("block " + std::to_string(b) +
                     " could not be meshed by the lattice mesher (a zone of no volume or zones "
                     "that do not fill the block)");
  return out;
}

std::vector<BlockTetrahedra> mesh_convex_blocks_with(const BlockModel& m,
                                                     const std::vector<unsigned int>& which,
                                                     const EdgeLengthAt& size, ConvexMesher mesher,
                                                     unsigned int* lattice_blocks)
{
  std::vector<BlockTetrahedra> out(which.size());
  std::vector<unsigned int> to_gmsh;
  std::vector<std::size_t> gmsh_slot;
  unsigned int by_lattice = 0;
  for (std::size_t i = 0; i < which.size(); ++i)
  {
    const unsigned int b = which[i];
    bool done = false;
    if (mesher != ConvexMesher::gmsh)
    {
      const auto [lo, hi] = edge_length_range(m, b, size);
      if (mesher == ConvexMesher::lattice || hi <= 1.25 * lo)
        done = mesh_convex_body_by_lattice(block_surface(m, b), lo, out[i]);
    }
    if (done)
      ++by_lattice;
    else
    {
      to_gmsh.push_back(b);
      gmsh_slot.push_back(i);
    }
  }
  if (!to_gmsh.empty())
  {
    std::vector<BlockTetrahedra> meshed = mesh_convex_blocks(m, to_gmsh, size);
    for (std::size_t k = 0; k < meshed.size(); ++k)
      out[gmsh_slot[k]] = std::move(meshed[k]);
  }
  if (lattice_blocks != nullptr)
    *lattice_blocks = by_lattice;
  return out;
}

} // namespace talus
