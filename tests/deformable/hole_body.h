#pragma once

// The quarter slab with a hole of hole_mesh.h, meshed the way blocks are
// (zone/convex_block_mesher.h: gmsh's unstructured tetrahedra) instead of
// by a structured grid: x >= 0, y >= 0, 0 <= z <= thickness, the hole a
// regular polygon inscribed in the circle of radius a (n_facets facets in
// the quarter, corners on the circle and on both axes), the outer boundary
// the square [0, R]^2 or a polygon of n_outer facets inscribed in the circle
// of radius R. One closed PolyhedralSurface (its two z faces are quarter
// annuli: non-convex polygons) goes to mesh_polyhedron with an edge length
// graded from h0 at the hole wall in proportion to the distance from the
// centre, h = h0 r / a, capped at h_max (about the thickness, so that the
// zones far out stay well shaped).

#include <talus/zone/block_mesher.h>
#include <talus/zone/convex_block_mesher.h>
#include <talus/zone/tet_mesh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <vector>

struct HoleBody
{
  double a = 1.0;         ///< hole radius, m
  double R = 20.0;        ///< outer radius or half-width of the square, m
  double thickness = 1.0; ///< m
  bool square = false;    ///< outer boundary the square [0, R]^2
  unsigned int n_facets = 32, n_outer = 32;
  double h0 = 0.1;    ///< zone edge length at the wall, m
  double h_max = 1.0; ///< largest zone edge length, m

  /// The quarter annulus in the plane z = 0, counter-clockwise: along the x axis
  /// from the wall out, the outer boundary, down the y axis, then the hole
  /// back to (a, 0). Points on the axes have exact zeros (so that regions
  /// find them).
  std::vector<talus::Vec3> outline() const
  {
    using talus::Vec3;
    std::vector<Vec3> o;
    const auto on_circle = [&](double r, unsigned int j, unsigned int n)
    {
      if (j == 0)
        return Vec3(r, 0.0, 0.0);
      if (j == n)
        return Vec3(0.0, r, 0.0);
      const double theta = 0.5 * M_PI * j / n;
      return Vec3(r * std::cos(theta), r * std::sin(theta), 0.0);
    };
    o.emplace_back(a, 0.0, 0.0);
    if (square)
    {
      o.emplace_back(R, 0.0, 0.0);
      o.emplace_back(R, R, 0.0);
      o.emplace_back(0.0, R, 0.0);
    }
    else
      for (unsigned int j = 0; j <= n_outer; ++j)
        o.push_back(on_circle(R, j, n_outer));
    for (unsigned int j = n_facets; j > 0; --j)
      o.push_back(on_circle(a, j, n_facets));
    return o;
  }

  /// The slab: the outline at z = 0 (vertices 0..n-1) and at z = thickness
  /// (n..2n-1), the two z faces and one rectangle per edge of the outline.
  talus::PolyhedralSurface surface() const
  {
    using talus::Vec3;
    const std::vector<Vec3> o = outline();
    const unsigned int n = static_cast<unsigned int>(o.size());
    talus::PolyhedralSurface s;
    for (const double z : {0.0, thickness})
      for (const auto& p : o)
        s.vertex.emplace_back(p[0], p[1], z);
    std::vector<unsigned int> bottom, top;
    for (unsigned int i = 0; i < n; ++i)
    {
      top.push_back(n + i);
      bottom.push_back(n - 1 - i); // clockwise seen from above: counter-clockwise from below
    }
    s.face = {bottom, top};
    s.face_normal = {Vec3(0, 0, -1), Vec3(0, 0, 1)};
    for (unsigned int i = 0; i < n; ++i)
    {
      const unsigned int j = (i + 1) % n;
      s.face.push_back({i, j, n + j, n + i});
      // Outward: to the right of the counter-clockwise outline.
      const Vec3 along = s.vertex[j] - s.vertex[i];
      s.face_normal.push_back(Vec3(along[1], -along[0], 0.0).normalized());
    }
    return s;
  }

  /// Area of the polygonal hole in the quarter (m^2).
  double hole_area() const { return 0.5 * n_facets * a * a * std::sin(0.5 * M_PI / n_facets); }

  double edge_length(const talus::Vec3& x) const
  {
    return std::min(h_max, h0 * std::max(std::hypot(x[0], x[1]), a) / a);
  }

  talus::TetMesh build() const
  {
    const talus::BlockTetrahedra tets =
        talus::mesh_polyhedron(surface(), [this](const talus::Vec3& x) { return edge_length(x); });
    talus::TetMesh mesh;
    talus::append_tetrahedra(mesh, tets, 0);
    return mesh;
  }
};

/// n to one significant digit ("20000" for 21254): zone counts from gmsh,
/// whose volume mesher gives the same mesh every time but may give
/// another one in another version of gmsh.
inline std::string one_digit(unsigned int n)
{
  unsigned int scale = 1;
  while (n / scale >= 10)
    scale *= 10;
  return std::to_string((n + scale / 2) / scale * scale);
}
