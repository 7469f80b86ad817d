#include "block_arrays.h"

#include <talus/joint/continuously_yielding.h>
#include <talus/solver/deformable_solver.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>

namespace talus
{

using block_records::Bytes;
using block_records::Reader;

namespace
{

std::vector<char> all_gathered(const std::vector<char>& mine, MPI_Comm comm,
                               std::vector<int>& counts, std::vector<int>& starts)
{
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  if (mine.size() > static_cast<std::size_t>(std::numeric_limits<int>::max() / ranks))
    throw std::runtime_error("BlockMigration::gather_whole: a rank's share of the model is "
                             "larger than one MPI message allows");
  const int size = static_cast<int>(mine.size());
  counts.assign(ranks, 0);
  starts.assign(ranks, 0);
  MPI_Allgather(&size, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  for (int r = 1; r < ranks; ++r)
    starts[r] = starts[r - 1] + counts[r - 1];
  std::vector<char> all(static_cast<std::size_t>(starts.back()) + counts.back());
  if (MPI_Allgatherv(mine.data(), size, MPI_BYTE, all.data(), counts.data(), starts.data(),
                     MPI_BYTE, comm) != MPI_SUCCESS)
    throw std::runtime_error("BlockMigration::gather_whole: a message between ranks failed");
  return all;
}

} // namespace

void BlockMigration::gather_whole(const RigidSolver& split, const RankBlocks& blocks,
                                  RigidSolver& whole, MPI_Comm comm)
{
  // visit_block_arrays takes a solver it may change; here it only reads.
  RigidSolver& s = const_cast<RigidSolver&>(split);
  // With zones, a sub-contact's gridpoints travel by their numbers in the
  // whole mesh, which are the whole (one run's) solver's own numbers.
  const GridpointShare* gridpoints = s.zones_ != nullptr ? s.zones_->share() : nullptr;
  const bool nodes = s.zones_ != nullptr;
  if ((s.zones_ != nullptr) != (whole.zones_ != nullptr) || (nodes && gridpoints == nullptr))
    throw std::logic_error("BlockMigration::gather_whole: the solvers' zones do not match");
  const BlockModel& m = s.m_;
  BlockModel& wm = whole.m_;
  const unsigned int n_whole = wm.n_blocks();
  // The whole solver's per-block arrays as the split one has them (loads in
  // time only where a stage set them).
  if (!s.timed_force_.empty())
  {
    whole.timed_force_.resize(n_whole);
    whole.timed_velocity_.resize(n_whole);
    whole.timed_held_.resize(n_whole);
  }
  std::size_t record = 0, whole_record = 0;
  visit_block_arrays(s, [&](auto& a) { record += sizeof(a[0]); });
  visit_block_arrays(whole,
                     [&](auto& a)
                     {
                       a.resize(n_whole);
                       whole_record += sizeof(a[0]);
                     });
  if (record != whole_record)
    throw std::logic_error("BlockMigration::gather_whole: the solvers keep other block arrays");

  // Owned blocks: global number, geometry, solver arrays.
  Bytes out;
  std::vector<unsigned int> owned;
  for (unsigned int i = 0; i < blocks.local.size(); ++i)
    if (blocks.owned[i])
      owned.push_back(i);
  out.put(static_cast<unsigned int>(owned.size()));
  for (unsigned int i : owned)
  {
    out.put(blocks.local[i]);
    out.put(m.vertex_start[i + 1] - m.vertex_start[i]);
    out.put(m.face_start[i + 1] - m.face_start[i]);
    for (unsigned int v = m.vertex_start[i]; v < m.vertex_start[i + 1]; ++v)
      out.put(m.vertex[v]);
    for (unsigned int f = m.face_start[i]; f < m.face_start[i + 1]; ++f)
      out.put(m.face_normal[f]);
    out.put(m.centroid[i]);
    out.put(m.volume[i]);
    out.put(m.inertia[i]);
    visit_block_arrays(s, [&](auto& a) { out.put(a[i]); });
  }
  // Contacts whose first block this rank owns (each contact on one rank),
  // with their sub-contacts, which are contiguous (block-pair order).
  const ContactSet& cs = s.contacts_;
  std::vector<unsigned int> sc_begin, sc_end;
  cs.subcontact_ranges(cs.n_slots(), sc_begin, sc_end);
  // (as the settings say, alike on every rank: a rank may have no sub-contacts)
  const bool dilation = s.s_.contact.dilation, yielding = s.s_.contact.yielding;
  unsigned int n_contacts = 0;
  for (unsigned int c = 0; c < cs.n_slots(); ++c)
    n_contacts += cs.alive[c] && blocks.owned[cs.block_a[c]];
  out.put(n_contacts);
  for (unsigned int c = 0; c < cs.n_slots(); ++c)
  {
    if (!cs.alive[c] || !blocks.owned[cs.block_a[c]])
      continue;
    block_records::put_contact(out, cs, c, blocks.local[cs.block_a[c]], blocks.local[cs.block_b[c]],
                               sc_begin[c], sc_end[c], dilation, yielding,
                               [&](Bytes& to, unsigned int k)
                               {
                                 if (nodes)
                                   block_records::put_subcontact_nodes(to, cs, k, *gridpoints);
                               });
  }

  std::vector<int> counts, starts;
  const std::vector<char> all = all_gathered(out.data, comm, counts, starts);

  // Every block into the whole model and solver; the contacts' records.
  std::vector<char> seen(n_whole, 0);
  std::vector<std::pair<std::uint64_t, const char*>> contacts;
  for (std::size_t r = 0; r < counts.size(); ++r)
  {
    Reader in{all.data() + starts[r]};
    const unsigned int n = in.get<unsigned int>();
    for (unsigned int k = 0; k < n; ++k)
    {
      const unsigned int g = in.get<unsigned int>();
      const unsigned int nv = in.get<unsigned int>(), nf = in.get<unsigned int>();
      if (g >= n_whole || seen[g] || nv != wm.vertex_start[g + 1] - wm.vertex_start[g] ||
          nf != wm.face_start[g + 1] - wm.face_start[g])
        throw std::logic_error("BlockMigration::gather_whole: a block not of the whole model, "
                               "or owned twice");
      seen[g] = 1;
      for (unsigned int v = wm.vertex_start[g]; v < wm.vertex_start[g + 1]; ++v)
        wm.vertex[v] = in.get<Vec3>();
      for (unsigned int f = wm.face_start[g]; f < wm.face_start[g + 1]; ++f)
        wm.face_normal[f] = in.get<Vec3>();
      wm.centroid[g] = in.get<Vec3>();
      wm.volume[g] = in.get<double>();
      wm.inertia[g] = in.get<std::decay_t<decltype(wm.inertia[g])>>();
      visit_block_arrays(whole,
                         [&](auto& a)
                         {
                           using T = typename std::decay_t<decltype(a)>::value_type;
                           std::memcpy(static_cast<void*>(&a[g]), in.at, sizeof(T));
                           in.at += sizeof(T);
                         });
    }
    const unsigned int nc = in.get<unsigned int>();
    for (unsigned int k = 0; k < nc; ++k)
    {
      const char* start = in.at;
      const unsigned int a = in.get<unsigned int>(), b = in.get<unsigned int>();
      in.at += block_records::contact_head_size - sizeof(unsigned int);
      const unsigned int n_sc = in.get<unsigned int>();
      in.at += n_sc * block_records::subcontact_size(dilation, yielding, nodes);
      contacts.emplace_back((static_cast<std::uint64_t>(a) << 32) | b, start);
    }
  }
  if (std::count(seen.begin(), seen.end(), 1) != static_cast<long>(n_whole))
    throw std::logic_error("BlockMigration::gather_whole: a block of the model has no owner");

  // The contacts in block-pair order, slots in that order (as a migration
  // lays them out), each contact's sub-contacts after its predecessor's.
  std::sort(contacts.begin(), contacts.end());
  ContactSet laid;
  for (const auto& [key, record_at] : contacts)
  {
    const unsigned int c = laid.append_slot(key);
    Reader in{record_at + 2 * sizeof(unsigned int)};
    block_records::get_contact(in, laid, c, dilation, yielding,
                               [&](Reader& from)
                               {
                                 if (!nodes)
                                   return;
                                 for (int n = 0; n < 6; ++n)
                                 {
                                   laid.sc_node.push_back(from.get<int>());
                                   laid.sc_weight.push_back(from.get<double>());
                                 }
                               });
  }
  laid.is_deformable_ = whole.contacts_.is_deformable_;
  laid.vertex_gridpoint_ = whole.contacts_.vertex_gridpoint_;
  whole.contacts_ = std::move(laid);

  // What the split solver holds of the whole model already (reduced every
  // step, the same on every rank), and what the stages set that its state
  // keeps (as RigidSolver::save_state has it).
  whole.s_.dynamic = s.s_.dynamic;
  whole.s_.joint_rule = s.s_.joint_rule;
  if (!whole.s_.joint_rule.trivial())
    whole.s_.contact.materials = &whole.s_.joint_rule;
  whole.damper_ = s.damper_;
  whole.dt_ = s.dt_;
  whole.dt_without_stiffness_damping_ = s.dt_without_stiffness_damping_;
  whole.time_ = s.time_;
  whole.ratio_ = s.ratio_;
  whole.gravity_work_ = s.gravity_work_;
  whole.friction_work_ = s.friction_work_;
  whole.damping_work_ = s.damping_work_;
  whole.boundary_work_ = s.boundary_work_;
  whole.kinetic_whole_step_ = s.kinetic_whole_step_;
  whole.initial_stored_ = s.initial_stored_;
  whole.energy_floor_ = s.energy_floor_;
  whole.growth_watch_ = s.growth_watch_;
  whole.step_ = s.step_;
  whole.last_output_ = s.last_output_;
  int moved = s.moved_beyond_tolerance_ ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &moved, 1, MPI_INT, MPI_LOR, comm);
  whole.moved_beyond_tolerance_ = moved != 0;
}

} // namespace talus
