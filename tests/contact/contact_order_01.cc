// The sub-contacts of a contact set lie in the order of their block pairs,
// whatever the order in which the contacts were found and whichever slots
// they hold. A run split among ranks finds its contacts in another order
// than a serial run; with this order every block still sums its contact
// forces in the same sequence, so the two give the same bits.
//
// The blocks of parameters/benched_slope.prm (three joint sets: slivers,
// faces that share edges, blocks of very different sizes) are given
// contacts twice: once pair by pair in ascending order, once in descending
// order after the contacts of a few blocks were made and deleted, so that
// the contacts take other slots. After an update both sets must hold the same
// sub-contacts in the same order, bit for bit.

#include <talus/contact/contact_set.h>
#include <talus/scene/build_blocks.h>
#include <talus/scene/scene.h>

#include <cstdio>
#include <utility>
#include <vector>

#include "../tests.h"

using namespace talus;

namespace
{

/// The pairs of blocks whose boxes, grown by the tolerance, overlap.
std::vector<std::pair<unsigned int, unsigned int>> near_pairs(const BlockModel& m, double tol)
{
  std::vector<Box> box(m.n_blocks());
  for (unsigned int b = 0; b < m.n_blocks(); ++b)
    box[b] = m.polyhedron(b).bounding_box();
  std::vector<std::pair<unsigned int, unsigned int>> pairs;
  for (unsigned int a = 0; a < m.n_blocks(); ++a)
    for (unsigned int b = a + 1; b < m.n_blocks(); ++b)
      if (box[a].overlaps(box[b], tol))
        pairs.emplace_back(a, b);
  return pairs;
}

/// Whether two sets hold the same sub-contacts in the same order: the same
/// block pair, position, area and normal force at every index.
bool same_subcontacts(const ContactSet& x, const ContactSet& y, unsigned int& first_difference)
{
  first_difference = 0;
  if (x.n_subcontacts() != y.n_subcontacts())
    return false;
  for (unsigned int i = 0; i < x.n_subcontacts(); ++i)
  {
    first_difference = i;
    const unsigned int cx = x.sc_contact[i], cy = y.sc_contact[i];
    if (x.block_a[cx] != y.block_a[cy] || x.block_b[cx] != y.block_b[cy] ||
        x.sc_position[i] != y.sc_position[i] || x.sc_area[i] != y.sc_area[i] ||
        x.sc_un[i] != y.sc_un[i])
      return false;
  }
  return true;
}

} // namespace

int main()
{
  Scene scene = read_scene(std::string(SOURCE_DIR) + "/../../parameters/benched_slope.prm", false);
  BuildReport built;
  const BlockModel model = build_blocks(scene, built);
  const ContactSettings& settings = scene.solver.contact;
  const auto pairs = near_pairs(model, settings.tolerance);

  ContactSet ascending;
  for (const auto& [a, b] : pairs)
    ascending.try_create(a, b, model, settings);
  ascending.update(model, settings);

  // The other set first holds the contacts of every seventh block and
  // deletes them, so that the free list hands out its slots out of order;
  // then it finds every contact in descending order. Each contact of either
  // set is made once and updated once: the same geometric history.
  ContactSet scrambled;
  std::vector<char> gone(model.n_blocks(), 0);
  for (unsigned int b = 0; b < model.n_blocks(); b += 7)
    gone[b] = 1;
  for (const auto& [a, b] : pairs)
    if (gone[a] || gone[b])
      scrambled.try_create(a, b, model, settings);
  scrambled.remove_contacts_of(gone);
  for (auto p = pairs.rbegin(); p != pairs.rend(); ++p)
    scrambled.try_create(p->first, p->second, model, settings);
  scrambled.update(model, settings);

  unsigned int moved_slots = 0;
  for (unsigned int i = 0; i < ascending.n_subcontacts(); ++i)
    if (i < scrambled.n_subcontacts() && ascending.sc_contact[i] != scrambled.sc_contact[i])
      ++moved_slots;
  std::fprintf(stderr, "%u blocks, %u contacts, %u sub-contacts; %u held in other slots\n",
               model.n_blocks(), ascending.n_contacts(), ascending.n_subcontacts(), moved_slots);
  std::printf("the contacts were found in another order and hold other slots: %s\n",
              talus_test::verdict(ascending.n_contacts() > 100 && moved_slots > 0));
  unsigned int at = 0;
  const bool same = same_subcontacts(ascending, scrambled, at);
  if (!same)
    std::fprintf(stderr, "sub-contacts %u and %u; first difference at %u\n",
                 ascending.n_subcontacts(), scrambled.n_subcontacts(), at);
  std::printf("the same sub-contacts in the same order, bit for bit: %s\n",
              talus_test::verdict(same));
}
