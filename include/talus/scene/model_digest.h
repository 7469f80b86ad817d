#pragma once

#include <talus/model/block_model.h>
#include <talus/scene/scene.h>
#include <talus/solver/rigid_face_loads.h>

#include <cstdint>
#include <string>
#include <vector>

namespace talus
{

/// What the run summary, the checks on the built model and the checkpoints
/// need to know of the whole block model, gathered one block at a time in
/// the order of the blocks' numbers. A rank that builds only the blocks of
/// its region (issue 24) sees every block once as the brick is cut, and so
/// prints, checks and fingerprints what a rank holding the whole model
/// does, bit for bit (the sums are taken in the same order).
class ModelDigest
{
public:
  ModelDigest() = default;
  /// Gathers (`scene` must outlive the digest), besides the counts and sums, the blocks that
  /// contain the scene's history points; with `face_loads`, also the parts of the blocks' faces
  /// that the scene's face loads select (its own and every stage's), which the whole model gives
  /// otherwise.
  ModelDigest(const Scene& scene, bool face_loads);
  /// The digest of a whole model.
  static ModelDigest of(const Scene& scene, const BlockModel& model);

  /// Adds block `b` of `model`: the next block of the whole model.
  void add(const BlockModel& model, unsigned int b);

  unsigned int n_blocks() const { return static_cast<unsigned int>(centroid_.size()); }
  unsigned long n_faces() const { return n_faces_; }
  unsigned long n_vertices() const { return n_vertices_; }
  /// m^3, summed in the blocks' order (BlockModel::total_volume).
  double total_volume() const { return volume_; }
  /// kg: each block's volume times its group's density, in order.
  double mass() const { return mass_; }
  const std::vector<std::string>& group_names() const { return group_names_; }
  /// Blocks per group, by group index.
  const std::vector<unsigned int>& blocks_per_group() const { return per_group_; }
  /// How many blocks the group named `name` holds (0 for no such group).
  unsigned int blocks_in(const std::string& name) const;
  /// Each block's centroid as built (m), by its number.
  const std::vector<Vec3>& centroid() const { return centroid_; }
  const std::string& group_name(unsigned int b) const { return group_names_[group_[b]]; }
  /// A fingerprint of the blocks' geometry as built: their vertices and
  /// each block's faces by its own vertex numbers.
  std::uint64_t geometry_fingerprint() const;

  /// Adds the block containing each history point (the block with the
  /// nearest centroid when none does) to the scene's history blocks, once
  /// each, after the numbered ones.
  void resolve_history_blocks(Scene& scene) const;

  /// With face loads gathered: whether part of a rigid block's face lies in
  /// the region of the scene's face load `k`, counted over its own face
  /// loads and then those of each stage that changes boundaries, in order.
  bool rigid_face_in(std::size_t k) const;
  /// With face loads gathered: `loads` on every block, as
  /// RigidFaceLoads(model, all blocks, loads).relative_to(model) gives them;
  /// `loads` are the scene's face loads from place `first` on (0: its own;
  /// a stage's: after those of the scene and of the stages before it).
  RigidFaceLoads face_load_table(const std::vector<FacePressure>& loads, std::size_t first) const;

private:
  /// The scene's face load regions: its own, then each stage's that
  /// changes boundaries.
  std::vector<const ConvexRegion*> regions_;
  std::vector<char> region_is_quiet_;
  std::vector<std::vector<FacePatch>> patches_; ///< per region, every block's
  const Scene* scene_ = nullptr;  ///< the densities, deformable groups, history points
  std::vector<double> density_;   ///< kg/m^3, by group index
  std::vector<char> rigid_group_; ///< by group index
  /// Per history point: the first block containing it, and the first
  /// with the nearest centroid (~0u: none yet).
  std::vector<unsigned int> containing_, nearest_;
  std::vector<double> nearest_distance_;

  unsigned long n_faces_ = 0, n_vertices_ = 0;
  double volume_ = 0.0, mass_ = 0.0;
  std::vector<std::string> group_names_;
  std::vector<unsigned int> per_group_, group_;
  std::vector<Vec3> centroid_;
  std::uint64_t vertex_hash_ = 14695981039346656037ull, face_hash_ = 14695981039346656037ull;
  bool face_loads_ = false;
};

} // namespace talus
