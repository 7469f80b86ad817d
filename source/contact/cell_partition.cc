#include <talus/contact/cell_partition.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace talus
{

namespace
{

/// The index of the cell slab along `axis` that holds coordinate x. Every
/// decision (binning, ownership) goes through it, so that a point exactly
/// on a cut is on the same side for all of them.
double slab(double x, double origin, double size)
{
  return std::floor((x - origin) / size);
}

} // namespace

CellPartition::CellPartition(const Box& domain, const Vec3& origin, const Vec3& cell_size,
                             const std::vector<Vec3>& point, const std::vector<double>& work,
                             unsigned int n_ranks)
    : origin_(origin), cell_size_(cell_size), n_ranks_(n_ranks), rank_work_(n_ranks, 0.0)
{
  if (n_ranks == 0 || point.size() != work.size() || !(cell_size.array() > 0.0).all())
    throw std::logic_error("CellPartition: no ranks, unequal point and work counts, or a cell "
                           "size that is not positive");
  std::vector<unsigned int> items(point.size());
  std::iota(items.begin(), items.end(), 0u);
  cuts_.reserve(2 * n_ranks);
  split(domain, 0, n_ranks, items, point, work);
}

int CellPartition::split(const Box& region, unsigned int first_rank, unsigned int n,
                         std::vector<unsigned int>& items, const std::vector<Vec3>& point,
                         const std::vector<double>& work)
{
  const int me = static_cast<int>(cuts_.size());
  cuts_.emplace_back();
  cuts_[me].first_rank = first_rank;
  cuts_[me].n_ranks = n;
  if (n == 1)
  {
    for (unsigned int i : items)
      rank_work_[first_rank] += work[i];
    return me;
  }
  // The slabs of whole cells inside the region along each axis.
  double first_slab[3], n_slabs[3];
  for (int a = 0; a < 3; ++a)
  {
    first_slab[a] = slab(region.lo[a], origin_[a], cell_size_[a]);
    n_slabs[a] = slab(region.hi[a], origin_[a], cell_size_[a]) - first_slab[a] + 1.0;
  }
  // Along each axis, every boundary between slabs and every count of ranks
  // below it: the best makes the larger work per rank on either side the
  // least. Items beyond the region (outside the model's box) count in its
  // end slabs.
  double total = 0.0;
  for (unsigned int i : items)
    total += work[i];
  double load[3], cut_at[3];
  unsigned int ranks_below[3];
  for (int a = 0; a < 3; ++a)
  {
    load[a] = std::numeric_limits<double>::infinity();
    cut_at[a] = first_slab[a] + n_slabs[a]; // all below: one cell thick, no cut
    ranks_below[a] = n / 2;
    if (n_slabs[a] < 2.0)
      continue;
    std::vector<double> per_slab(static_cast<std::size_t>(n_slabs[a]), 0.0);
    for (unsigned int i : items)
    {
      const double k = slab(point[i][a], origin_[a], cell_size_[a]) - first_slab[a];
      per_slab[static_cast<std::size_t>(std::clamp(k, 0.0, n_slabs[a] - 1.0))] += work[i];
    }
    double below = 0.0;
    for (std::size_t k = 0; k + 1 < per_slab.size(); ++k)
    {
      below += per_slab[k];
      // Ranks below in proportion to the work below, and its neighbours.
      const double share = below / total * n;
      for (double nb : {std::floor(share), std::ceil(share)})
      {
        const unsigned int m = static_cast<unsigned int>(std::clamp(nb, 1.0, n - 1.0));
        const double l = std::max(below / m, (total - below) / (n - m));
        if (l < load[a])
        {
          load[a] = l;
          cut_at[a] = first_slab[a] + static_cast<double>(k) + 1.0;
          ranks_below[a] = m;
        }
      }
    }
  }
  // The longest side (fewest ghosts) among the axes whose cut is within 1 %
  // of the best: a crowded corner may be cut finely only across another.
  const double best_load = std::min({load[0], load[1], load[2]});
  int axis = -1;
  for (int a = 0; a < 3; ++a)
    if (load[a] <= best_load * 1.01 && (axis < 0 || n_slabs[a] > n_slabs[axis]))
      axis = a;
  if (axis < 0) // no side can be cut: every axis one cell thick
    axis = 0;
  const double cut = cut_at[axis];
  const unsigned int n_below = ranks_below[axis];
  cuts_[me].axis = axis;
  cuts_[me].position = cut; // in slabs from the origin
  std::vector<unsigned int> lower, upper;
  for (unsigned int i : items)
    (slab(point[i][axis], origin_[axis], cell_size_[axis]) < cut ? lower : upper).push_back(i);
  items.clear();
  items.shrink_to_fit();
  Box region_below = region, region_above = region;
  region_below.hi[axis] = origin_[axis] + (cut - 0.5) * cell_size_[axis];
  region_above.lo[axis] = origin_[axis] + (cut + 0.5) * cell_size_[axis];
  const int b = split(region_below, first_rank, n_below, lower, point, work);
  const int u = split(region_above, first_rank + n_below, n - n_below, upper, point, work);
  cuts_[me].below = b;
  cuts_[me].above = u;
  return me;
}

unsigned int CellPartition::owner(const Vec3& x) const
{
  int c = 0;
  while (cuts_[c].axis >= 0)
  {
    const Cut& cut = cuts_[c];
    c = slab(x[cut.axis], origin_[cut.axis], cell_size_[cut.axis]) < cut.position ? cut.below
                                                                                  : cut.above;
  }
  return cuts_[c].first_rank;
}

Box CellPartition::region(unsigned int rank) const
{
  const double inf = std::numeric_limits<double>::infinity();
  Box box{Vec3::Constant(-inf), Vec3::Constant(inf)};
  int c = 0;
  while (cuts_[c].axis >= 0)
  {
    const Cut& cut = cuts_[c];
    const double at = origin_[cut.axis] + cut.position * cell_size_[cut.axis];
    if (rank < cuts_[cut.below].first_rank + cuts_[cut.below].n_ranks)
    {
      box.hi[cut.axis] = std::min(box.hi[cut.axis], at);
      c = cut.below;
    }
    else
    {
      box.lo[cut.axis] = std::max(box.lo[cut.axis], at);
      c = cut.above;
    }
  }
  return box;
}

void CellPartition::ranks_near(const Box& b, double reach, std::vector<unsigned int>& ranks) const
{
  ranks.clear();
  Box grown = b;
  grown.lo.array() -= reach;
  grown.hi.array() += reach;
  near(0, grown, ranks);
}

void CellPartition::near(int c, const Box& b, std::vector<unsigned int>& ranks) const
{
  const Cut& cut = cuts_[c];
  if (cut.axis < 0)
  {
    ranks.push_back(cut.first_rank);
    return;
  }
  const double at = origin_[cut.axis] + cut.position * cell_size_[cut.axis];
  if (b.lo[cut.axis] < at)
    near(cut.below, b, ranks);
  if (b.hi[cut.axis] >= at)
    near(cut.above, b, ranks);
}

double CellPartition::imbalance() const
{
  const double total = std::accumulate(rank_work_.begin(), rank_work_.end(), 0.0);
  if (total <= 0.0)
    return 1.0;
  return *std::max_element(rank_work_.begin(), rank_work_.end()) * n_ranks_ / total;
}

std::vector<double> CellPartition::numbers() const
{
  std::vector<double> out{origin_[0],    origin_[1],    origin_[2],       cell_size_[0],
                          cell_size_[1], cell_size_[2], double(n_ranks_), double(cuts_.size())};
  for (const Cut& c : cuts_)
    out.insert(out.end(), {double(c.axis), c.position, double(c.first_rank), double(c.n_ranks),
                           double(c.below), double(c.above)});
  out.insert(out.end(), rank_work_.begin(), rank_work_.end());
  return out;
}

CellPartition CellPartition::from_numbers(const std::vector<double>& numbers)
{
  const auto bad = []
  { return std::invalid_argument("CellPartition: the saved partition is not whole"); };
  if (numbers.size() < 8)
    throw bad();
  CellPartition p;
  p.origin_ = Vec3(numbers[0], numbers[1], numbers[2]);
  p.cell_size_ = Vec3(numbers[3], numbers[4], numbers[5]);
  p.n_ranks_ = static_cast<unsigned int>(numbers[6]);
  const std::size_t n_cuts = static_cast<std::size_t>(numbers[7]);
  if (p.n_ranks_ == 0 || numbers.size() != 8 + 6 * n_cuts + p.n_ranks_)
    throw bad();
  for (std::size_t c = 0; c < n_cuts; ++c)
  {
    const double* x = numbers.data() + 8 + 6 * c;
    Cut cut;
    cut.axis = static_cast<int>(x[0]);
    cut.position = x[1];
    cut.first_rank = static_cast<unsigned int>(x[2]);
    cut.n_ranks = static_cast<unsigned int>(x[3]);
    cut.below = static_cast<int>(x[4]);
    cut.above = static_cast<int>(x[5]);
    // Children come after their cut (split() numbers them so): no cycles.
    const int n = static_cast<int>(n_cuts), me = static_cast<int>(c);
    if (cut.axis > 2 || cut.first_rank + cut.n_ranks > p.n_ranks_ ||
        (cut.axis >= 0 && (cut.below <= me || cut.below >= n || cut.above <= me || cut.above >= n)))
      throw bad();
    p.cuts_.push_back(cut);
  }
  p.rank_work_.assign(numbers.end() - p.n_ranks_, numbers.end());
  return p;
}

} // namespace talus
