#include <talus/contact/block_decomposition.h>
#include <talus/contact/cell_space.h>

#include <algorithm>
#include <map>

namespace talus
{

unsigned int RankBlocks::n_owned() const
{
  return static_cast<unsigned int>(std::count(owned.begin(), owned.end(), 1));
}

namespace
{

/// Each block's box: the bounds of its vertices.
std::vector<Box> vertex_boxes(const BlockModel& m)
{
  std::vector<Box> box(m.n_blocks());
  for (unsigned int b = 0; b < m.n_blocks(); ++b)
  {
    Box e{m.vertex[m.vertex_start[b]], m.vertex[m.vertex_start[b]]};
    for (unsigned int v = m.vertex_start[b]; v < m.vertex_start[b + 1]; ++v)
    {
      e.lo = e.lo.cwiseMin(m.vertex[v]);
      e.hi = e.hi.cwiseMax(m.vertex[v]);
    }
    box[b] = e;
  }
  return box;
}

/// Blocks whose boxes grown by half the reach overlap: each block's
/// neighbours (CSR: neighbours of b are neighbour[start[b] .. start[b+1])).
void neighbours_within(const std::vector<Box>& box, double reach, const std::vector<char>& removed,
                       std::vector<unsigned int>& start, std::vector<unsigned int>& neighbour)
{
  const unsigned int n = static_cast<unsigned int>(box.size());
  // The live blocks only enter the cell space: a removed block's box may
  // be unknown (BlockMigration), and its pairs would be dropped anyway.
  std::vector<unsigned int> live_block;
  std::vector<Box> envelope;
  Box bounds{Vec3::Zero(), Vec3::Zero()};
  for (unsigned int b = 0; b < n; ++b)
  {
    if (!removed.empty() && removed[b])
      continue;
    Box e = box[b];
    e.lo.array() -= 0.5 * reach;
    e.hi.array() += 0.5 * reach;
    bounds.lo = envelope.empty() ? e.lo : bounds.lo.cwiseMin(e.lo);
    bounds.hi = envelope.empty() ? e.hi : bounds.hi.cwiseMax(e.hi);
    envelope.push_back(e);
    live_block.push_back(b);
  }
  CellSpace cells;
  cells.define(bounds, static_cast<unsigned int>(envelope.size()));
  cells.map(envelope);
  std::vector<std::pair<unsigned int, unsigned int>> pairs;
  cells.candidate_pairs(envelope, {}, pairs);
  for (auto& [a, b] : pairs)
  {
    a = live_block[a];
    b = live_block[b];
  }
  std::vector<unsigned int> count(n + 1, 0);
  for (const auto& [a, b] : pairs)
  {
    ++count[a + 1];
    ++count[b + 1];
  }
  start.assign(n + 1, 0);
  for (unsigned int b = 0; b < n; ++b)
    start[b + 1] = start[b] + count[b + 1];
  neighbour.assign(start[n], 0);
  std::vector<unsigned int> fill(start.begin(), start.end() - 1);
  for (const auto& [a, b] : pairs)
  {
    neighbour[fill[a]++] = b;
    neighbour[fill[b]++] = a;
  }
}

/// Marks (1) the blocks within `layers` steps of the blocks already marked.
void grow(std::vector<char>& mark, unsigned int layers, const std::vector<unsigned int>& start,
          const std::vector<unsigned int>& neighbour)
{
  std::vector<unsigned int> front;
  for (unsigned int b = 0; b < mark.size(); ++b)
    if (mark[b])
      front.push_back(b);
  for (unsigned int layer = 0; layer < layers; ++layer)
  {
    std::vector<unsigned int> next;
    for (unsigned int b : front)
      for (unsigned int k = start[b]; k < start[b + 1]; ++k)
        if (!mark[neighbour[k]])
        {
          mark[neighbour[k]] = 1;
          next.push_back(neighbour[k]);
        }
    front.swap(next);
  }
}

} // namespace

RankBlocks decompose_blocks(const BlockModel& m, const CellPartition& partition, unsigned int rank,
                            double reach, unsigned int layers, const std::vector<char>& removed)
{
  std::vector<unsigned int> owner(m.n_blocks());
  for (unsigned int b = 0; b < m.n_blocks(); ++b)
    owner[b] = partition.owner(m.centroid[b]);
  return decompose_blocks(vertex_boxes(m), owner, rank, reach, layers, removed);
}

RankBlocks decompose_blocks(const std::vector<Box>& box, const std::vector<unsigned int>& owner,
                            unsigned int rank, double reach, unsigned int layers,
                            const std::vector<char>& removed)
{
  const unsigned int n = static_cast<unsigned int>(box.size());
  const auto live = [&](unsigned int b) { return removed.empty() || !removed[b]; };
  std::vector<unsigned int> start, neighbour;
  neighbours_within(box, reach, removed, start, neighbour);

  // Held by a rank: its own blocks and those within `layers` steps.
  const auto held_by = [&](unsigned int r)
  {
    std::vector<char> mark(n, 0);
    for (unsigned int b = 0; b < n; ++b)
      mark[b] = owner[b] == r && live(b);
    grow(mark, layers, start, neighbour);
    return mark;
  };
  const std::vector<char> mine = held_by(rank);
  RankBlocks out;
  out.rank = rank;
  std::vector<int> local_of(n, -1);
  for (unsigned int b = 0; b < n; ++b)
    if (mine[b])
    {
      local_of[b] = static_cast<int>(out.local.size());
      out.local.push_back(b);
      out.owned.push_back(owner[b] == rank);
    }
  // Ghosts come from their owners; this rank's blocks go to every rank
  // that holds them, and only an owner of a ghost here can hold one (its
  // own block is within reach of it).
  std::map<unsigned int, std::vector<unsigned int>> receive, send;
  for (unsigned int i = 0; i < out.local.size(); ++i)
    if (!out.owned[i])
      receive[owner[out.local[i]]].push_back(i);
  for (const auto& [other, ghosts] : receive)
  {
    const std::vector<char> theirs = held_by(other);
    for (unsigned int i = 0; i < out.local.size(); ++i)
      if (out.owned[i] && theirs[out.local[i]])
        send[other].push_back(i);
  }
  out.receive.assign(receive.begin(), receive.end());
  for (const auto& [other, blocks] : send)
    out.send.emplace_back(other, blocks);
  return out;
}

} // namespace talus
