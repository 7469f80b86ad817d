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
                             unsigned int n_ranks, const SumOverProcesses& sum_over_processes)
    : origin_(origin), cell_size_(cell_size), n_ranks_(n_ranks), rank_work_(n_ranks, 0.0)
{
  if (n_ranks == 0 || point.size() != work.size() || !(cell_size.array() > 0.0).all())
    throw std::logic_error("CellPartition: no ranks, unequal point and work counts, or a cell "
                           "size that is not positive");
  cuts_.reserve(2 * n_ranks);
  cuts_.emplace_back();
  cuts_[0].first_rank = 0;
  cuts_[0].n_ranks = n_ranks;
  // Level by level (each region's cut comes from its own points only, so
  // the order of the levels does not change the cuts): the numbers of every
  // open region of a level together, so that processes holding parts of
  // the work add them once per level.
  std::vector<Open> open(1);
  open[0].cut = 0;
  open[0].region = domain;
  open[0].items.resize(point.size());
  std::iota(open[0].items.begin(), open[0].items.end(), 0u);
  while (!open.empty())
  {
    std::vector<double> numbers;
    for (const Open& o : open)
      add_slab_work(o, point, work, numbers);
    if (sum_over_processes)
      sum_over_processes(numbers);
    std::vector<Open> next;
    std::size_t at = 0;
    for (Open& o : open)
      cut(o, point, numbers, at, next);
    open = std::move(next);
  }
}

void CellPartition::slabs_of(const Box& region, double first_slab[3], double n_slabs[3]) const
{
  for (int a = 0; a < 3; ++a)
  {
    first_slab[a] = slab(region.lo[a], origin_[a], cell_size_[a]);
    n_slabs[a] = slab(region.hi[a], origin_[a], cell_size_[a]) - first_slab[a] + 1.0;
  }
}

void CellPartition::add_slab_work(const Open& o, const std::vector<Vec3>& point,
                                  const std::vector<double>& work,
                                  std::vector<double>& numbers) const
{
  double total = 0.0;
  for (unsigned int i : o.items)
    total += work[i];
  numbers.push_back(total);
  if (cuts_[o.cut].n_ranks == 1)
    return;
  // Along each axis, the work per slab of whole cells in the region; points
  // beyond it (outside the model's box) count in its end slabs.
  double first_slab[3], n_slabs[3];
  slabs_of(o.region, first_slab, n_slabs);
  for (int a = 0; a < 3; ++a)
  {
    if (n_slabs[a] < 2.0)
      continue;
    const std::size_t first = numbers.size();
    numbers.resize(first + static_cast<std::size_t>(n_slabs[a]), 0.0);
    for (unsigned int i : o.items)
    {
      const double k = slab(point[i][a], origin_[a], cell_size_[a]) - first_slab[a];
      numbers[first + static_cast<std::size_t>(std::clamp(k, 0.0, n_slabs[a] - 1.0))] += work[i];
    }
  }
}

void CellPartition::cut(Open& o, const std::vector<Vec3>& point, const std::vector<double>& numbers,
                        std::size_t& at, std::vector<Open>& next)
{
  const int me = o.cut;
  const unsigned int first_rank = cuts_[me].first_rank, n = cuts_[me].n_ranks;
  const double total = numbers[at++];
  if (n == 1)
  {
    rank_work_[first_rank] += total;
    return;
  }
  // Along each axis, every boundary between slabs and every count of ranks
  // below it: the best makes the larger work per rank on either side the
  // least.
  double first_slab[3], n_slabs[3];
  slabs_of(o.region, first_slab, n_slabs);
  double load[3], cut_at[3];
  unsigned int ranks_below[3];
  for (int a = 0; a < 3; ++a)
  {
    load[a] = std::numeric_limits<double>::infinity();
    cut_at[a] = first_slab[a] + n_slabs[a]; // all below: one cell thick, no cut
    ranks_below[a] = n / 2;
    if (n_slabs[a] < 2.0)
      continue;
    const double* per_slab = numbers.data() + at;
    const std::size_t count = static_cast<std::size_t>(n_slabs[a]);
    at += count;
    double below = 0.0;
    for (std::size_t k = 0; k + 1 < count; ++k)
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
  const double position = cut_at[axis];
  const unsigned int n_below = ranks_below[axis];
  Open lower{static_cast<int>(cuts_.size()), o.region, {}};
  Open upper{static_cast<int>(cuts_.size()) + 1, o.region, {}};
  for (unsigned int i : o.items)
    (slab(point[i][axis], origin_[axis], cell_size_[axis]) < position ? lower : upper)
        .items.push_back(i);
  o.items.clear();
  o.items.shrink_to_fit();
  lower.region.hi[axis] = origin_[axis] + (position - 0.5) * cell_size_[axis];
  upper.region.lo[axis] = origin_[axis] + (position + 0.5) * cell_size_[axis];
  cuts_.emplace_back();
  cuts_.emplace_back();
  cuts_[me].axis = axis;
  cuts_[me].position = position; // in slabs from the origin
  cuts_[me].below = lower.cut;
  cuts_[me].above = upper.cut;
  cuts_[lower.cut].first_rank = first_rank;
  cuts_[lower.cut].n_ranks = n_below;
  cuts_[upper.cut].first_rank = first_rank + n_below;
  cuts_[upper.cut].n_ranks = n - n_below;
  next.push_back(std::move(lower));
  next.push_back(std::move(upper));
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
    // Children come after their cut (cut() numbers them so): no cycles.
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
