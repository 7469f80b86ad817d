#include <talus/contact/cell_space.h>

#include <algorithm>
#include <cmath>

namespace talus
{

void CellSpace::define(const Box& bounds, unsigned int n_blocks)
{
  bounds_ = bounds;
  const Vec3 size = (bounds.hi - bounds.lo).cwiseMax(1e-12);
  // About one cell per block (the manual's optimum), shaped like the space.
  const double cell = std::cbrt(size.prod() / std::max(1u, n_blocks));
  for (int d = 0; d < 3; ++d)
  {
    // A space grown to an infinite or NaN size (a run diverging) is one cell
    // until the solver stops it: never an index out of range.
    const double n = std::round(size[d] / cell);
    n_[d] = static_cast<unsigned int>(std::isfinite(n) ? std::clamp(n, 1.0, 1024.0) : 1.0);
    cell_size_[d] = size[d] / n_[d];
  }
}

void CellSpace::cell_range(const Box& b, int lo[3], int hi[3]) const
{
  // Clamped as doubles: a NaN or huge coordinate must not reach the cast.
  const auto cell_of = [&](double x, int d)
  {
    const double c = std::floor((x - bounds_.lo[d]) / cell_size_[d]);
    return std::isnan(c) ? 0 : static_cast<int>(std::clamp(c, 0.0, n_[d] - 1.0));
  };
  for (int d = 0; d < 3; ++d)
  {
    lo[d] = cell_of(b.lo[d], d);
    hi[d] = cell_of(b.hi[d], d);
  }
}

void CellSpace::map(const std::vector<Box>& envelopes)
{
  // A block leaving the space grows it by 10 % on that side (and a remap).
  bool grown = false;
  for (const Box& e : envelopes)
    for (int d = 0; d < 3; ++d)
    {
      const double extent = bounds_.hi[d] - bounds_.lo[d];
      if (e.lo[d] < bounds_.lo[d])
      {
        bounds_.lo[d] = std::min(e.lo[d], bounds_.lo[d] - 0.1 * extent);
        grown = true;
      }
      if (e.hi[d] > bounds_.hi[d])
      {
        bounds_.hi[d] = std::max(e.hi[d], bounds_.hi[d] + 0.1 * extent);
        grown = true;
      }
    }
  if (grown)
  {
    ++regrowths_;
    define(bounds_, static_cast<unsigned int>(envelopes.size()));
  }

  // Counting sort of (cell, block) entries into CSR arrays.
  cell_start_.assign(n_cells() + 1, 0);
  int lo[3], hi[3];
  for (const Box& e : envelopes)
  {
    cell_range(e, lo, hi);
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i)
          ++cell_start_[(k * n_[1] + j) * n_[0] + i + 1];
  }
  for (unsigned int c = 0; c < n_cells(); ++c)
    cell_start_[c + 1] += cell_start_[c];
  cell_block_.resize(cell_start_.back());
  std::vector<unsigned int> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (unsigned int b = 0; b < envelopes.size(); ++b)
  {
    cell_range(envelopes[b], lo, hi);
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i)
          cell_block_[fill[(k * n_[1] + j) * n_[0] + i]++] = b;
  }
}

void CellSpace::candidate_pairs(const std::vector<Box>& envelopes, const std::vector<char>& only,
                                std::vector<std::pair<unsigned int, unsigned int>>& pairs) const
{
  pairs.clear();
  // `seen[j] == i + 1` marks j as already paired with i: no sort, no set.
  std::vector<unsigned int> seen(envelopes.size(), 0);
  int lo[3], hi[3];
  for (unsigned int b = 0; b < envelopes.size(); ++b)
  {
    if (!only.empty() && !only[b])
      continue;
    cell_range(envelopes[b], lo, hi);
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i)
        {
          const unsigned int c = (k * n_[1] + j) * n_[0] + i;
          for (unsigned int e = cell_start_[c]; e < cell_start_[c + 1]; ++e)
          {
            const unsigned int other = cell_block_[e];
            // A pair of two flagged blocks is produced from its first block only.
            if (other == b || seen[other] == b + 1 || ((only.empty() || only[other]) && other < b))
              continue;
            seen[other] = b + 1;
            if (envelopes[b].overlaps(envelopes[other]))
              pairs.emplace_back(std::min(b, other), std::max(b, other));
          }
        }
  }
}

} // namespace talus
