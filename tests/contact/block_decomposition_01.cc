// The blocks each rank holds when a model is split among ranks
// (decompose_blocks): every block is owned by one rank; every contact of
// an owned block joins two blocks its rank holds (with two layers, every
// contact of the ghosts of the first layer too, so that a ghost that
// becomes owned has all its contacts); local blocks are in global order; what a rank
// sends each neighbour is what that neighbour receives from it.
//
// The 238 blocks of parameters/benched_slope.prm (slivers, blocks of very
// different sizes) and the tunnel of parameters/tunnel_in_jointed_rock.prm,
// on 2, 3, 4 and 7 ranks; contacts are those a contact set finds on the
// whole model at the scene's contact tolerance.

#include <talus/contact/block_decomposition.h>
#include <talus/contact/contact_set.h>
#include <talus/scene/build_blocks.h>
#include <talus/scene/scene.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "../tests.h"

using namespace talus;

namespace
{

void check_scene(const std::string& file)
{
  Scene scene = read_scene(std::string(SOURCE_DIR) + "/../../parameters/" + file, false);
  BuildReport built;
  const BlockModel model = build_blocks(scene, built);
  const ContactSettings& settings = scene.solver.contact;
  // Contacts of the whole model (every pair of boxes within the tolerance).
  ContactSet contacts;
  std::vector<Box> box(model.n_blocks());
  for (unsigned int b = 0; b < model.n_blocks(); ++b)
    box[b] = model.polyhedron(b).bounding_box();
  for (unsigned int a = 0; a < model.n_blocks(); ++a)
    for (unsigned int b = a + 1; b < model.n_blocks(); ++b)
      if (box[a].overlaps(box[b], settings.tolerance))
        contacts.try_create(a, b, model, settings);
  // Reach: the tolerance and as much again for motion.
  const double reach = 2.0 * settings.tolerance;
  Box domain = box[0];
  for (const Box& b : box)
  {
    domain.lo = domain.lo.cwiseMin(b.lo);
    domain.hi = domain.hi.cwiseMax(b.hi);
  }
  const std::vector<double> work(model.n_blocks(), 1.0);
  for (unsigned int n : {2u, 3u, 4u, 7u})
    for (unsigned int layers : {1u, 2u})
    {
      const CellPartition partition(domain, domain.lo, (domain.hi - domain.lo) / 16.0,
                                    model.centroid, work, n);
      std::vector<RankBlocks> rank, one_layer;
      for (unsigned int r = 0; r < n; ++r)
      {
        rank.push_back(decompose_blocks(model, partition, r, reach, layers));
        one_layer.push_back(decompose_blocks(model, partition, r, reach, 1));
      }
      // Owned once; local in global order.
      std::vector<int> owners(model.n_blocks(), 0);
      bool ordered = true;
      std::size_t held = 0;
      for (const RankBlocks& rb : rank)
      {
        ordered &= std::is_sorted(rb.local.begin(), rb.local.end()) &&
                   std::adjacent_find(rb.local.begin(), rb.local.end()) == rb.local.end();
        for (unsigned int i = 0; i < rb.local.size(); ++i)
          owners[rb.local[i]] += rb.owned[i];
        held += rb.local.size();
      }
      const bool once = std::all_of(owners.begin(), owners.end(), [](int k) { return k == 1; });
      // Contacts of owned blocks (and, with two layers, of ghosts) held.
      const auto holds = [](const RankBlocks& rb, unsigned int b, bool* owned = nullptr)
      {
        const auto at = std::lower_bound(rb.local.begin(), rb.local.end(), b);
        const bool in = at != rb.local.end() && *at == b;
        if (owned != nullptr)
          *owned = in && rb.owned[at - rb.local.begin()];
        return in;
      };
      unsigned int missing = 0, missing_ghost = 0;
      for (unsigned int c = 0; c < contacts.n_slots(); ++c)
      {
        if (!contacts.alive[c])
          continue;
        const unsigned int a = contacts.block_a[c], b = contacts.block_b[c];
        for (unsigned int r = 0; r < n; ++r)
        {
          bool owns_a = false, owns_b = false;
          const bool has_a = holds(rank[r], a, &owns_a), has_b = holds(rank[r], b, &owns_b);
          if ((owns_a && !has_b) || (owns_b && !has_a))
            ++missing;
          // A ghost of the first layer (a neighbour of an owned block).
          if ((holds(one_layer[r], a) && !has_b) || (holds(one_layer[r], b) && !has_a))
            ++missing_ghost;
        }
      }
      // Sends match receipts, in global numbers.
      bool matched = true;
      for (const RankBlocks& rb : rank)
        for (const auto& [other, list] : rb.send)
        {
          std::vector<unsigned int> sent, received;
          for (unsigned int i : list)
            sent.push_back(rb.local[i]);
          for (const auto& [from, got] : rank[other].receive)
            if (from == rb.rank)
              for (unsigned int i : got)
                received.push_back(rank[other].local[i]);
          matched &= sent == received && !sent.empty();
        }
      for (const RankBlocks& rb : rank)
        matched &= rb.receive.size() == rb.send.size();
      std::fprintf(stderr, "%s, %u ranks, %u layers: %zu blocks held for %u (%.2f each)\n",
                   file.c_str(), n, layers, held, model.n_blocks(),
                   double(held) / model.n_blocks());
      std::printf("%s, %u ranks, %u layer%s: owned once %s, global order %s, contacts of owned "
                  "blocks held %s",
                  file.c_str(), n, layers, layers > 1 ? "s" : "", talus_test::verdict(once),
                  talus_test::verdict(ordered), talus_test::verdict(missing == 0));
      if (layers > 1)
        std::printf(", contacts of ghosts held %s", talus_test::verdict(missing_ghost == 0));
      std::printf(", sends match receipts %s\n", talus_test::verdict(matched));
    }
}

} // namespace

int main()
{
  check_scene("benched_slope.prm");
  check_scene("tunnel_in_jointed_rock.prm");
}
