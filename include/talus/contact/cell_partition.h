#pragma once

#include <talus/geometry/plane.h>

#include <functional>
#include <vector>

namespace talus
{

/// Space split among ranks along the cells of the cell space (the manual's
/// "Data Structure": each processor takes charge of cells and of the blocks
/// in them). Recursive bisection: the ranks are halved, and the region
/// they share is cut across its longest side at the cell boundary that
/// splits the work between the halves in proportion to their number of
/// ranks. Every rank's region is therefore a box of whole cells; the
/// regions of the ranks at the outside reach to infinity, so that a block
/// that leaves the model's box still has an owner.
class CellPartition
{
public:
  /// Splits among `n_ranks` the work `work[i]` (any unit: blocks,
  /// sub-contacts and zones weighed by their cost) that sits at
  /// `point[i]` (a block's centroid), on the grid of cells of size
  /// `cell_size` (m, per axis) whose corner is `origin` (m), inside
  /// `domain` (the box the cuts are placed in; the model's bounds).
  ///
  /// The work may be spread over several processes, each passing only its
  /// own points: `sum_over_processes` then adds, element by element, the
  /// numbers every process computed from its points (the work of each open
  /// region's cell slabs along each axis, a few hundred numbers a region)
  /// and must give every process the same sums, bit for bit. Every process
  /// then makes the same cuts, those one process makes from all the points
  /// when the sums are exact, without any process holding them all. It is
  /// called collectively once per level of the bisection: log2 n_ranks + 1
  /// times when the cuts halve the ranks, more when crowded work makes them
  /// lopsided (up to n_ranks). Without it the points are all the work.
  using SumOverProcesses = std::function<void(std::vector<double>&)>;
  CellPartition(const Box& domain, const Vec3& origin, const Vec3& cell_size,
                const std::vector<Vec3>& point, const std::vector<double>& work,
                unsigned int n_ranks, const SumOverProcesses& sum_over_processes = nullptr);

  unsigned int n_ranks() const { return n_ranks_; }

  /// The rank whose region holds x (a point on a cut belongs to the side
  /// above it).
  unsigned int owner(const Vec3& x) const;

  /// Rank r's region; sides at the outside of the model are at +-infinity.
  Box region(unsigned int rank) const;

  /// The ranks whose regions come within `reach` (m) of the box `b`: the
  /// ranks that must see a block of that envelope as a ghost.
  void ranks_near(const Box& b, double reach, std::vector<unsigned int>& ranks) const;

  /// The work each rank received, and the largest over the mean (1: even).
  const std::vector<double>& rank_work() const { return rank_work_; }
  double imbalance() const;

  /// The cuts, the grid and the ranks' work as numbers (a checkpoint keeps
  /// the partition a rebalance chose), and the partition made from them.
  std::vector<double> numbers() const;
  static CellPartition from_numbers(const std::vector<double>& numbers);

private:
  CellPartition() = default;
  /// One cut of the bisection tree: ranks [first, first + n) split at
  /// `position` along `axis` into `below` (n_below ranks) and `above`.
  struct Cut
  {
    int axis = -1; ///< -1: a leaf (one rank)
    double position = 0.0;
    unsigned int first_rank = 0, n_ranks = 1;
    int below = -1, above = -1; ///< child cuts
  };
  /// A region of the bisection still to be cut: its cut's index, its box,
  /// and the points in it.
  struct Open
  {
    int cut;
    Box region;
    std::vector<unsigned int> items;
  };
  /// The region's slabs of whole cells along each axis: the first, and how
  /// many (a cut needs at least 2).
  void slabs_of(const Box& region, double first_slab[3], double n_slabs[3]) const;
  /// Appends to `numbers` what cutting `open` needs from the points: for a
  /// leaf its work, else its total work and its work per slab along each
  /// axis that has 2 slabs or more.
  void add_slab_work(const Open& open, const std::vector<Vec3>& point,
                     const std::vector<double>& work, std::vector<double>& numbers) const;
  /// Cuts `open` by its numbers (starting at `numbers[at]`, which it
  /// advances), appending its two halves to `next`; a leaf takes its work.
  void cut(Open& open, const std::vector<Vec3>& point, const std::vector<double>& numbers,
           std::size_t& at, std::vector<Open>& next);
  void near(int cut, const Box& b, std::vector<unsigned int>& ranks) const;

  Vec3 origin_, cell_size_;
  unsigned int n_ranks_ = 1;
  std::vector<Cut> cuts_; ///< cuts_[0] is the root
  std::vector<double> rank_work_;
};

} // namespace talus
