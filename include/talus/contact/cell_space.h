#pragma once

#include <talus/geometry/plane.h>

#include <utility>
#include <vector>

namespace talus
{

class CheckpointReader;
class CheckpointWriter;

/// Neighbour search by cell space: the model's bounding box divided into
/// rectangular cells of about one block each; each block is entered in the
/// cells its envelope (axis-aligned box, enlarged by a margin) covers, and
/// the candidates of a block are the blocks sharing a cell with it. Cost per
/// block does not depend on the number of blocks.
class CellSpace
{
public:
  /// Sets the space to cover `bounds` with about one cell per block.
  void define(const Box& bounds, unsigned int n_blocks);

  /// Enters every envelope; envelopes outside the space grow it by 10 % in
  /// the direction they leave it (then everything is mapped again).
  void map(const std::vector<Box>& envelopes);

  /// Pairs (i < j) of blocks whose envelopes overlap, each pair once.
  /// When `only` is not empty, only pairs with at least one block flagged.
  void candidate_pairs(const std::vector<Box>& envelopes, const std::vector<char>& only,
                       std::vector<std::pair<unsigned int, unsigned int>>& pairs) const;

  const Box& bounds() const { return bounds_; }
  /// m, per axis; the grid's corner is bounds().lo.
  const Vec3& cell_size() const { return cell_size_; }
  unsigned int n_cells() const { return n_[0] * n_[1] * n_[2]; }
  unsigned int regrowths() const { return regrowths_; }

  /// Checkpoints: the bounds (grown during a run) and the grid on them.
  void save_state(CheckpointWriter& out) const;
  void load_state(CheckpointReader& in);

private:
  void cell_range(const Box& b, int lo[3], int hi[3]) const;

  Box bounds_;
  unsigned int n_[3] = {1, 1, 1};
  Vec3 cell_size_ = Vec3::Ones();
  std::vector<unsigned int> cell_start_; ///< CSR: blocks of cell c are
  std::vector<unsigned int> cell_block_; ///< cell_block_[cell_start_[c] ..]
  unsigned int regrowths_ = 0;
};

} // namespace talus
