#include <talus/solver/rigid_face_loads.h>

#include <algorithm>
#include <cmath>

namespace talus
{

namespace
{
/// Keeps the part of the planar polygon `p` on the side x[axis] <= bound
/// (sign +1) or x[axis] >= bound (sign -1): one step of Sutherland-Hodgman.
std::vector<Vec3> clip(const std::vector<Vec3>& p, int axis, double bound, double sign)
{
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const Vec3& a = p[i];
    const Vec3& b = p[(i + 1) % p.size()];
    const double da = sign * (a[axis] - bound), db = sign * (b[axis] - bound);
    if (da <= 0.0)
      out.push_back(a);
    if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0))
      out.push_back(a + da / (da - db) * (b - a));
  }
  return out;
}
} // namespace

std::vector<FacePatch> face_patches_in(const BlockModel& m, const std::vector<char>& rigid,
                                       const ConvexRegion& shape)
{
  const Box& region = shape.bounds;
  std::vector<FacePatch> patches;
  // A thin box around a face would also cut strips off the faces beside
  // it: across the box's thinnest extent, only faces that lie within it.
  int thin = 0;
  for (int d = 1; d < 3; ++d)
    if (region.hi[d] - region.lo[d] < region.hi[thin] - region.lo[thin])
      thin = d;
  for (unsigned int b = 0; b < m.n_blocks(); ++b)
  {
    if (!rigid[b])
      continue;
    for (unsigned int f = m.face_start[b]; f < m.face_start[b + 1]; ++f)
    {
      const unsigned int first = m.face_loop_start[f], last = m.face_loop_start[f + 1];
      std::vector<Vec3> polygon;
      bool within = true;
      for (unsigned int k = first; k < last; ++k)
      {
        polygon.push_back(m.vertex[m.face_vertex[k]]);
        within &=
            polygon.back()[thin] >= region.lo[thin] && polygon.back()[thin] <= region.hi[thin];
      }
      if (!shape.is_box)
        within = std::all_of(polygon.begin(), polygon.end(),
                             [&](const Vec3& x) { return shape.holds(x); });
      if (!within)
        continue;
      for (int d = 0; d < 3 && !polygon.empty() && shape.is_box; ++d)
      {
        polygon = clip(polygon, d, region.hi[d], 1.0);
        if (!polygon.empty())
          polygon = clip(polygon, d, region.lo[d], -1.0);
      }
      if (polygon.size() < 3)
        continue;
      // Area and centroid of the part (a fan from its first point).
      const Vec3& n = m.face_normal[f];
      double area = 0.0;
      Vec3 centre = Vec3::Zero();
      for (std::size_t i = 1; i + 1 < polygon.size(); ++i)
      {
        const double t = 0.5 * (polygon[i] - polygon[0]).cross(polygon[i + 1] - polygon[0]).dot(n);
        area += t;
        centre += t * (polygon[0] + polygon[i] + polygon[i + 1]) / 3.0;
      }
      const Vec3& x0 = m.vertex[m.face_vertex[first]];
      const double size2 = (m.vertex[m.face_vertex[first + 1]] - x0).squaredNorm();
      if (!(std::abs(area) > 1e-12 * size2)) // a box that only touches the face
        continue;
      centre /= area;
      // The centroid in the face's own terms: x0 + alpha e1 + beta e2 with
      // the two vertices that span the largest triangle with x0.
      FacePatch patch;
      patch.block = b;
      patch.face = f;
      patch.area = std::abs(area);
      double largest = -1.0;
      for (unsigned int i = first + 1; i < last; ++i)
        for (unsigned int j = i + 1; j < last; ++j)
        {
          const double twice =
              (m.vertex[m.face_vertex[i]] - x0).cross(m.vertex[m.face_vertex[j]] - x0).norm();
          if (twice > largest)
          {
            largest = twice;
            patch.corner = {{m.face_vertex[first], m.face_vertex[i], m.face_vertex[j]}};
          }
        }
      const Vec3 e1 = m.vertex[patch.corner[1]] - x0, e2 = m.vertex[patch.corner[2]] - x0;
      const Vec3 r = centre - x0;
      const double a11 = e1.dot(e1), a12 = e1.dot(e2), a22 = e2.dot(e2);
      const double det = a11 * a22 - a12 * a12;
      patch.alpha = (a22 * e1.dot(r) - a12 * e2.dot(r)) / det;
      patch.beta = (a11 * e2.dot(r) - a12 * e1.dot(r)) / det;
      patches.push_back(patch);
    }
  }
  return patches;
}

namespace
{
std::vector<std::vector<FacePatch>> patches_of(const BlockModel& blocks,
                                               const std::vector<char>& rigid,
                                               const std::vector<FacePressure>& loads)
{
  std::vector<std::vector<FacePatch>> patches;
  for (const FacePressure& load : loads)
    patches.push_back(load.quiet ? std::vector<FacePatch>{}
                                 : face_patches_in(blocks, rigid, load.region));
  return patches;
}
} // namespace

RigidFaceLoads::RigidFaceLoads(const BlockModel& blocks, const std::vector<char>& rigid,
                               const std::vector<FacePressure>& loads)
    : RigidFaceLoads(patches_of(blocks, rigid, loads), loads)
{
}

RigidFaceLoads::RigidFaceLoads(const std::vector<std::vector<FacePatch>>& patches,
                               const std::vector<FacePressure>& loads)
{
  std::vector<unsigned int> slot_of_block;
  for (std::size_t l = 0; l < loads.size(); ++l)
  {
    const FacePressure& load = loads[l];
    const int function = load.motion.varies() ? static_cast<int>(functions_.size()) : -1;
    if (load.motion.varies())
      functions_.push_back(load.motion);
    if (load.quiet) // zone faces only
      continue;
    for (const FacePatch& patch : patches[l])
    {
      if (patch.block >= slot_of_block.size())
        slot_of_block.resize(patch.block + 1, ~0u);
      unsigned int& slot = slot_of_block[patch.block];
      if (slot == ~0u)
      {
        slot = static_cast<unsigned int>(loaded_block_.size());
        loaded_block_.push_back(patch.block);
      }
      patch_.push_back(Load{patch, slot, load.pressure, load.traction, function});
    }
  }
  scale_.assign(functions_.size(), 1.0);
  force_.resize(loaded_block_.size());
  moment_.resize(loaded_block_.size());
  velocity_before_.resize(loaded_block_.size());
  spin_before_.resize(loaded_block_.size());
}

void RigidFaceLoads::add(const BlockModel& m, std::vector<Vec3>& force, std::vector<Vec3>& moment,
                         const std::vector<Vec3>& velocity, const std::vector<Vec3>& spin,
                         double time)
{
  for (std::size_t i = 0; i < functions_.size(); ++i) // once per load and step
    scale_[i] = functions_[i].scale(time);
  for (std::size_t k = 0; k < loaded_block_.size(); ++k)
  {
    const unsigned int b = loaded_block_[k];
    force_[k].setZero();
    moment_[k].setZero();
    velocity_before_[k] = velocity[b];
    spin_before_[k] = spin[b];
  }
  for (const Load& l : patch_)
  {
    const FacePatch& p = l.patch;
    const unsigned int k = l.slot;
    const Vec3& x0 = m.vertex[p.corner[0]];
    const Vec3 at =
        x0 + p.alpha * (m.vertex[p.corner[1]] - x0) + p.beta * (m.vertex[p.corner[2]] - x0);
    // Pressure pushes in, against the outward normal; traction in global axes.
    const double scale = l.function < 0 ? 1.0 : scale_[l.function];
    const Vec3 f = (-l.pressure * m.face_normal[p.face] + l.traction) * (scale * p.area);
    force_[k] += f;
    moment_[k] += (at - m.centroid[p.block]).cross(f);
  }
  for (std::size_t j = 0; j < loaded_block_.size(); ++j)
  {
    force[loaded_block_[j]] += force_[j];
    moment[loaded_block_[j]] += moment_[j];
  }
}

void RigidFaceLoads::account(const std::vector<char>& fixed, const std::vector<Vec3>& velocity,
                             const std::vector<Vec3>& spin, double h, double dt,
                             ExactSum& boundary_work, ExactSum& kinetic) const
{
  for (std::size_t k = 0; k < loaded_block_.size(); ++k)
  {
    const unsigned int b = loaded_block_[k];
    if (fixed[b])
      continue;
    const Vec3 reach = 0.5 * h * (velocity_before_[k] + velocity[b]);
    const Vec3 turn = 0.5 * h * (spin_before_[k] + spin[b]);
    boundary_work += force_[k].dot(reach) + moment_[k].dot(turn);
    kinetic += 0.5 * (force_[k].dot(velocity[b]) + moment_[k].dot(spin[b])) * dt;
  }
}

RigidFaceLoads RigidFaceLoads::relative_to(const BlockModel& blocks) const
{
  RigidFaceLoads r = *this;
  for (Load& l : r.patch_)
  {
    l.patch.face -= blocks.face_start[l.patch.block];
    for (unsigned int& v : l.patch.corner)
      v -= blocks.vertex_start[l.patch.block];
  }
  return r;
}

RigidFaceLoads RigidFaceLoads::localized(const BlockModel& model,
                                         const std::vector<unsigned int>& global_of_local,
                                         const std::vector<char>& take) const
{
  RigidFaceLoads r;
  r.functions_ = functions_;
  r.scale_.assign(functions_.size(), 1.0);
  std::vector<unsigned int> slot_of_block(model.n_blocks(), ~0u);
  for (const Load& l : patch_)
  {
    const auto at = std::lower_bound(global_of_local.begin(), global_of_local.end(), l.patch.block);
    if (at == global_of_local.end() || *at != l.patch.block)
      continue;
    const unsigned int b = static_cast<unsigned int>(at - global_of_local.begin());
    if (!take[b])
      continue;
    Load here = l;
    here.patch.block = b;
    here.patch.face += model.face_start[b];
    for (unsigned int& v : here.patch.corner)
      v += model.vertex_start[b];
    unsigned int& slot = slot_of_block[b];
    if (slot == ~0u)
    {
      slot = static_cast<unsigned int>(r.loaded_block_.size());
      r.loaded_block_.push_back(b);
    }
    here.slot = slot;
    r.patch_.push_back(here);
  }
  r.force_.resize(r.loaded_block_.size());
  r.moment_.resize(r.loaded_block_.size());
  r.velocity_before_.resize(r.loaded_block_.size());
  r.spin_before_.resize(r.loaded_block_.size());
  return r;
}

} // namespace talus
