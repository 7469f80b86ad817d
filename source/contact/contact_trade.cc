// The contacts of a rank's share of a model split among ranks (issue 24):
// none between two ghosts, and each contact across ranks found, updated
// and laid out once by ContactSet::update, by one of its two ranks
// (RankBlocks::computes_contact), and taken by the other.

#include <talus/contact/block_decomposition.h>
#include <talus/contact/contact_set.h>
#include <talus/joint/continuously_yielding.h>

#include <algorithm>
#include <stdexcept>

namespace talus
{

void ContactSet::drop_contacts_among(const std::vector<char>& among)
{
  bool any = false;
  for (unsigned int c = 0; c < n_slots(); ++c)
    if (alive[c] && among[block_a[c]] && among[block_b[c]])
    {
      remove(c);
      any = true;
    }
  if (!any)
    return;
  // Sub-contacts of the contacts left, moved down in place.
  const bool nodes = !sc_node.empty(), dilated = !sc_dilation.empty(), yielded = !sc_yield.empty();
  unsigned int kept = 0;
  for (unsigned int i = 0; i < n_subcontacts(); ++i)
  {
    if (!alive[sc_contact[i]])
      continue;
    const unsigned int k = kept++;
    sc_contact[k] = sc_contact[i];
    sc_position[k] = sc_position[i];
    sc_area[k] = sc_area[i];
    sc_un[k] = sc_un[i];
    sc_fn[k] = sc_fn[i];
    for (int d = 0; d < 3; ++d)
    {
      sc_fs[3 * k + d] = sc_fs[3 * i + d];
      sc_us[3 * k + d] = sc_us[3 * i + d];
    }
    if (dilated)
      sc_dilation[k] = sc_dilation[i];
    if (yielded)
      for (unsigned int y = 0; y < yield_state_size; ++y)
        sc_yield[yield_state_size * k + y] = sc_yield[yield_state_size * i + y];
    sc_state[k] = sc_state[i];
    sc_material[k] = sc_material[i];
    sc_fresh[k] = sc_fresh[i];
    if (nodes)
      for (int n = 0; n < 6; ++n)
      {
        sc_node[6 * k + n] = sc_node[6 * i + n];
        sc_weight[6 * k + n] = sc_weight[6 * i + n];
      }
  }
  sc_contact.resize(kept);
  sc_position.resize(kept);
  sc_area.resize(kept);
  sc_un.resize(kept);
  sc_fn.resize(kept);
  sc_fs.resize(3 * kept);
  sc_us.resize(3 * kept);
  if (dilated)
    sc_dilation.resize(kept);
  if (yielded)
    sc_yield.resize(yield_state_size * kept);
  sc_state.resize(kept);
  sc_material.resize(kept);
  sc_fresh.resize(kept);
  if (nodes)
  {
    sc_node.resize(6 * kept);
    sc_weight.resize(6 * kept);
  }
}

void ContactSet::subcontact_ranges(unsigned int n, std::vector<unsigned int>& begin,
                                   std::vector<unsigned int>& end) const
{
  begin.assign(n, 0);
  end.assign(n, 0);
  for (unsigned int k = 0; k < n_subcontacts(); ++k)
  {
    const unsigned int c = sc_contact[k];
    if (end[c] == 0)
      begin[c] = k;
    end[c] = k + 1;
  }
}

void ContactSet::append_subcontacts(const ContactSet& from, unsigned int begin, unsigned int end,
                                    unsigned int c)
{
  const bool dilation = !from.sc_dilation.empty(), yielding = !from.sc_yield.empty(),
             nodes = !from.sc_node.empty();
  for (unsigned int k = begin; k < end; ++k)
  {
    sc_contact.push_back(c);
    sc_position.push_back(from.sc_position[k]);
    sc_area.push_back(from.sc_area[k]);
    sc_un.push_back(from.sc_un[k]);
    sc_fn.push_back(from.sc_fn[k]);
    sc_fs.insert(sc_fs.end(), &from.sc_fs[3 * k], &from.sc_fs[3 * k] + 3);
    sc_us.insert(sc_us.end(), &from.sc_us[3 * k], &from.sc_us[3 * k] + 3);
    if (dilation)
      sc_dilation.push_back(from.sc_dilation[k]);
    if (yielding)
      sc_yield.insert(sc_yield.end(), &from.sc_yield[yield_state_size * k],
                      &from.sc_yield[yield_state_size * k] + yield_state_size);
    sc_state.push_back(from.sc_state[k]);
    sc_material.push_back(from.sc_material[k]);
    sc_fresh.push_back(from.sc_fresh[k]);
    if (nodes)
    {
      sc_node.insert(sc_node.end(), &from.sc_node[6 * k], &from.sc_node[6 * k] + 6);
      sc_weight.insert(sc_weight.end(), &from.sc_weight[6 * k], &from.sc_weight[6 * k] + 6);
    }
  }
}

void ContactSet::update_across_ranks(const BlockModel& m, const ContactSettings& settings,
                                     const CommonPlaneSettings& cps,
                                     const std::vector<double>* path, ContactTrade& trade)
{
  const RankBlocks& blocks = trade.blocks();
  if (blocks.owned.size() != m.n_blocks())
    throw std::logic_error("ContactSet: the trade's blocks are not those of the model");
  // Per live contact: 0 computed here alone, 1 computed here for another
  // rank too, 2 computed by another rank.
  const auto kind = [&](unsigned int c)
  {
    const unsigned int a = block_a[c], b = block_b[c];
    if (!blocks.computes_contact(a, b))
      return 2;
    return blocks.owned[a] && blocks.owned[b] ? 0 : 1;
  };

  // 1. The contacts this rank computes for another first, and sent at
  // once: the other rank then waits for these alone.
  std::vector<unsigned int> sent, sent_begin, sent_end;
  for (const unsigned int c : pair_order_)
  {
    if (!alive[c] || kind(c) != 1)
      continue;
    const unsigned int first = n_subcontacts();
    update_contact(c, m, settings, cps, path);
    if (!alive[c])
      continue;
    sent.push_back(c);
    sent_begin.push_back(first);
    sent_end.push_back(n_subcontacts());
  }
  trade.send(*this, sent, sent_begin, sent_end);
  // Their sub-contacts aside until they are laid out in pair order below
  // (the arrays here keep their memory).
  ContactSet computed;
  for (std::size_t i = 0; i < sent.size(); ++i)
    computed.append_subcontacts(*this, sent_begin[i], sent_end[i], sent[i]);
  clear_subcontacts();

  // 2. Those another rank computes, as it sent them: a contact it no
  // longer has goes, one it made comes (new slots, merged into the pair
  // order), the others take its plane and state.
  ContactSet taken;
  trade.receive(taken);
  std::vector<unsigned int> made;                                // new slots, in pair order
  std::vector<std::pair<unsigned int, unsigned int>> from_taken; // slot, taken's slot
  const auto take = [&](unsigned int c, unsigned int t)
  {
    plane[c] = taken.plane[t];
    gap[c] = taken.gap[t];
    type[c] = taken.type[t];
    material[c] = taken.material[t];
    path_at_update[c] = taken.path_at_update[t];
    from_taken.emplace_back(c, t);
  };
  const auto make = [&](unsigned int t)
  {
    // Appended, not from the free list: a slot freed in this walk is still
    // in the pair order, dead.
    if (slot_of_pair_.count(pair_key(taken.block_a[t], taken.block_b[t])))
      throw std::logic_error("ContactSet: a contact taken from another rank is one this rank "
                             "computes");
    const unsigned int c = n_slots();
    block_a.push_back(taken.block_a[t]);
    block_b.push_back(taken.block_b[t]);
    plane.push_back(taken.plane[t]);
    gap.push_back(0.0);
    type.push_back(taken.type[t]);
    alive.push_back(1);
    material.push_back(0);
    path_at_update.push_back(-1.0);
    slot_of_pair_[pair_key(taken.block_a[t], taken.block_b[t])] = c;
    ++n_alive_;
    take(c, t);
    made.push_back(c);
  };
  unsigned int t = 0;
  const auto taken_key = [&](unsigned int k)
  { return pair_key(taken.block_a[k], taken.block_b[k]); };
  for (const unsigned int c : pair_order_)
  {
    if (!alive[c] || kind(c) != 2)
      continue;
    const std::uint64_t key = pair_key(block_a[c], block_b[c]);
    for (; t < taken.n_slots() && taken_key(t) < key; ++t)
      make(t);
    if (t < taken.n_slots() && taken_key(t) == key)
      take(c, t++);
    else
      remove(c);
  }
  for (; t < taken.n_slots(); ++t)
    make(t);
  if (!made.empty())
  {
    // The new slots merged into the pair order (both sorted).
    std::vector<unsigned int> merged;
    merged.reserve(pair_order_.size() + made.size());
    std::size_t k = 0;
    for (const unsigned int c : pair_order_)
    {
      if (!alive[c])
        continue;
      const std::uint64_t key = pair_key(block_a[c], block_b[c]);
      for (; k < made.size() && pair_key(block_a[made[k]], block_b[made[k]]) < key; ++k)
        merged.push_back(made[k]);
      merged.push_back(c);
    }
    merged.insert(merged.end(), made.begin() + long(k), made.end());
    pair_order_.swap(merged);
  }

  // 3. Everything in pair order: the contacts computed for another rank and
  // those taken as they are, the rest updated here.
  std::vector<int> taken_of(n_slots(), -1);
  for (const auto& [c, k] : from_taken)
    taken_of[c] = static_cast<int>(k);
  std::vector<unsigned int> computed_begin, computed_end, taken_begin, taken_end;
  computed.subcontact_ranges(n_slots(), computed_begin, computed_end);
  taken.subcontact_ranges(taken.n_slots(), taken_begin, taken_end);
  for (const unsigned int c : pair_order_)
  {
    if (!alive[c])
      continue;
    const int k = kind(c);
    if (k == 2)
      append_subcontacts(taken, taken_begin[taken_of[c]], taken_end[taken_of[c]], c);
    else if (k == 1)
      append_subcontacts(computed, computed_begin[c], computed_end[c], c);
    else
      update_contact(c, m, settings, cps, path);
  }
}

} // namespace talus
