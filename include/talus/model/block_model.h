#pragma once

#include <talus/geometry/convex_polyhedron.h>

#include <array>
#include <string>
#include <vector>

namespace talus
{

/// Every block of a scene in flat arrays (structure of arrays), indexed by
/// block number. Geometry: vertices of block b are
/// [vertex_start[b], vertex_start[b+1]); its faces are
/// [face_start[b], face_start[b+1]); the vertex loop of face f is
/// face_vertex[face_loop_start[f] .. face_loop_start[f+1]) and holds global
/// vertex numbers.
class BlockModel
{
public:
  /// Appends a block; computes its mass properties. Returns its number.
  unsigned int add_block(const ConvexPolyhedron& shape, unsigned int group);

  unsigned int n_blocks() const { return static_cast<unsigned int>(volume.size()); }
  unsigned int n_vertices() const { return static_cast<unsigned int>(vertex.size()); }
  unsigned int n_faces() const { return static_cast<unsigned int>(face_normal.size()); }

  /// The blocks `blocks` (numbers of this model, in that order) as a model
  /// of their own, with every value copied bit for bit: the blocks a rank
  /// holds of a model split among ranks. Groups keep their numbers.
  BlockModel subset(const std::vector<unsigned int>& blocks) const;

  /// Block b as a polyhedron object (for geometry work off the hot path).
  ConvexPolyhedron polyhedron(unsigned int b) const;

  /// Index of the group called `name`, added if new.
  unsigned int group_index(const std::string& name);

  double total_volume() const;

  // Geometry.
  std::vector<Vec3> vertex;                 ///< m
  std::vector<unsigned int> vertex_start{0}; ///< per block, n_blocks + 1
  std::vector<unsigned int> face_start{0};   ///< per block, n_blocks + 1
  std::vector<unsigned int> face_loop_start{0}; ///< per face, n_faces + 1
  std::vector<unsigned int> face_vertex;    ///< global vertex numbers
  std::vector<Vec3> face_normal;            ///< outward unit normals
  /// What made each face: joint_set_origin(i) for a face on a joint of the
  /// scene's i-th joint set, joint_origin(j) for its j-th single joint, 0
  /// for the brick's faces and excavation surfaces. A contact between two
  /// faces of one joint lies on that joint (ContactSet::joint_origin).
  std::vector<int> face_origin;
  static int joint_set_origin(std::size_t i) { return static_cast<int>(i) + 1; }
  static int joint_origin(std::size_t j) { return -static_cast<int>(j) - 1; }
  /// Triangular faces of deformable blocks only (empty otherwise): the
  /// share of the face's area each of its three corners carries in
  /// contacts (a third each, but for hexahedral zones the mean of both
  /// overlays' splits of a boundary quadrilateral; see use_zone_surfaces).
  std::vector<std::array<double, 3>> face_corner_share;

  // Mass properties per block (unit density; multiply by density).
  std::vector<double> volume;                   ///< m^3
  std::vector<Vec3> centroid;                   ///< m
  std::vector<std::array<double, 6>> inertia;   ///< m^5: xx, yy, zz, xy, yz, zx about centroid

  // Selections.
  std::vector<unsigned int> group;      ///< per block, index into group_names
  std::vector<std::string> group_names;
};

} // namespace talus
