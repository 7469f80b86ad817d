#include <talus/base/fnv1a.h>
#include <talus/scene/model_digest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace talus
{

ModelDigest::ModelDigest(const Scene& scene, bool face_loads)
    : scene_(&scene), face_loads_(face_loads)
{
  const std::size_t points = scene.history_block_points.size();
  containing_.assign(points, ~0u);
  nearest_.assign(points, ~0u);
  nearest_distance_.assign(points, 1e300);
  if (!face_loads)
    return;
  for (const FacePressure& p : scene.face_pressures)
    regions_.push_back(&p.region), region_is_quiet_.push_back(p.quiet);
  for (const StageSpec& stage : scene.stages)
    if (stage.changes_boundaries)
      for (const FacePressure& p : stage.boundaries.face_pressures)
        regions_.push_back(&p.region), region_is_quiet_.push_back(p.quiet);
  patches_.resize(regions_.size());
}

ModelDigest ModelDigest::of(const Scene& scene, const BlockModel& model)
{
  ModelDigest digest(scene, false);
  for (unsigned int b = 0; b < model.n_blocks(); ++b)
    digest.add(model, b);
  return digest;
}

void ModelDigest::add(const BlockModel& model, unsigned int b)
{
  const auto number = static_cast<unsigned int>(centroid_.size());
  const std::string& name = model.group_names[model.group[b]];
  const auto named = std::find(group_names_.begin(), group_names_.end(), name);
  const auto g = static_cast<unsigned int>(named - group_names_.begin());
  if (named == group_names_.end())
  {
    group_names_.push_back(name);
    per_group_.push_back(0);
    density_.push_back(scene_->density_of(name));
    const std::vector<std::string>& d = scene_->deformable.groups;
    rigid_group_.push_back(std::find(d.begin(), d.end(), name) == d.end());
  }
  ++per_group_[g];
  group_.push_back(g);
  centroid_.push_back(model.centroid[b]);
  const unsigned int v0 = model.vertex_start[b], v1 = model.vertex_start[b + 1];
  const unsigned int f0 = model.face_start[b], f1 = model.face_start[b + 1];
  n_faces_ += f1 - f0;
  n_vertices_ += v1 - v0;
  volume_ += model.volume[b];
  mass_ += density_[g] * model.volume[b];

  // The fingerprint: the vertices in order (as the whole array's), and
  // the faces by the block's own vertex numbers (the same on any copy).
  vertex_hash_ = fnv1a(&model.vertex[v0], (v1 - v0) * sizeof(Vec3), vertex_hash_);
  for (unsigned int k = model.face_loop_start[f0]; k < model.face_loop_start[f1]; ++k)
  {
    const unsigned int own = model.face_vertex[k] - v0;
    face_hash_ = fnv1a(&own, sizeof own, face_hash_);
  }

  // History points: the first block that holds the point (inside every
  // face plane, within 1e-9 of the block's size), else the first of the
  // nearest centroids.
  for (std::size_t i = 0; i < containing_.size(); ++i)
  {
    if (containing_[i] != ~0u)
      continue;
    const Vec3& p = scene_->history_block_points[i];
    bool inside = true;
    for (unsigned int f = f0; inside && f < f1; ++f)
    {
      const Vec3& on_face = model.vertex[model.face_vertex[model.face_loop_start[f]]];
      inside = model.face_normal[f].dot(p - on_face) <= 1e-9 * std::cbrt(model.volume[b]);
    }
    if (inside)
      containing_[i] = number;
    const double d = (model.centroid[b] - p).norm();
    if (d < nearest_distance_[i])
    {
      nearest_distance_[i] = d;
      nearest_[i] = number;
    }
  }

  // The face loads' parts on this block, its faces and vertices counted
  // from its first (RigidFaceLoads::relative_to).
  if (!face_loads_)
    return;
  std::vector<char> only(model.n_blocks(), 0);
  only[b] = 1;
  for (std::size_t r = 0; r < regions_.size(); ++r)
    for (FacePatch patch : face_patches_in(model, only, *regions_[r]))
    {
      patch.block = number;
      patch.face -= f0;
      for (unsigned int& v : patch.corner)
        v -= v0;
      patches_[r].push_back(patch);
    }
}

unsigned int ModelDigest::blocks_in(const std::string& name) const
{
  const auto named = std::find(group_names_.begin(), group_names_.end(), name);
  return named == group_names_.end() ? 0 : per_group_[named - group_names_.begin()];
}

std::uint64_t ModelDigest::geometry_fingerprint() const
{
  return fnv1a(&face_hash_, sizeof face_hash_, vertex_hash_);
}

void ModelDigest::resolve_history_blocks(Scene& scene) const
{
  std::vector<unsigned int>& blocks = scene.solver.history_blocks;
  for (std::size_t i = 0; i < containing_.size(); ++i)
  {
    const unsigned int b = containing_[i] != ~0u ? containing_[i] : nearest_[i];
    if (b != ~0u && std::find(blocks.begin(), blocks.end(), b) == blocks.end())
      blocks.push_back(b);
  }
}

bool ModelDigest::rigid_face_in(std::size_t k) const
{
  if (k >= regions_.size())
    throw std::logic_error("ModelDigest::rigid_face_in: the scene has no face load " +
                           std::to_string(k) + " (or the digest did not gather them)");
  return !region_is_quiet_[k] &&
         std::any_of(patches_[k].begin(), patches_[k].end(),
                     [&](const FacePatch& p) { return rigid_group_[group_[p.block]]; });
}

RigidFaceLoads ModelDigest::face_load_table(const std::vector<FacePressure>& loads,
                                            std::size_t first) const
{
  if (first + loads.size() > patches_.size())
    throw std::logic_error("ModelDigest::face_load_table: not the scene's face loads (or the "
                           "digest did not gather them)");
  const std::vector<std::vector<FacePatch>> these(patches_.begin() + first,
                                                  patches_.begin() + first + loads.size());
  return RigidFaceLoads(these, loads);
}

} // namespace talus
