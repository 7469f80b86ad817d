#pragma once

#include <talus/geometry/plane.h>

#include <string>
#include <utility>
#include <vector>

namespace talus
{

/// A convex polyhedron: vertices, and faces as vertex loops ordered
/// counter-clockwise when seen from outside (so the right-hand normal points
/// outward). Face loops are stored flat (`face_start` has one entry more than
/// there are faces) so that thousands of blocks cost few allocations.
class ConvexPolyhedron
{
public:
  ConvexPolyhedron() = default;

  /// Builds from vertices and face loops and computes the face planes.
  ConvexPolyhedron(std::vector<Vec3> vertices, const std::vector<std::vector<unsigned int>>& faces);

  /// Builds from already flat face storage; computes the face planes.
  ConvexPolyhedron(std::vector<Vec3> vertices, std::vector<unsigned int> face_start,
                   std::vector<unsigned int> face_vertices);

  /// The axis-aligned box [lo, hi] as a six-faced polyhedron.
  static ConvexPolyhedron box(const Vec3& lo, const Vec3& hi);

  /// A tetrahedron with the given corners (any order; orientation is fixed).
  static ConvexPolyhedron tetrahedron(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

  /// A right prism: the convex polygon `base` (counter-clockwise about
  /// `axis`) swept by the vector `axis`.
  static ConvexPolyhedron prism(const std::vector<Vec3>& base, const Vec3& axis);

  unsigned int n_vertices() const { return static_cast<unsigned int>(vertices_.size()); }
  unsigned int n_faces() const { return static_cast<unsigned int>(face_start_.size()) - 1; }
  /// Edges from Euler's formula; valid for a closed polyhedron of genus 0.
  unsigned int n_edges() const { return n_vertices() + n_faces() - 2; }

  const std::vector<Vec3>& vertices() const { return vertices_; }
  const Vec3& vertex(unsigned int i) const { return vertices_[i]; }

  /// Number of vertices of face f and the index of its k-th vertex.
  unsigned int face_size(unsigned int f) const { return face_start_[f + 1] - face_start_[f]; }
  unsigned int face_vertex(unsigned int f, unsigned int k) const
  {
    return face_vertices_[face_start_[f] + k];
  }
  const std::vector<unsigned int>& face_start() const { return face_start_; }
  const std::vector<unsigned int>& face_vertices() const { return face_vertices_; }

  /// Outward unit normal and offset of face f.
  const Plane& face_plane(unsigned int f) const { return face_planes_[f]; }

  /// What made face f (a code of the caller's; 0 when nothing was said, as
  /// for the starting brick): the block generator records which joint set
  /// or joint each cut face lies on (BlockModel::face_origin).
  int face_origin(unsigned int f) const { return face_origins_.empty() ? 0 : face_origins_[f]; }
  /// One code per face (or none).
  void set_face_origins(std::vector<int> origins) { face_origins_ = std::move(origins); }

  /// The distinct edges as vertex pairs (i < j).
  std::vector<std::pair<unsigned int, unsigned int>> edges() const;

  Box bounding_box() const;
  /// Length of the bounding-box diagonal: the size that scales tolerances.
  double size() const { return bounding_box().diagonal(); }

  /// Smallest and largest signed distance of the vertices from `plane`.
  std::pair<double, double> extent_along(const Plane& plane) const;

  /// Exact volume by the divergence theorem (positive for outward loops).
  double volume() const;

  /// Mean of the vertices: an interior point of a convex polyhedron.
  Vec3 vertex_mean() const;

  /// True if `x` is inside or within `tol` of the surface.
  bool contains(const Vec3& x, double tol) const;

  /// Checks that the polyhedron is closed, consistently and outwardly
  /// oriented, has planar faces and is convex, all within `relative_tol` times
  /// its size. Throws GeometryError naming the first failure, prefixed by
  /// `what` (e.g. "block 12").
  void validate(const std::string& what, double relative_tol = 1e-9) const;

private:
  void compute_planes();

  std::vector<Vec3> vertices_;
  std::vector<unsigned int> face_start_{0};
  std::vector<unsigned int> face_vertices_;
  std::vector<Plane> face_planes_;
  std::vector<int> face_origins_; ///< empty: every face 0
};

} // namespace talus
