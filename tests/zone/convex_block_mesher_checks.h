#pragma once

// The checks shared by the convex_block_mesher tests: what a mesh of one
// convex block must be (positive zones filling the block, a surface that is
// the block's faces, a size in the band of the target edge length, quality
// zones), measured on BlockTetrahedra, and a converter to TetMesh for the
// solvers.

#include <talus/geometry/block_generator.h>
#include <talus/model/block_model.h>
#include <talus/zone/convex_block_mesher.h>
#include <talus/zone/tet_mesh.h>

#include "../tests.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace talus_test
{
using talus::BlockModel;
using talus::BlockTetrahedra;
using talus::Vec3;

/// What one block's mesh is, against the block.
struct BlockMeshFigures
{
  unsigned int zones = 0;
  unsigned int gridpoints = 0;
  unsigned int boundary_triangles = 0;
  /// Gridpoints on none of the block's face planes.
  unsigned int interior_gridpoints = 0;
  /// Zones of zero or negative volume.
  unsigned int non_positive = 0;
  /// |sum of zone volumes - block volume| / block volume.
  double volume_error = 0.0;
  /// Zone faces used more than twice (a mesh that is not a manifold).
  unsigned int faces_over_used = 0;
  /// Boundary triangles on none of the block's face planes (within 1e-12
  /// of the block's size), or facing inwards.
  unsigned int triangles_off_faces = 0;
  /// Largest distance of a boundary triangle's corner from its face's
  /// plane, over the block's size.
  double largest_off_plane = 0.0;
  /// Largest |sum of the triangles' areas on a face - the face's area| /
  /// the face's area, over the block's faces.
  double face_area_error = 0.0;
  /// zones / regular_tetrahedra_in(volume, h).
  double band = 0.0;
  /// Smallest width of the block (over its face normals), m.
  double width = 0.0;
  /// Radius ratios of the zones (radius_ratio), sorted.
  std::vector<double> quality;

  bool exact(double tolerance = 1e-12) const
  {
    return non_positive == 0 && faces_over_used == 0 && triangles_off_faces == 0 &&
           volume_error <= tolerance && face_area_error <= tolerance;
  }
};

inline double median(const std::vector<double>& sorted)
{
  if (sorted.empty())
    return 0.0;
  const std::size_t n = sorted.size();
  return n % 2 == 1 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
}

inline double signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

/// Area of face f of the model (a planar loop), m^2.
inline double face_area(const BlockModel& m, unsigned int f)
{
  Vec3 twice = Vec3::Zero();
  const unsigned int first = m.face_loop_start[f], end = m.face_loop_start[f + 1];
  const Vec3& o = m.vertex[m.face_vertex[first]];
  for (unsigned int k = first + 1; k + 1 < end; ++k)
    twice += (m.vertex[m.face_vertex[k]] - o).cross(m.vertex[m.face_vertex[k + 1]] - o);
  return 0.5 * m.face_normal[f].dot(twice);
}

/// The zone faces that appear once, turned to face out of their zone: the
/// mesh's surface, and (in `zone_of`, if given) the zone of each.
/// `over_used` counts faces that appear more than twice.
inline std::vector<std::array<unsigned int, 3>>
boundary_triangles(const BlockTetrahedra& mesh, unsigned int& over_used,
                   std::vector<unsigned int>* zone_of = nullptr)
{
  static const int face_of[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  struct Use
  {
    unsigned int count = 0, zone = 0;
    std::array<unsigned int, 3> out;
  };
  std::map<std::array<unsigned int, 3>, Use> seen;
  for (unsigned int z = 0; z < mesh.tet.size(); ++z)
    for (const auto& f : face_of)
    {
      // With t positively oriented, (t[f0], t[f1], t[f2]) faces out.
      const auto& t = mesh.tet[z];
      const std::array<unsigned int, 3> out{{t[f[0]], t[f[1]], t[f[2]]}};
      std::array<unsigned int, 3> key = out;
      std::sort(key.begin(), key.end());
      Use& use = seen[key];
      if (use.count++ == 0)
      {
        use.out = out;
        use.zone = z;
      }
    }
  std::vector<std::array<unsigned int, 3>> once;
  over_used = 0;
  if (zone_of != nullptr)
    zone_of->clear();
  for (const auto& [key, use] : seen)
    if (use.count == 1)
    {
      once.push_back(use.out);
      if (zone_of != nullptr)
        zone_of->push_back(use.zone);
    }
    else if (use.count > 2)
      ++over_used;
  return once;
}

/// Measures block b's mesh at the target edge length h (m).
inline BlockMeshFigures measure_block_mesh(const BlockModel& m, unsigned int b,
                                           const BlockTetrahedra& mesh, double h)
{
  BlockMeshFigures r;
  r.zones = static_cast<unsigned int>(mesh.tet.size());
  r.gridpoints = static_cast<unsigned int>(mesh.point.size());
  const auto P = [&](unsigned int g) -> const Vec3& { return mesh.point[g]; };
  double filled = 0.0;
  for (const auto& t : mesh.tet)
  {
    const double v = signed_volume(P(t[0]), P(t[1]), P(t[2]), P(t[3]));
    if (!(v > 0.0))
      ++r.non_positive;
    filled += v;
    r.quality.push_back(talus::radius_ratio(P(t[0]), P(t[1]), P(t[2]), P(t[3])));
  }
  std::sort(r.quality.begin(), r.quality.end());
  r.volume_error = std::abs(filled - m.volume[b]) / m.volume[b];

  const talus::ConvexPolyhedron shape = m.polyhedron(b);
  const double size = shape.size();
  r.width = 1e300;
  for (unsigned int f = m.face_start[b]; f < m.face_start[b + 1]; ++f)
  {
    const talus::Plane plane(m.face_normal[f],
                             m.face_normal[f].dot(m.vertex[m.face_vertex[m.face_loop_start[f]]]));
    const auto [lo, hi] = shape.extent_along(plane);
    r.width = std::min(r.width, hi - lo);
  }

  for (const Vec3& p : mesh.point)
  {
    bool on_face = false;
    for (unsigned int f = m.face_start[b]; f < m.face_start[b + 1] && !on_face; ++f)
      on_face = std::abs(m.face_normal[f].dot(p - m.vertex[m.face_vertex[m.face_loop_start[f]]])) <=
                1e-12 * size;
    if (!on_face)
      ++r.interior_gridpoints;
  }

  // Each boundary triangle on the block face whose plane holds its corners
  // (the nearest one), facing the way that face does; areas summed per face.
  const std::vector<std::array<unsigned int, 3>> surface =
      boundary_triangles(mesh, r.faces_over_used);
  r.boundary_triangles = static_cast<unsigned int>(surface.size());
  std::vector<double> area(m.face_start[b + 1] - m.face_start[b], 0.0);
  for (const auto& tri : surface)
  {
    unsigned int best = 0;
    double best_distance = 1e300;
    for (unsigned int f = m.face_start[b]; f < m.face_start[b + 1]; ++f)
    {
      const Vec3& n = m.face_normal[f];
      const Vec3& o = m.vertex[m.face_vertex[m.face_loop_start[f]]];
      double distance = 0.0;
      for (unsigned int g : tri)
        distance = std::max(distance, std::abs(n.dot(P(g) - o)));
      if (distance < best_distance)
      {
        best_distance = distance;
        best = f;
      }
    }
    r.largest_off_plane = std::max(r.largest_off_plane, best_distance / size);
    const double signed_area =
        0.5 * m.face_normal[best].dot((P(tri[1]) - P(tri[0])).cross(P(tri[2]) - P(tri[0])));
    if (best_distance > 1e-12 * size || !(signed_area > 0.0))
      ++r.triangles_off_faces;
    area[best - m.face_start[b]] += signed_area;
  }
  for (unsigned int f = m.face_start[b]; f < m.face_start[b + 1]; ++f)
  {
    const double a = face_area(m, f);
    r.face_area_error = std::max(r.face_area_error, std::abs(area[f - m.face_start[b]] - a) / a);
  }
  r.band = r.zones / talus::regular_tetrahedra_in(m.volume[b], h);
  return r;
}

/// What in a block's own shape can force poor zones: its smallest face
/// angle and dihedral angle (degrees) and its shortest edge (m).
struct BlockShape
{
  double smallest_face_angle = 180.0;
  double smallest_dihedral = 180.0;
  double shortest_edge = 1e300;

  /// Whether a zone below 0.1 in radius ratio is forced by the shape at
  /// edge length h: an angle below 20 degrees, an edge or a width below h/4.
  bool forces_slivers(double width, double h) const
  {
    return smallest_face_angle < 20.0 || smallest_dihedral < 20.0 || shortest_edge < 0.25 * h ||
           width < 0.25 * h;
  }
};

inline BlockShape block_shape(const BlockModel& m, unsigned int b)
{
  BlockShape s;
  const double degrees = 180.0 / M_PI;
  std::map<std::pair<unsigned int, unsigned int>, std::vector<unsigned int>> faces_at_edge;
  for (unsigned int f = m.face_start[b]; f < m.face_start[b + 1]; ++f)
  {
    const unsigned int first = m.face_loop_start[f];
    const unsigned int n = m.face_loop_start[f + 1] - first;
    for (unsigned int k = 0; k < n; ++k)
    {
      const unsigned int p = m.face_vertex[first + (k + n - 1) % n], q = m.face_vertex[first + k],
                         r = m.face_vertex[first + (k + 1) % n];
      const Vec3 a = m.vertex[p] - m.vertex[q], c = m.vertex[r] - m.vertex[q];
      s.smallest_face_angle =
          std::min(s.smallest_face_angle, degrees * std::atan2(a.cross(c).norm(), a.dot(c)));
      s.shortest_edge = std::min(s.shortest_edge, c.norm());
      faces_at_edge[std::minmax(q, r)].push_back(f);
    }
  }
  for (const auto& [edge, faces] : faces_at_edge)
    if (faces.size() == 2)
    {
      const Vec3 &n0 = m.face_normal[faces[0]], &n1 = m.face_normal[faces[1]];
      // The interior angle between two faces is 180 degrees less the angle
      // between their outward normals.
      s.smallest_dihedral = std::min(s.smallest_dihedral,
                                     180.0 - degrees * std::atan2(n0.cross(n1).norm(), n0.dot(n1)));
    }
  return s;
}

/// Checks the meshes of blocks `which` of `m` at edge length h and prints
/// the verdicts (standard output) and the figures per block (standard
/// error). Blocks less than `roomless` h wide must have at most one
/// interior gridpoint (2 for gmsh, which keeps gridpoints about h from the
/// faces; the lattice mesher keeps them 0.6h from each face). Returns the
/// figures of each block.
inline std::vector<BlockMeshFigures> report_meshes(const std::string& name, const BlockModel& m,
                                                   const std::vector<BlockTetrahedra>& meshes,
                                                   const std::vector<unsigned int>& which, double h,
                                                   double roomless = 2.0)
{
  std::vector<BlockMeshFigures> all;
  std::vector<double> quality; // of blocks at least h/2 thick
  unsigned int non_positive = 0, over_used = 0, off_faces = 0, wide = 0, out_of_band = 0,
               narrow = 0, narrow_filled = 0, poor = 0, poor_unforced = 0;
  double volume_error = 0.0, area_error = 0.0, off_plane = 0.0;
  std::fprintf(stderr, "%s, h = %g m:\n", name.c_str(), h);
  for (std::size_t i = 0; i < which.size(); ++i)
  {
    const unsigned int b = which[i];
    BlockMeshFigures f = measure_block_mesh(m, b, meshes[i], h);
    const BlockShape shape = block_shape(m, b);
    non_positive += f.non_positive;
    over_used += f.faces_over_used;
    off_faces += f.triangles_off_faces;
    volume_error = std::max(volume_error, f.volume_error);
    area_error = std::max(area_error, f.face_area_error);
    off_plane = std::max(off_plane, f.largest_off_plane);
    // A block less than 2h wide has no room for a gridpoint h from its
    // faces: its zones are set by its faces' triangles, not by its volume.
    if (f.width >= 2.0 * h)
    {
      ++wide;
      if (!(f.band >= 0.5 && f.band <= 2.0))
        ++out_of_band;
    }
    if (f.width < roomless * h)
    {
      ++narrow;
      if (f.interior_gridpoints > 1)
        ++narrow_filled;
    }
    const unsigned int below = static_cast<unsigned int>(
        std::lower_bound(f.quality.begin(), f.quality.end(), 0.1) - f.quality.begin());
    poor += below;
    if (below > 0 && !shape.forces_slivers(f.width, h))
      poor_unforced += below;
    if (f.width >= 0.5 * h)
      quality.insert(quality.end(), f.quality.begin(), f.quality.end());
    std::fprintf(stderr,
                 "  block %u: %u faces, %u corners, volume %.6g m^3, width %.3g m, %u zones, "
                 "%u gridpoints (%u interior), "
                 "%u boundary triangles, band %.3f, radius ratio median %.3f smallest %.3g, "
                 "%u below 0.1; shape: face angle %.1f deg, dihedral %.1f deg, edge %.3g m; "
                 "volume error %.1e, area error %.1e, off plane %.1e\n",
                 b, m.face_start[b + 1] - m.face_start[b],
                 m.vertex_start[b + 1] - m.vertex_start[b], m.volume[b], f.width, f.zones,
                 f.gridpoints, f.interior_gridpoints, f.boundary_triangles, f.band,
                 median(f.quality), f.quality.empty() ? 0.0 : f.quality.front(), below,
                 shape.smallest_face_angle, shape.smallest_dihedral, shape.shortest_edge,
                 f.volume_error, f.face_area_error, f.largest_off_plane);
    all.push_back(std::move(f));
  }
  std::sort(quality.begin(), quality.end());
  std::printf("%s: %zu blocks, h = %g m\n", name.c_str(), which.size(), h);
  std::printf("  every zone of positive volume: %s\n", verdict(non_positive == 0));
  std::printf("  zone volumes sum to each block's volume within 1e-12: %s\n",
              verdict(volume_error <= 1e-12));
  std::printf("  no zone face shared by more than two zones: %s\n", verdict(over_used == 0));
  std::printf("  mesh surface on the block's faces (within 1e-12 of the size, facing out): %s\n",
              verdict(off_faces == 0));
  std::printf("  surface areas per block face within 1e-12 of the face's area: %s\n",
              verdict(area_error <= 1e-12));
  if (wide > 0)
    std::printf("  %u blocks at least 2h wide: zones within 0.5-2x the regular-tetrahedra "
                "count: %s\n",
                wide, verdict(out_of_band == 0));
  if (narrow > 0)
    std::printf("  %u blocks less than %gh wide: their faces' triangles and at most one "
                "interior gridpoint: %s\n",
                narrow, roomless, verdict(narrow_filled == 0));
  if (quality.empty())
    std::printf("  median radius ratio: not checked, every block is thinner than h/2\n");
  else
    std::printf("  median radius ratio at least 0.6 (blocks at least h/2 wide): %s\n",
                verdict(median(quality) >= 0.6));
  // One line whether or not there are any, so that a forced sliver more or
  // less (gmsh's meshes follow the build's rounding) does not change it.
  std::printf("  zones below radius ratio 0.1 only in blocks whose shape forces them: %s\n",
              verdict(poor_unforced == 0));
  std::fprintf(stderr,
               "  all: median radius ratio %.4f over %zu zones of blocks at least h/2 wide; "
               "%u below 0.1 (%u not forced), "
               "volume error %.1e, area error %.1e, off plane %.1e\n",
               median(quality), quality.size(), poor, poor_unforced, volume_error, area_error,
               off_plane);
  return all;
}

/// The blocks' meshes as one TetMesh (each block with its own gridpoints),
/// with boundary faces facing out, as mesh_blocks makes it.
inline talus::TetMesh to_tet_mesh(const std::vector<BlockTetrahedra>& meshes,
                                  const std::vector<unsigned int>& block_of)
{
  talus::TetMesh out;
  for (std::size_t i = 0; i < meshes.size(); ++i)
  {
    const unsigned int offset = out.n_gridpoints();
    const unsigned int first_zone = out.n_zones();
    for (const Vec3& p : meshes[i].point)
    {
      out.position.insert(out.position.end(), {p.x(), p.y(), p.z()});
      out.gridpoint_block.push_back(block_of[i]);
    }
    for (const auto& t : meshes[i].tet)
    {
      out.zone_gridpoint.push_back({{offset + t[0], offset + t[1], offset + t[2], offset + t[3]}});
      out.zone_block.push_back(block_of[i]);
    }
    unsigned int over_used = 0;
    std::vector<unsigned int> zone_of;
    const auto surface = boundary_triangles(meshes[i], over_used, &zone_of);
    for (std::size_t k = 0; k < surface.size(); ++k)
    {
      const auto& tri = surface[k];
      out.face_gridpoint.push_back({{offset + tri[0], offset + tri[1], offset + tri[2]}});
      out.face_zone.push_back(first_zone + zone_of[k]);
    }
  }
  return out;
}

/// A cube of side 2 m turned about an oblique axis, its edges and six
/// corners cut off by planes at 1.25 m and 1.5 m from its centre: every
/// piece of the cutting, `inner` the one of 24 faces in the middle.
inline talus::BlockModel many_faced_block(unsigned int& inner)
{
  using namespace talus;
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Vec3 centre(0.3, -0.2, 0.1);
  BlockGenerator generator(ConvexPolyhedron::box(Vec3::Constant(-4), Vec3::Constant(4)), {});
  std::vector<Plane> planes;
  for (int axis = 0; axis < 3; ++axis)
    for (int sign : {-1, 1})
    {
      Vec3 face = Vec3::Zero();
      face[axis] = sign;
      planes.emplace_back(face, 1.0);
      Vec3 edge = face;
      edge[(axis + 1) % 3] = 1;
      planes.emplace_back(edge.normalized(), 1.25);
      edge[(axis + 1) % 3] = -1;
      planes.emplace_back(edge.normalized(), 1.25);
    }
  for (const Vec3& corner : {Vec3(1, 1, 1), Vec3(-1, 1, 1), Vec3(1, -1, 1), Vec3(1, 1, -1),
                             Vec3(-1, -1, 1), Vec3(1, -1, -1)})
    planes.emplace_back(corner.normalized(), 1.5);
  for (const Plane& p : planes)
  {
    const Vec3 normal = turn * p.normal;
    generator.cut_plane(Plane(normal, p.offset + normal.dot(centre)));
  }
  BlockModel model;
  inner = 0;
  for (const ConvexPolyhedron& b : generator.blocks())
  {
    const unsigned int i = model.add_block(b, 0);
    if (b.contains(centre, 0.0))
      inner = i;
  }
  return model;
}

} // namespace talus_test
