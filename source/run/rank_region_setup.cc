// A rank's share of a scene's rigid blocks built without the whole model
// (issue 24): the brick is cut one piece at a time, and each rank keeps the
// blocks of its region and those near it.

#include <talus/base/exceptions.h>
#include <talus/contact/cell_partition.h>
#include <talus/contact/cell_space.h>
#include <talus/geometry/mass_properties.h>
#include <talus/run/rank_share.h>

#include <algorithm>
#include <vector>

namespace talus
{

RankShare::RankShare(const Scene& scene, BuildReport& report, double reach, MPI_Comm comm,
                     ModelDigest* digest, const std::function<void()>& check,
                     const RankBlocks* saved)
    : comm_(comm), reach_(reach)
{
  MPI_Comm_rank(comm, &rank_);
  MPI_Comm_size(comm, &ranks_);
  const auto rank = static_cast<unsigned int>(rank_), ranks = static_cast<unsigned int>(ranks_);

  // 1. The model's bounds (those of every block's vertices, as the whole
  // model's) and its largest block, from every block; the centroids of this
  // rank's every ranks-th block for the partition.
  Box domain{Vec3::Zero(), Vec3::Zero()};
  bool first = true;
  double largest = 0.0; // m: the longest side of a block's box
  std::vector<Vec3> point;
  std::vector<unsigned int> none;
  build_blocks_where(
      scene, report,
      [&](unsigned int b, const ConvexPolyhedron& block)
      {
        const Box box = block.bounding_box();
        if (first)
          domain = box;
        first = false;
        domain.lo = domain.lo.cwiseMin(box.lo);
        domain.hi = domain.hi.cwiseMax(box.hi);
        largest = std::max(largest, (box.hi - box.lo).maxCoeff());
        if (b % ranks == rank)
          point.push_back(compute_mass_properties(block).centroid);
        if (digest != nullptr)
          digest->add(scene_block(scene, block, b), 0);
        return false;
      },
      none, n_blocks_);
  if (check)
    check();

  // 2. The regions, as the constructor from the whole model cuts them: a
  // block's work is 1, so the ranks' sums of cell slabs are exact.
  CellSpace cells;
  cells.define(domain, n_blocks_);
  partition_ = std::make_unique<CellPartition>(
      domain, domain.lo, cells.cell_size(), point, std::vector<double>(point.size(), 1.0), ranks,
      [comm](std::vector<double>& numbers) { sum_exactly_over_ranks(numbers, comm); });
  point = std::vector<Vec3>();
  balance_ = std::make_unique<RankBalance>(domain, cells.cell_size(), rebalance_threshold());

  // 3. The blocks this rank owns, and every block that can come within
  // reach of one of them: an owned block's box lies within the largest
  // block's side of the region, a ghost's within reach of that.
  Box near = partition_->region(rank);
  const double margin = largest + reach;
  near.lo.array() -= margin;
  near.hi.array() += margin;
  std::vector<unsigned int> global;
  BuildReport again;
  if (saved != nullptr) // a restart: the blocks the rank held at its checkpoint
  {
    BlockModel held = build_blocks_where(
        scene, again,
        [&](unsigned int b, const ConvexPolyhedron&)
        { return std::binary_search(saved->local.begin(), saved->local.end(), b); },
        global, n_blocks_);
    // (Agreed among the ranks before any of them stops: a rank that went on
    // would wait for the others in the exchanges.)
    int fits = global == saved->local;
    MPI_Allreduce(MPI_IN_PLACE, &fits, 1, MPI_INT, MPI_LAND, comm);
    if (!fits)
      throw InputError("a rank's checkpoint names blocks that this scene does not have (it has " +
                       std::to_string(n_blocks_) +
                       "): the checkpoint was written for another "
                       "scene");
    local_ = std::move(held);
    blocks_ = *saved;
    start_exchanges();
    return;
  }
  const BlockModel held = build_blocks_where(
      scene, again,
      [&](unsigned int, const ConvexPolyhedron& block)
      {
        return block.bounding_box().overlaps(near) ||
               partition_->owner(compute_mass_properties(block).centroid) == rank;
      },
      global, n_blocks_);

  // 4. Owned blocks and ghosts among those held, as among all blocks: every
  // block an owned one can touch is held, and so is every block of another
  // rank that can touch one of this rank's (which decides what is sent).
  RankBlocks mine = decompose_blocks(held, *partition_, rank, reach, ghost_layers);
  local_ = held.subset(mine.local);
  for (unsigned int& b : mine.local)
    b = global[b];
  blocks_ = std::move(mine);
  start_exchanges();
}

} // namespace talus
