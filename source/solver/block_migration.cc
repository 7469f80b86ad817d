#include "block_arrays.h"

#include <talus/base/exceptions.h>
#include <talus/base/gather.h>
#include <talus/joint/continuously_yielding.h>
#include <talus/solver/block_migration.h>
#include <talus/solver/deformable_solver.h>
#include <talus/solver/rigid_solver.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <stdexcept>
#include <type_traits>
#include <unordered_map>
#include <unordered_set>

namespace talus
{

namespace
{

using block_records::Bytes;
using block_records::Reader;

/// The position of global block g in the ascending `local`, or -1.
int local_of(const std::vector<unsigned int>& local, unsigned int g)
{
  const auto it = std::lower_bound(local.begin(), local.end(), g);
  return it != local.end() && *it == g ? static_cast<int>(it - local.begin()) : -1;
}

/// Appends block b of `from` to `to`, every value bit for bit (as
/// BlockModel::subset).
void append_block(BlockModel& to, const BlockModel& from, unsigned int b)
{
  const unsigned int v0 = from.vertex_start[b], first = to.n_vertices();
  to.vertex.insert(to.vertex.end(), from.vertex.begin() + v0,
                   from.vertex.begin() + from.vertex_start[b + 1]);
  to.vertex_start.push_back(to.n_vertices());
  for (unsigned int f = from.face_start[b]; f < from.face_start[b + 1]; ++f)
  {
    for (unsigned int k = from.face_loop_start[f]; k < from.face_loop_start[f + 1]; ++k)
      to.face_vertex.push_back(from.face_vertex[k] - v0 + first);
    to.face_loop_start.push_back(static_cast<unsigned int>(to.face_vertex.size()));
    to.face_normal.push_back(from.face_normal[f]);
    to.face_origin.push_back(from.face_origin[f]);
    if (!from.face_corner_share.empty())
      to.face_corner_share.push_back(from.face_corner_share[f]);
  }
  to.face_start.push_back(to.n_faces());
  to.volume.push_back(from.volume[b]);
  to.centroid.push_back(from.centroid[b]);
  to.inertia.push_back(from.inertia[b]);
  to.group.push_back(from.group[b]);
}

void put_geometry(Bytes& out, const BlockModel& m, unsigned int b)
{
  const unsigned int v0 = m.vertex_start[b];
  out.put<unsigned int>(m.vertex_start[b + 1] - v0);
  out.put<unsigned int>(m.face_start[b + 1] - m.face_start[b]);
  out.put<char>(!m.face_corner_share.empty());
  for (unsigned int v = v0; v < m.vertex_start[b + 1]; ++v)
    out.put(m.vertex[v]);
  for (unsigned int f = m.face_start[b]; f < m.face_start[b + 1]; ++f)
  {
    out.put<unsigned int>(m.face_loop_start[f + 1] - m.face_loop_start[f]);
    for (unsigned int k = m.face_loop_start[f]; k < m.face_loop_start[f + 1]; ++k)
      out.put<unsigned int>(m.face_vertex[k] - v0);
    out.put(m.face_normal[f]);
    out.put(m.face_origin[f]);
    if (!m.face_corner_share.empty())
      out.put(m.face_corner_share[f]);
  }
  out.put(m.volume[b]);
  out.put(m.centroid[b]);
  out.put(m.inertia[b]);
  out.put(m.group[b]);
}

/// Reads put_geometry's block as the one block of `m`.
void get_geometry(Reader& in, BlockModel& m)
{
  const unsigned int nv = in.get<unsigned int>(), nf = in.get<unsigned int>();
  const bool shares = in.get<char>() != 0;
  for (unsigned int v = 0; v < nv; ++v)
    m.vertex.push_back(in.get<Vec3>());
  m.vertex_start.push_back(nv);
  for (unsigned int f = 0; f < nf; ++f)
  {
    const unsigned int loop = in.get<unsigned int>();
    for (unsigned int k = 0; k < loop; ++k)
      m.face_vertex.push_back(in.get<unsigned int>());
    m.face_loop_start.push_back(static_cast<unsigned int>(m.face_vertex.size()));
    m.face_normal.push_back(in.get<Vec3>());
    m.face_origin.push_back(in.get<int>());
    if (shares)
      m.face_corner_share.push_back(in.get<std::array<double, 3>>());
  }
  m.face_start.push_back(nf);
  m.volume.push_back(in.get<double>());
  m.centroid.push_back(in.get<Vec3>());
  m.inertia.push_back(in.get<std::array<double, 6>>());
  m.group.push_back(in.get<unsigned int>());
}

} // namespace

std::vector<std::vector<char>> block_records::trade(const std::vector<std::vector<char>>& out,
                                                    MPI_Comm comm, int tag)
{
  const int ranks = static_cast<int>(out.size());
  std::vector<int> send_count(ranks), receive_count(ranks);
  for (int r = 0; r < ranks; ++r)
    send_count[r] = static_cast<int>(out[r].size());
  MPI_Alltoall(send_count.data(), 1, MPI_INT, receive_count.data(), 1, MPI_INT, comm);
  std::vector<std::vector<char>> in(ranks);
  std::vector<MPI_Request> requests;
  for (int r = 0; r < ranks; ++r)
    if (receive_count[r] > 0)
    {
      in[r].resize(receive_count[r]);
      requests.emplace_back();
      MPI_Irecv(in[r].data(), receive_count[r], MPI_BYTE, r, tag, comm, &requests.back());
    }
  for (int r = 0; r < ranks; ++r)
    if (send_count[r] > 0)
    {
      requests.emplace_back();
      MPI_Isend(out[r].data(), send_count[r], MPI_BYTE, r, tag, comm, &requests.back());
    }
  if (MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE) !=
      MPI_SUCCESS)
    throw std::runtime_error("BlockMigration: a message between ranks failed");
  return in;
}

BlockMigration::BlockMigration(const RigidSolver& solver, const RankBlocks& blocks,
                               const CellPartition& partition, double reach, unsigned int layers,
                               MPI_Comm comm)
    : partition_(partition), reach_(reach), layers_(layers), comm_(comm),
      allowance_(0.5 * (reach - 2.0 * solver.s_.contact.tolerance)), path_at_choice_(solver.path)
{
  if (!(allowance_ > 0.0))
    throw std::invalid_argument("BlockMigration: the reach must exceed twice the contact "
                                "tolerance (the rest is the motion allowed between choices)");
  if (blocks.local.size() != solver.path.size())
    throw std::invalid_argument("BlockMigration: the solver does not hold these blocks");
}

bool BlockMigration::due(const RigidSolver& solver, const RankBlocks& blocks) const
{
  bool mine = false;
  for (std::size_t i = 0; i < blocks.local.size() && !mine; ++i)
    if (blocks.owned[i] && !solver.removed_[i])
      mine = solver.path[i] - path_at_choice_[i] > allowance_ ||
             // (without rebuild_ a deformable block stays with its first owner)
             ((!solver.is_deformable_[i] || rebuild_) &&
              partition_.owner(solver.m_.centroid[i]) != blocks.rank);
  if (solver.ranks_.any)
    return solver.ranks_.any(mine);
  int in = mine, out = 0; // a solver not split_among_ranks: decided here all the same
  MPI_Allreduce(&in, &out, 1, MPI_INT, MPI_LOR, comm_);
  return out != 0;
}

bool BlockMigration::update(RigidSolver& solver, RankBlocks& blocks)
{
  if (!due(solver, blocks))
    return false;
  migrate(solver, blocks);
  solver.localize_loads(blocks.local); // face loads and water on the blocks owned now
  return true;
}

bool BlockMigration::migrate_to_new_regions(RigidSolver& solver, RankBlocks& blocks)
{
  if (!migrate(solver, blocks, true))
    return false;
  solver.localize_loads(blocks.local);
  return true;
}

bool BlockMigration::migrate(RigidSolver& s, RankBlocks& blocks, bool may_refuse)
{
  // Face loads move as a table of the whole model (set_face_load_table),
  // water with the flags that choose its blocks; update() places both again.
  if (!s.face_loads_.empty() && !s.has_face_load_table_)
    throw std::logic_error("BlockMigration: face loads without their table "
                           "(RigidSolver::set_face_load_table) do not move between ranks");
  int rank = 0, n_ranks = 1;
  MPI_Comm_rank(comm_, &rank);
  MPI_Comm_size(comm_, &n_ranks);
  BlockModel& m = s.m_;
  ContactSet& cs = s.contacts_;
  const std::vector<unsigned int>& old_local = blocks.local;
  const unsigned int n_old = static_cast<unsigned int>(old_local.size());

  // 1. Each owned block's box and centroid to the ranks whose regions come
  // within `span` of its box, point to point. A block whose centroid lies
  // in a region has its box there; one within `layers` steps of it (a step:
  // boxes within the reach) lies within layers (reach + s) of the region, s
  // the longest side of any block's box; so does every block on a chain of
  // `layers` steps from a block of this rank to one of another's, which
  // decides what this rank sends that one. Every rank then chooses its
  // blocks and lists as it would from the whole model. (s: the boxes as
  // they are now; one step more of margin.)
  double largest = 0.0;
  std::vector<Box> own_box(n_old);
  for (unsigned int i = 0; i < n_old; ++i)
    if (blocks.owned[i] && !s.removed_[i])
    {
      Box e{m.vertex[m.vertex_start[i]], m.vertex[m.vertex_start[i]]};
      for (unsigned int v = m.vertex_start[i]; v < m.vertex_start[i + 1]; ++v)
      {
        e.lo = e.lo.cwiseMin(m.vertex[v]);
        e.hi = e.hi.cwiseMax(m.vertex[v]);
      }
      own_box[i] = e;
      largest = std::max(largest, (e.hi - e.lo).maxCoeff());
    }
  MPI_Allreduce(MPI_IN_PLACE, &largest, 1, MPI_DOUBLE, MPI_MAX, comm_);
  const double span = (layers_ + 1) * (reach_ + largest);
  // A deformable block stays with its first owner (below) wherever it
  // goes: the owners of those that have left their regions must hear of
  // the blocks near them too. Their boxes, from every rank to every rank
  // (few: most deformable blocks barely move).
  std::vector<double> strays; // owner, lo, hi
  for (unsigned int i = 0; i < n_old; ++i)
    if (blocks.owned[i] && !s.removed_[i] && s.is_deformable_[i] && !rebuild_ &&
        partition_.owner(m.centroid[i]) != blocks.rank)
    {
      strays.push_back(rank);
      strays.insert(strays.end(), own_box[i].lo.data(), own_box[i].lo.data() + 3);
      strays.insert(strays.end(), own_box[i].hi.data(), own_box[i].hi.data() + 3);
    }
  strays = gathered_on_every_rank(strays, comm_);
  std::vector<std::vector<char>> boxes_out(n_ranks);
  std::vector<unsigned int> near;
  for (unsigned int i = 0; i < n_old; ++i)
    if (blocks.owned[i] && !s.removed_[i]) // a removed block is held nowhere from now on
    {
      partition_.ranks_near(own_box[i], span, near);
      for (std::size_t k = 0; k < strays.size(); k += 7)
      {
        const Vec3 lo(strays[k + 1], strays[k + 2], strays[k + 3]),
            hi(strays[k + 4], strays[k + 5], strays[k + 6]);
        if ((own_box[i].lo.array() - span <= hi.array()).all() &&
            (lo.array() <= own_box[i].hi.array() + span).all())
          near.push_back(static_cast<unsigned int>(strays[k]));
      }
      std::sort(near.begin(), near.end());
      near.erase(std::unique(near.begin(), near.end()), near.end());
      Bytes record;
      record.put(old_local[i]);
      record.put(own_box[i].lo);
      record.put(own_box[i].hi);
      record.put(m.centroid[i]);
      record.put(s.is_deformable_[i]);
      for (unsigned int q : near)
        boxes_out[q].insert(boxes_out[q].end(), record.data.begin(), record.data.end());
    }
  const std::vector<std::vector<char>> boxes_in = block_records::trade(boxes_out, comm_, 2411);
  // The blocks this rank knows of, by global number: box, old and new owner.
  struct Known
  {
    unsigned int block, old_owner, owner;
    Box box;
    char deformable;
  };
  std::vector<Known> known;
  for (int r = 0; r < n_ranks; ++r)
  {
    Reader in{boxes_in[r].data()};
    while (in.at != boxes_in[r].data() + boxes_in[r].size())
    {
      Known k;
      k.block = in.get<unsigned int>();
      k.old_owner = static_cast<unsigned int>(r);
      k.box.lo = in.get<Vec3>();
      k.box.hi = in.get<Vec3>();
      k.owner = partition_.owner(in.get<Vec3>());
      // Without rebuild_ a deformable block stays with its first owner,
      // which holds its zones.
      k.deformable = in.get<char>();
      if (k.deformable && !rebuild_)
        k.owner = k.old_owner;
      known.push_back(k);
    }
  }
  std::sort(known.begin(), known.end(),
            [](const Known& a, const Known& b) { return a.block < b.block; });
  std::vector<Box> box(known.size());
  std::vector<unsigned int> owner(known.size());
  long taken_over = 0; // blocks this rank owns now that another owned
  for (std::size_t k = 0; k < known.size(); ++k)
  {
    box[k] = known[k].box;
    owner[k] = known[k].owner;
    taken_over += known[k].owner == static_cast<unsigned int>(rank) &&
                  known[k].old_owner != static_cast<unsigned int>(rank);
  }
  MPI_Allreduce(MPI_IN_PLACE, &taken_over, 1, MPI_LONG, MPI_SUM, comm_);
  // Chosen among the known blocks, then numbered globally again (the
  // lists hold positions in `local`, which stay).
  RankBlocks next = decompose_blocks(box, owner, static_cast<unsigned int>(rank), reach_, layers_);
  std::vector<unsigned int> old_owner(next.local.size());
  for (std::size_t j = 0; j < next.local.size(); ++j)
  {
    old_owner[j] = known[next.local[j]].old_owner;
    next.local[j] = known[next.local[j]].block;
  }
  const unsigned int n_new = static_cast<unsigned int>(next.local.size());
  const auto is_deformable_known = [&](unsigned int block)
  {
    const auto it = std::lower_bound(known.begin(), known.end(), block,
                                     [](const Known& k, unsigned int b) { return k.block < b; });
    return it != known.end() && it->block == block && it->deformable;
  };
  bool zones_move = false; // the zones split again (rebuild_)
  {
    // A rank holds the surface gridpoints of the deformable blocks near
    // its own when the zones were last split (build_block_system_on_ranks,
    // rebuild_): any of those can become a ghost here, others cannot
    // without a new split (decided alike on every rank, so that all stop
    // or split together).
    long first_new = -1;
    for (unsigned int j = 0; j < n_new && first_new < 0; ++j)
      if (is_deformable_known(next.local[j]) && local_of(old_local, next.local[j]) < 0 &&
          s.held_surfaces_.count(next.local[j]) == 0)
        first_new = next.local[j];
    long any = first_new;
    MPI_Allreduce(&first_new, &any, 1, MPI_LONG, MPI_MAX, comm_);
    if (rebuild_)
    {
      int moved = any >= 0;
      for (const Known& k : known)
        moved |= k.deformable && k.owner != k.old_owner;
      MPI_Allreduce(MPI_IN_PLACE, &moved, 1, MPI_INT, MPI_LOR, comm_);
      zones_move = moved != 0;
      any = -1;
    }
    if (any >= 0 && may_refuse)
      return false;
    if (any >= 0)
      throw InputError(
          "on " + std::to_string(n_ranks) + " MPI ranks: deformable block " + std::to_string(any) +
          " came within reach of blocks of a rank that does not hold its surface (at step " +
          std::to_string(s.steps_done()) +
          "): a rank holds the surfaces of the deformable blocks within two block sizes of its "
          "own when the run begins, and no others yet. Allowed: run this scene without mpirun, "
          "or on fewer ranks");
  }

  owner_changes_ += static_cast<unsigned long>(taken_over);

  // 2. Requests: the blocks this rank newly holds, to their old owners.
  std::vector<int> old_of(n_new); // per new local block: its old local index, or -1
  std::vector<std::vector<char>> request(n_ranks);
  for (unsigned int j = 0; j < n_new; ++j)
  {
    old_of[j] = local_of(old_local, next.local[j]);
    // A ghost that becomes owned comes whole from its old owner, which
    // holds every contact it has (here its contacts with other ghosts were
    // never made).
    if (old_of[j] >= 0 && next.owned[j] && !blocks.owned[old_of[j]])
      old_of[j] = -1;
    if (old_of[j] < 0)
    {
      Bytes b;
      b.put(next.local[j]);
      auto& to = request[old_owner[j]];
      to.insert(to.end(), b.data.begin(), b.data.end());
      ++received_;
    }
  }
  std::vector<int> new_of(n_old, -1); // per old local block: its new local index, or -1
  for (unsigned int j = 0; j < n_new; ++j)
    if (old_of[j] >= 0)
      new_of[old_of[j]] = static_cast<int>(j);
  for (unsigned int i = 0; i < n_old; ++i)
    dropped_ += new_of[i] < 0;
  const std::vector<std::vector<char>> asked = block_records::trade(request, comm_, 2412);

  // 3. Replies: each block asked for with its geometry, its state in the
  // solver and every contact it has (an owned block has all of its own).
  // The sub-contacts of a contact are contiguous (ContactSet's pair order).
  std::vector<unsigned int> sc_begin, sc_end;
  cs.subcontact_ranges(cs.n_slots(), sc_begin, sc_end);
  std::vector<std::vector<unsigned int>> contacts_of(n_old);
  for (unsigned int c = 0; c < cs.n_slots(); ++c)
    if (cs.alive[c])
    {
      contacts_of[cs.block_a[c]].push_back(c);
      contacts_of[cs.block_b[c]].push_back(c);
    }
  const bool dilation = s.s_.contact.dilation, yielding = s.s_.contact.yielding;
  // With zones, each sub-contact's gridpoints (sc_node) travel by their
  // numbers in the whole mesh, local numbers being each rank's own.
  const GridpointShare* gridpoints = s.zones_ != nullptr ? s.zones_->share() : nullptr;
  const bool nodes = gridpoints != nullptr;
  if (s.zones_ != nullptr && !nodes)
    throw std::logic_error("BlockMigration: zones not split among the ranks");
  std::unordered_map<unsigned int, int> local_gridpoint;
  if (nodes)
    for (std::size_t i = 0; i < gridpoints->whole_gridpoint.size(); ++i)
      local_gridpoint[gridpoints->whole_gridpoint[i]] = static_cast<int>(i);
  // A contact with its sub-contacts, blocks by global number.
  const auto put_contact = [&](Bytes& out, unsigned int c)
  {
    block_records::put_contact(out, cs, c, old_local[cs.block_a[c]], old_local[cs.block_b[c]],
                               sc_begin[c], sc_end[c], dilation, yielding,
                               [&](Bytes& to, unsigned int k)
                               {
                                 if (nodes)
                                   block_records::put_subcontact_nodes(to, cs, k, *gridpoints);
                               });
  };
  std::vector<std::vector<char>> reply(n_ranks);
  for (int r = 0; r < n_ranks; ++r)
  {
    Bytes out;
    Reader in{asked[r].data()};
    for (std::size_t k = 0; k < asked[r].size() / sizeof(unsigned int); ++k)
    {
      const unsigned int g = in.get<unsigned int>();
      const int i = local_of(old_local, g);
      if (i < 0 || !blocks.owned[i])
        throw std::logic_error("BlockMigration: asked for a block this rank does not own");
      out.put(g);
      put_geometry(out, m, static_cast<unsigned int>(i));
      visit_block_arrays(s, [&](auto& array) { out.put(array[i]); });
      out.put<unsigned int>(static_cast<unsigned int>(contacts_of[i].size()));
      for (unsigned int c : contacts_of[i])
        put_contact(out, c);
    }
    reply[r] = std::move(out.data);
  }
  const std::vector<std::vector<char>> got = block_records::trade(reply, comm_, 2413);

  // 4. The blocks received: geometry as one-block models, where their
  // solver state starts, and their contacts (records of put_contact) with
  // blocks held here from now on, each pair once (a contact between two
  // blocks new here comes from both their owners). None of them is among
  // the contacts kept, which join two blocks held before.
  std::vector<BlockModel> arrived(n_new);
  std::vector<const char*> arrays_of(n_new, nullptr);
  std::vector<std::pair<std::uint64_t, const char*>> received_contacts;
  std::unordered_set<std::uint64_t> have;
  const auto skip_contact = [&](Reader& in)
  {
    const char* start = in.at;
    const unsigned int a = in.get<unsigned int>(), b = in.get<unsigned int>();
    in.at += block_records::contact_head_size - sizeof(unsigned int);
    const unsigned int n_sc = in.get<unsigned int>();
    in.at += n_sc * block_records::subcontact_size(dilation, yielding, nodes);
    const int la = local_of(next.local, a), lb = local_of(next.local, b);
    if (la >= 0 && lb >= 0 && (next.owned[la] || next.owned[lb]) &&
        have.insert(ContactSet::pair_key(la, lb)).second)
      received_contacts.emplace_back(ContactSet::pair_key(la, lb), start);
  };
  std::size_t arrays_size = 0;
  visit_block_arrays(s, [&](auto& array) { arrays_size += sizeof(array[0]); });
  for (int r = 0; r < n_ranks; ++r)
  {
    Reader in{got[r].data()};
    while (in.at != got[r].data() + got[r].size())
    {
      const int j = local_of(next.local, in.get<unsigned int>());
      get_geometry(in, arrived[j]);
      arrays_of[j] = in.at;
      in.at += arrays_size;
      const unsigned int n_contacts = in.get<unsigned int>();
      for (unsigned int k = 0; k < n_contacts; ++k)
        skip_contact(in);
    }
  }

  // 5. The model and the solver's arrays in the new local order (the
  // global order): kept blocks from here, others as received.
  BlockModel model;
  model.group_names = m.group_names;
  std::vector<int> vertex_gridpoint; // with zones: the surfaces' gridpoints, kept blocks only
  for (unsigned int j = 0; j < n_new; ++j)
  {
    const std::size_t first = model.vertex.size();
    if (old_of[j] >= 0)
      append_block(model, m, static_cast<unsigned int>(old_of[j]));
    else
      append_block(model, arrived[j], 0);
    if (s.zones_ == nullptr || zones_move)
      continue;
    if (old_of[j] >= 0)
      vertex_gridpoint.insert(vertex_gridpoint.end(),
                              s.vertex_gridpoint_.begin() + m.vertex_start[old_of[j]],
                              s.vertex_gridpoint_.begin() + m.vertex_start[old_of[j] + 1]);
    else if (is_deformable_known(next.local[j])) // a surface held here (checked above)
    {
      const std::vector<int>& surface = s.held_surfaces_.at(next.local[j]);
      if (surface.size() != model.vertex.size() - first)
        throw std::logic_error("BlockMigration: a deformable block's surface is not the one held");
      vertex_gridpoint.insert(vertex_gridpoint.end(), surface.begin(), surface.end());
    }
    else
      vertex_gridpoint.resize(vertex_gridpoint.size() + model.vertex.size() - first, -1);
  }
  std::size_t at = 0; // byte offset of the array in a received block's state
  visit_block_arrays(s,
                     [&](auto& array)
                     {
                       using T = typename std::decay_t<decltype(array)>::value_type;
                       std::vector<T> next_array(n_new);
                       for (unsigned int j = 0; j < n_new; ++j)
                         if (old_of[j] >= 0)
                           next_array[j] = array[old_of[j]];
                         else
                           std::memcpy(static_cast<void*>(&next_array[j]), arrays_of[j] + at,
                                       sizeof(T));
                       at += sizeof(T);
                       array.swap(next_array);
                     });
  m = std::move(model);
  // With the zones split again: each sub-contact's gridpoints from their
  // numbers in the whole mesh to the new split's local numbers.
  std::unordered_map<unsigned int, int> next_gridpoint;
  if (zones_move)
  {
    ZonesMoved moved = rebuild_(blocks, next, m);
    s.zones_ = moved.zones;
    vertex_gridpoint = std::move(moved.vertex_gridpoint);
    s.held_surfaces_ = std::move(moved.held_surfaces);
    const std::vector<unsigned int>& whole = s.zones_->share()->whole_gridpoint;
    for (std::size_t i = 0; i < whole.size(); ++i)
      next_gridpoint[whole[i]] = static_cast<int>(i);
    ++zone_moves_;
  }
  const auto node_now = [&](int node)
  {
    if (node < 0 || !zones_move)
      return node;
    const auto it = next_gridpoint.find(gridpoints->whole_gridpoint[std::size_t(node)]);
    if (it == next_gridpoint.end())
      throw std::logic_error("BlockMigration: a contact's gridpoint is not held in the new split");
    return it->second;
  };
  if (s.zones_ != nullptr)
  {
    // In place: the contacts point at these.
    s.vertex_gridpoint_ = vertex_gridpoint;
    s.deformable_blocks_.clear();
    for (unsigned int j = 0; j < n_new; ++j)
      if (s.is_deformable_[j])
        s.deformable_blocks_.push_back(j);
  }

  // 6. The contacts again, in block-pair order (those kept are in it
  // already, the global order being kept), slots in that order, each
  // contact's sub-contacts after its predecessor's.
  cs.sort_by_pair();
  std::vector<std::pair<std::uint64_t, unsigned int>> kept; // new pair, old slot
  for (const unsigned int c : cs.pair_order_)
    if (cs.alive[c] && new_of[cs.block_a[c]] >= 0 && new_of[cs.block_b[c]] >= 0 &&
        (next.owned[new_of[cs.block_a[c]]] || next.owned[new_of[cs.block_b[c]]]))
      kept.emplace_back(ContactSet::pair_key(new_of[cs.block_a[c]], new_of[cs.block_b[c]]), c);
  std::sort(received_contacts.begin(), received_contacts.end());
  ContactSet laid;
  const auto add_kept = [&](std::uint64_t key, unsigned int old)
  {
    block_records::copy_contact(laid, laid.append_slot(key), cs, old, sc_begin[old], sc_end[old],
                                dilation, yielding, nodes, node_now);
  };
  const auto add_received = [&](std::uint64_t key, const char* record)
  {
    Reader in{record + 2 * sizeof(unsigned int)};
    block_records::get_contact(in, laid, laid.append_slot(key), dilation, yielding,
                               [&](Reader& from)
                               {
                                 if (nodes)
                                   block_records::get_nodes_held(
                                       from, laid, zones_move ? next_gridpoint : local_gridpoint,
                                       "BlockMigration: a contact's gridpoint is not held here");
                               });
  };
  for (std::size_t k = 0, r = 0; k < kept.size() || r < received_contacts.size();)
    if (r == received_contacts.size() ||
        (k < kept.size() && kept[k].first < received_contacts[r].first))
    {
      add_kept(kept[k].first, kept[k].second);
      ++k;
    }
    else
    {
      add_received(received_contacts[r].first, received_contacts[r].second);
      ++r;
    }
  laid.is_deformable_ = cs.is_deformable_; // rigid only: none
  laid.vertex_gridpoint_ = cs.vertex_gridpoint_;
  laid.planes_computed_ = cs.planes_computed_;
  cs = std::move(laid);

  // 7. The rest of the solver: ghosts, the cell space on the blocks held
  // now, eq. 1's flag for the blocks received, the block of the ratio.
  s.ghost_.assign(n_new, 0);
  s.subcontacts_stale_ = true;
  for (unsigned int j = 0; j < n_new; ++j)
  {
    s.ghost_[j] = !next.owned[j];
    if (old_of[j] < 0)
      s.moved_beyond_tolerance_ |= s.moved[j] > s.s_.contact.tolerance;
  }
  Box bounds{Vec3::Zero(), Vec3::Zero()};
  if (!m.vertex.empty())
    bounds = Box{m.vertex[0], m.vertex[0]};
  for (const Vec3& v : m.vertex)
  {
    bounds.lo = bounds.lo.cwiseMin(v);
    bounds.hi = bounds.hi.cwiseMax(v);
  }
  s.cells_.define(bounds, n_new);
  s.ratio_block_ = s.ratio_block_ < n_old && new_of[s.ratio_block_] >= 0
                       ? static_cast<unsigned int>(new_of[s.ratio_block_])
                       : 0;
  s.too_fast_.clear();
  s.pairs_.clear();
  blocks = std::move(next);
  path_at_choice_ = s.path;
  ++events_;
  return true;
}

} // namespace talus
