#include <talus/geometry/block_generator.h>
#include <talus/geometry/mass_properties.h>
#include <talus/geometry/plane_cut.h>

#include <cmath>

namespace talus
{

BlockGenerator::BlockGenerator(ConvexPolyhedron start, CuttingSettings settings)
    : settings_(settings)
{
  blocks_.push_back(std::move(start));
}

double BlockGenerator::tolerance_for(const ConvexPolyhedron& block) const
{
  return settings_.relative_tolerance * block.size();
}

bool BlockGenerator::try_cut(const ConvexPolyhedron& block, const Plane& plane,
                             ConvexPolyhedron& above, ConvexPolyhedron& below, int origin)
{
  PlaneCut cut = cut_by_plane(block, plane, tolerance_for(block), origin);
  if (!cut.intersects)
    return false;
  if (settings_.minimum_volume > 0.0)
  {
    for (const ConvexPolyhedron* piece : {&cut.above, &cut.below})
    {
      const double v = piece->volume();
      if (v < settings_.minimum_volume)
      {
        if (report_.skipped_slivers == 0 || v < report_.smallest_refused)
        {
          report_.smallest_refused = v;
          report_.smallest_refused_at = piece->vertex_mean();
        }
        ++report_.skipped_slivers;
        return false;
      }
    }
  }
  ++report_.cuts;
  above = std::move(cut.above);
  below = std::move(cut.below);
  return true;
}

void BlockGenerator::cut_joint_set(const JointSetSpec& set, int origin)
{
  const Vec3 n = normal_from_dip(set.dip, set.dip_direction);
  const Plane reference = Plane::through(set.origin, n);
  std::vector<ConvexPolyhedron> result;
  result.reserve(blocks_.size());
  for (ConvexPolyhedron& block : blocks_)
  {
    if (set.limited && !set.extent.contains(compute_mass_properties(block).centroid))
    {
      result.push_back(std::move(block));
      continue;
    }
    // Joints k (at k * spacing from the origin) that pass strictly through the
    // block: found from the block's extent along the normal, so no other joint
    // of the set is ever looked at.
    const double tol = tolerance_for(block);
    const auto [lo, hi] = block.extent_along(reference);
    long k_first = static_cast<long>(std::ceil((lo + tol) / set.spacing));
    long k_last = static_cast<long>(std::floor((hi - tol) / set.spacing));
    if (set.count > 0)
    {
      k_first = std::max(k_first, 0L);
      k_last = std::min(k_last, static_cast<long>(set.count) - 1);
    }
    ConvexPolyhedron rest = std::move(block);
    for (long k = k_first; k <= k_last; ++k)
    {
      const Plane joint(n, reference.offset + k * set.spacing);
      ConvexPolyhedron above, below;
      if (try_cut(rest, joint, above, below, origin))
      {
        result.push_back(std::move(below));
        rest = std::move(above);
      }
    }
    result.push_back(std::move(rest));
  }
  blocks_ = std::move(result);
}

void BlockGenerator::cut_plane(const Plane& plane, const Box* extent, int origin)
{
  std::vector<ConvexPolyhedron> result;
  result.reserve(blocks_.size() + 16);
  for (ConvexPolyhedron& block : blocks_)
  {
    ConvexPolyhedron above, below;
    if ((extent == nullptr || extent->contains(compute_mass_properties(block).centroid)) &&
        try_cut(block, plane, above, below, origin))
    {
      result.push_back(std::move(below));
      result.push_back(std::move(above));
    }
    else
      result.push_back(std::move(block));
  }
  blocks_ = std::move(result);
}

double BlockGenerator::excavate(const ConvexRegion& region) { return split_by(region, false); }

double BlockGenerator::cut_along(const ConvexRegion& region) { return split_by(region, true); }

double BlockGenerator::split_by(const ConvexRegion& region, bool keep)
{
  double removed = 0.0;
  std::vector<ConvexPolyhedron> result;
  result.reserve(blocks_.size() + 64);
  for (ConvexPolyhedron& block : blocks_)
  {
    const double tol = tolerance_for(block);
    bool apart = !block.bounding_box().overlaps(region.bounds, -tol);
    // A block wholly outside one face of the region (touching it at most)
    // is not cut at all.
    for (std::size_t f = 0; f < region.planes.size() && !apart; ++f)
      apart = block.extent_along(region.planes[f]).first >= -tol;
    if (apart)
    {
      result.push_back(std::move(block));
      continue;
    }
    // Peel off the parts outside each face of the region; what is left at the
    // end lies inside the region and is removed.
    ConvexPolyhedron inside = std::move(block);
    bool outside = false;
    for (const Plane& face : region.planes)
    {
      const auto [lo, hi] = inside.extent_along(face);
      if (lo >= -tol) // wholly outside this face: the rest is kept
      {
        outside = true;
        break;
      }
      if (hi <= tol) // wholly inside this face
        continue;
      ConvexPolyhedron above, below;
      if (try_cut(inside, face, above, below))
      {
        result.push_back(std::move(above));
        inside = std::move(below);
      }
      else if (hi < -lo) // refused sliver: the larger part decides
        continue;
      else
      {
        outside = true;
        break;
      }
    }
    if (!outside)
      removed += inside.volume();
    if (outside || keep)
      result.push_back(std::move(inside));
  }
  blocks_ = std::move(result);
  return removed;
}

} // namespace talus
