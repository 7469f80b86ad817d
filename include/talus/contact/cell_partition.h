#pragma once

#include <talus/geometry/plane.h>

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
  CellPartition(const Box& domain, const Vec3& origin, const Vec3& cell_size,
                const std::vector<Vec3>& point, const std::vector<double>& work,
                unsigned int n_ranks);

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
  int split(const Box& region, unsigned int first_rank, unsigned int n,
            std::vector<unsigned int>& items, const std::vector<Vec3>& point,
            const std::vector<double>& work);
  void near(int cut, const Box& b, std::vector<unsigned int>& ranks) const;

  Vec3 origin_, cell_size_;
  unsigned int n_ranks_ = 1;
  std::vector<Cut> cuts_; ///< cuts_[0] is the root
  std::vector<double> rank_work_;
};

} // namespace talus
