// Space split among ranks by recursive bisection of the cell space
// (CellPartition): every block has one owner whose region holds it, the
// regions are boxes of whole cells that tile space without overlap, the
// work each rank receives is the work of the blocks it owns, the ranks
// near an envelope are those a search of every region finds, and the work
// is shared evenly to within the grain of the cells.
//
// Cases: the 238 blocks of parameters/benched_slope.prm (three joint sets,
// blocks of very different sizes) on the grid of its cell space; 100,000
// points spread evenly through a 100 m x 50 m x 20 m box on 1 m cells; and
// the same number crowded into one corner of it (a half-normal cloud), the
// case a split of the box itself would share worst. 2, 3, 4, 7 and 16 ranks.

#include <talus/contact/cell_partition.h>
#include <talus/contact/cell_space.h>
#include <talus/scene/build_blocks.h>
#include <talus/scene/scene.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "../tests.h"

using namespace talus;

namespace
{

bool on_cell_boundary(double x, double origin, double size)
{
  if (std::isinf(x))
    return true;
  const double k = (x - origin) / size;
  return std::abs(k - std::round(k)) < 1e-9;
}

/// A region clipped to the domain (its outer sides are at infinity).
Box clipped(Box r, const Box& domain)
{
  r.lo = r.lo.cwiseMax(domain.lo);
  r.hi = r.hi.cwiseMin(domain.hi);
  return r;
}

double overlap_volume(const Box& a, const Box& b)
{
  double v = 1.0;
  for (int d = 0; d < 3; ++d)
    v *= std::max(0.0, std::min(a.hi[d], b.hi[d]) - std::max(a.lo[d], b.lo[d]));
  return v;
}

void check_partition(const std::string& name, const Box& domain, const Vec3& cell,
                     const std::vector<Vec3>& point, const std::vector<double>& work,
                     unsigned int n_ranks, double largest_imbalance)
{
  const CellPartition p(domain, domain.lo, cell, point, work, n_ranks);
  // Owners hold their blocks, and the work per rank is theirs.
  std::vector<double> owned(n_ranks, 0.0);
  bool held = true;
  for (std::size_t i = 0; i < point.size(); ++i)
  {
    const unsigned int r = p.owner(point[i]);
    held &= r < n_ranks && p.region(r).contains(point[i]);
    if (r < n_ranks)
      owned[r] += work[i];
  }
  bool same_work = true;
  for (unsigned int r = 0; r < n_ranks; ++r)
    same_work &= owned[r] == p.rank_work()[r];
  // Regions of whole cells that tile the domain.
  bool whole_cells = true;
  double volume = 0.0, overlaps = 0.0;
  for (unsigned int r = 0; r < n_ranks; ++r)
  {
    const Box region = p.region(r);
    for (int d = 0; d < 3; ++d)
      whole_cells &= on_cell_boundary(region.lo[d], domain.lo[d], cell[d]) &&
                     on_cell_boundary(region.hi[d], domain.lo[d], cell[d]);
    volume += clipped(region, domain).volume();
    for (unsigned int s = r + 1; s < n_ranks; ++s)
      overlaps += overlap_volume(clipped(region, domain), clipped(p.region(s), domain));
  }
  // Ranks near an envelope (each point's 0.6 m box, 0.5 m reach) against
  // every region (half-open: a region holds its lower sides).
  bool near_ok = true;
  std::vector<unsigned int> found;
  for (std::size_t i = 0; i < point.size(); i += 7)
  {
    const Box e{point[i] - Vec3::Constant(0.3), point[i] + Vec3::Constant(0.3)};
    p.ranks_near(e, 0.5, found);
    std::sort(found.begin(), found.end());
    std::vector<unsigned int> all;
    for (unsigned int r = 0; r < n_ranks; ++r)
    {
      const Box region = p.region(r);
      bool meets = true;
      for (int d = 0; d < 3; ++d)
        meets &= e.lo[d] - 0.5 < region.hi[d] && e.hi[d] + 0.5 >= region.lo[d];
      if (meets)
        all.push_back(r);
    }
    near_ok &= found == all;
  }
  const bool tiles = std::abs(volume - domain.volume()) <= 1e-9 * domain.volume() &&
                     overlaps <= 1e-9 * domain.volume();
  std::printf("%s, %u ranks: owners hold their blocks %s, work per rank %s, whole cells %s, "
              "tiling %s, ranks near %s, imbalance %.3f (at most %.2f) %s\n",
              name.c_str(), n_ranks, talus_test::verdict(held), talus_test::verdict(same_work),
              talus_test::verdict(whole_cells), talus_test::verdict(tiles),
              talus_test::verdict(near_ok), p.imbalance(), largest_imbalance,
              talus_test::verdict(p.imbalance() <= largest_imbalance));
}

} // namespace

int main()
{
  const std::vector<unsigned int> ranks{2, 3, 4, 7, 16};
  {
    Scene scene =
        read_scene(std::string(SOURCE_DIR) + "/../../parameters/benched_slope.prm", false);
    BuildReport built;
    const BlockModel model = build_blocks(scene, built);
    Box domain{model.vertex[0], model.vertex[0]};
    for (const Vec3& v : model.vertex)
    {
      domain.lo = domain.lo.cwiseMin(v);
      domain.hi = domain.hi.cwiseMax(v);
    }
    CellSpace cells;
    cells.define(domain, model.n_blocks());
    // One unit of work per block. Coarse grain: a cell holds about one
    // block, so a slab of cells (what a cut moves) holds about a tenth of
    // the 238; the bound allows a quarter of a share more.
    const std::vector<double> work(model.n_blocks(), 1.0);
    for (unsigned int n : {2u, 3u, 4u, 7u})
      check_partition("benched slope", domain, cells.cell_size(), model.centroid, work, n, 1.25);
  }
  std::mt19937 random(2026);
  const Box box{Vec3(0, 0, 0), Vec3(100, 50, 20)};
  std::vector<Vec3> even(100000), crowded(100000);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (std::size_t i = 0; i < even.size(); ++i)
  {
    even[i] =
        box.lo + (box.hi - box.lo).cwiseProduct(Vec3(unit(random), unit(random), unit(random)));
    // Half-normal about the corner, 8 m x 4 m x 2 m spread, kept in the box.
    Vec3 x(std::abs(normal(random)) * 8.0, std::abs(normal(random)) * 4.0,
           std::abs(normal(random)) * 2.0);
    crowded[i] = x.cwiseMin(box.hi - Vec3::Constant(1e-6));
  }
  const std::vector<double> ones(even.size(), 1.0);
  for (unsigned int n : ranks)
    check_partition("even cloud", box, Vec3::Ones(), even, ones, n, 1.05);
  for (unsigned int n : ranks)
    check_partition("crowded cloud", box, Vec3::Ones(), crowded, ones, n, 1.25);
}
