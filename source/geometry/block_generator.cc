#include <talus/geometry/block_generator.h>
#include <talus/geometry/mass_properties.h>
#include <talus/geometry/plane_cut.h>

#include <algorithm>
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

CutOperation CutOperation::joint_set(const JointSetSpec& set, int origin)
{
  CutOperation op;
  op.kind = Kind::joint_set;
  op.set = set;
  op.origin = origin;
  return op;
}

CutOperation CutOperation::single_plane(const Plane& plane, const Box* extent, int origin)
{
  CutOperation op;
  op.kind = Kind::plane;
  op.plane = plane;
  op.limited = extent != nullptr;
  if (extent)
    op.extent = *extent;
  op.origin = origin;
  return op;
}

CutOperation CutOperation::excavation(const ConvexRegion& region)
{
  CutOperation op;
  op.kind = Kind::excavate;
  op.region = region;
  return op;
}

CutOperation CutOperation::along(const ConvexRegion& region)
{
  CutOperation op;
  op.kind = Kind::cut_along;
  op.region = region;
  return op;
}

bool BlockGenerator::try_cut(const ConvexPolyhedron& block, const Plane& plane,
                             ConvexPolyhedron& above, ConvexPolyhedron& below, int origin,
                             CuttingReport& report) const
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
        if (report.skipped_slivers == 0 || v < report.smallest_refused)
        {
          report.smallest_refused = v;
          report.smallest_refused_at = piece->vertex_mean();
        }
        ++report.skipped_slivers;
        return false;
      }
    }
  }
  ++report.cuts;
  above = std::move(cut.above);
  below = std::move(cut.below);
  return true;
}

void BlockGenerator::cut_by_set(const JointSetSpec& set, int origin, ConvexPolyhedron&& block,
                                std::vector<ConvexPolyhedron>& out, CuttingReport& report) const
{
  if (set.limited && !set.extent.contains(compute_mass_properties(block).centroid))
  {
    out.push_back(std::move(block));
    return;
  }
  const Vec3 n = normal_from_dip(set.dip, set.dip_direction);
  const Plane reference = Plane::through(set.origin, n);
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
    if (try_cut(rest, joint, above, below, origin, report))
    {
      out.push_back(std::move(below));
      rest = std::move(above);
    }
  }
  out.push_back(std::move(rest));
}

void BlockGenerator::split_by(const ConvexRegion& region, bool keep, ConvexPolyhedron&& block,
                              std::vector<ConvexPolyhedron>& out, CuttingReport& report,
                              double& volume) const
{
  const double tol = tolerance_for(block);
  bool apart = !block.bounding_box().overlaps(region.bounds, -tol);
  // A block wholly outside one face of the region (touching it at most)
  // is not cut at all.
  for (std::size_t f = 0; f < region.planes.size() && !apart; ++f)
    apart = block.extent_along(region.planes[f]).first >= -tol;
  if (apart)
  {
    out.push_back(std::move(block));
    return;
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
    if (try_cut(inside, face, above, below, 0, report))
    {
      out.push_back(std::move(above));
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
    volume += inside.volume();
  if (outside || keep)
    out.push_back(std::move(inside));
}

void BlockGenerator::cut_piece(const CutOperation& op, ConvexPolyhedron&& block,
                               std::vector<ConvexPolyhedron>& out, CuttingReport& report,
                               double& volume) const
{
  switch (op.kind)
  {
  case CutOperation::Kind::joint_set:
    cut_by_set(op.set, op.origin, std::move(block), out, report);
    return;
  case CutOperation::Kind::plane:
  {
    ConvexPolyhedron above, below;
    if ((!op.limited || op.extent.contains(compute_mass_properties(block).centroid)) &&
        try_cut(block, op.plane, above, below, op.origin, report))
    {
      out.push_back(std::move(below));
      out.push_back(std::move(above));
    }
    else
      out.push_back(std::move(block));
    return;
  }
  case CutOperation::Kind::excavate:
    split_by(op.region, false, std::move(block), out, report, volume);
    return;
  case CutOperation::Kind::cut_along:
    split_by(op.region, true, std::move(block), out, report, volume);
    return;
  }
}

double BlockGenerator::apply(const CutOperation& op)
{
  double volume = 0.0;
  std::vector<ConvexPolyhedron> result;
  result.reserve(blocks_.size() + 64);
  for (ConvexPolyhedron& block : blocks_)
    cut_piece(op, std::move(block), result, report_, volume);
  blocks_ = std::move(result);
  return volume;
}

void BlockGenerator::cut_joint_set(const JointSetSpec& set, int origin)
{
  apply(CutOperation::joint_set(set, origin));
}

void BlockGenerator::cut_plane(const Plane& plane, const Box* extent, int origin)
{
  apply(CutOperation::single_plane(plane, extent, origin));
}

double BlockGenerator::excavate(const ConvexRegion& region)
{
  return apply(CutOperation::excavation(region));
}

double BlockGenerator::cut_along(const ConvexRegion& region)
{
  return apply(CutOperation::along(region));
}

void BlockGenerator::cut_depth_first(
    const std::vector<CutOperation>& ops,
    const std::function<void(unsigned long, ConvexPolyhedron&)>& visit,
    std::vector<OperationTally>& tally) const
{
  tally.assign(ops.size(), OperationTally());
  // level[k]: the pieces operation k made of the piece it was given, not
  // yet taken further; next[k]: the first of them still to go.
  std::vector<std::vector<ConvexPolyhedron>> level(ops.size() + 1);
  std::vector<std::size_t> next(ops.size() + 1, 0);
  level[0] = blocks_; // the generator's blocks are the start
  unsigned long number = 0;
  std::size_t k = 0; // the level whose next piece goes on
  for (;;)
  {
    if (next[k] == level[k].size())
    {
      if (k == 0)
        break;
      --k; // this branch is done: back to the pieces above
      continue;
    }
    ConvexPolyhedron& piece = level[k][next[k]++];
    if (k == ops.size())
    {
      visit(number++, piece);
      continue;
    }
    std::vector<ConvexPolyhedron>& below = level[k + 1];
    below.clear();
    cut_piece(ops[k], std::move(piece), below, tally[k].cutting, tally[k].volume);
    next[k + 1] = 0;
    ++k;
  }
}

CuttingReport total_report(const std::vector<OperationTally>& tally)
{
  CuttingReport sum;
  for (const OperationTally& t : tally)
  {
    const CuttingReport& r = t.cutting;
    // A refused piece replaces the smallest so far only when smaller, as
    // when the operations are applied in turn.
    if (r.skipped_slivers > 0 &&
        (sum.skipped_slivers == 0 || r.smallest_refused < sum.smallest_refused))
    {
      sum.smallest_refused = r.smallest_refused;
      sum.smallest_refused_at = r.smallest_refused_at;
    }
    sum.cuts += r.cuts;
    sum.skipped_slivers += r.skipped_slivers;
  }
  return sum;
}

} // namespace talus
