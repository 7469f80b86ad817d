#pragma once

// Internal to source/solver: the per-block arrays of RigidSolver that a
// block carries between ranks (block_migration.cc) and into the whole
// model's state (whole_state.cc).

#include <talus/contact/contact_set.h>
#include <talus/joint/continuously_yielding.h>
#include <talus/solver/block_migration.h>
#include <talus/solver/rigid_solver.h>
#include <talus/zone/gridpoint_share.h>

#include <cstring>
#include <stdexcept>
#include <unordered_map>
#include <vector>

namespace talus
{

namespace block_records
{

/// Values appended bit for bit (plain numbers, and Eigen's fixed-size
/// vectors and matrices, which are their numbers).
struct Bytes
{
  std::vector<char> data;
  template <typename T>
  void put(const T& x)
  {
    const char* p = reinterpret_cast<const char*>(&x);
    data.insert(data.end(), p, p + sizeof(T));
  }
};

/// Reads what Bytes wrote, in the same order.
struct Reader
{
  const char* at;
  template <typename T>
  T get()
  {
    T x;
    std::memcpy(static_cast<void*>(&x), at, sizeof(T));
    at += sizeof(T);
    return x;
  }
};

/// One int per rank each way (MPI_Alltoall), then the messages whose
/// lengths they give, point to point between the ranks with something to
/// trade (defined in block_migration.cc).
std::vector<std::vector<char>> trade(const std::vector<std::vector<char>>& out, MPI_Comm comm,
                                     int tag);

/// The bytes of a contact's record before its sub-contacts, after its two
/// block numbers (put_contact).
constexpr std::size_t contact_head_size = sizeof(CommonPlane) + sizeof(double) +
                                          sizeof(ContactType) + sizeof(unsigned char) +
                                          sizeof(double) + sizeof(unsigned int);

/// The bytes of one sub-contact's record (put_contact).
inline std::size_t subcontact_size(bool dilation, bool yielding, bool nodes)
{
  return sizeof(Vec3) + 9 * sizeof(double) + 3 * sizeof(unsigned char) +
         (dilation ? sizeof(double) : 0) + (yielding ? yield_state_size * sizeof(double) : 0) +
         (nodes ? 6 * (sizeof(int) + sizeof(double)) : 0);
}

/// Sub-contact k's gridpoints (6) with their weights, each gridpoint by
/// its number in the whole mesh (`gridpoints`: the split zones' share), -1
/// for none: how they travel between ranks.
inline void put_subcontact_nodes(Bytes& to, const ContactSet& cs, unsigned int k,
                                 const GridpointShare& gridpoints)
{
  for (unsigned int n = 6 * k; n < 6 * k + 6; ++n)
  {
    to.put<int>(cs.sc_node[n] < 0
                    ? -1
                    : static_cast<int>(gridpoints.whole_gridpoint[std::size_t(cs.sc_node[n])]));
    to.put(cs.sc_weight[n]);
  }
}

/// Appends contact c of `cs` between blocks numbered `a` and `b` (as the
/// receiver knows them): its plane and state, then its sub-contacts
/// [begin, end) with theirs; `put_nodes(out, k)` adds sub-contact k's
/// gridpoints, if the record has them.
template <typename PutNodes>
void put_contact(Bytes& out, const ContactSet& cs, unsigned int c, unsigned int a, unsigned int b,
                 unsigned int begin, unsigned int end, bool dilation, bool yielding,
                 PutNodes&& put_nodes)
{
  out.put(a);
  out.put(b);
  out.put(cs.plane[c]);
  out.put(cs.gap[c]);
  out.put(cs.type[c]);
  out.put(cs.material[c]);
  out.put(cs.path_at_update[c]);
  out.put(end - begin);
  for (unsigned int k = begin; k < end; ++k)
  {
    out.put(cs.sc_position[k]);
    out.put(cs.sc_area[k]);
    out.put(cs.sc_un[k]);
    out.put(cs.sc_fn[k]);
    for (int d = 0; d < 3; ++d)
      out.put(cs.sc_fs[3 * k + d]);
    for (int d = 0; d < 3; ++d)
      out.put(cs.sc_us[3 * k + d]);
    out.put(cs.sc_state[k]);
    out.put(cs.sc_material[k]);
    out.put(cs.sc_fresh[k]);
    if (dilation)
      out.put(cs.sc_dilation[k]);
    if (yielding)
      for (unsigned int y = 0; y < yield_state_size; ++y)
        out.put(cs.sc_yield[yield_state_size * k + y]);
    put_nodes(out, k);
  }
}

/// Reads a record of put_contact, from after its block numbers, into slot
/// c of `laid` (the last made, its blocks set): the contact's plane and
/// state, and its sub-contacts appended; `get_nodes(in)` reads a
/// sub-contact's gridpoints, if the record has them.
template <typename GetNodes>
void get_contact(Reader& in, ContactSet& laid, unsigned int c, bool dilation, bool yielding,
                 GetNodes&& get_nodes)
{
  laid.plane.push_back(in.get<CommonPlane>());
  laid.gap.push_back(in.get<double>());
  laid.type.push_back(in.get<ContactType>());
  laid.material.push_back(in.get<unsigned char>());
  laid.path_at_update.push_back(in.get<double>());
  const unsigned int n_sc = in.get<unsigned int>();
  for (unsigned int k = 0; k < n_sc; ++k)
  {
    laid.sc_contact.push_back(c);
    laid.sc_position.push_back(in.get<Vec3>());
    laid.sc_area.push_back(in.get<double>());
    laid.sc_un.push_back(in.get<double>());
    laid.sc_fn.push_back(in.get<double>());
    for (int d = 0; d < 3; ++d)
      laid.sc_fs.push_back(in.get<double>());
    for (int d = 0; d < 3; ++d)
      laid.sc_us.push_back(in.get<double>());
    laid.sc_state.push_back(in.get<unsigned char>());
    laid.sc_material.push_back(in.get<unsigned char>());
    laid.sc_fresh.push_back(in.get<unsigned char>());
    if (dilation)
      laid.sc_dilation.push_back(in.get<double>());
    if (yielding)
      for (unsigned int y = 0; y < yield_state_size; ++y)
        laid.sc_yield.push_back(in.get<double>());
    get_nodes(in);
  }
}

/// Appends contact `old` of `cs`, with its sub-contacts [begin, end), to
/// `laid` as slot c (ContactSet::append_slot): every value as it is, but
/// each gridpoint of its sub-contacts (if they have them: `nodes`) renamed
/// by `node_now(node)`.
template <typename NodeNow>
void copy_contact(ContactSet& laid, unsigned int c, const ContactSet& cs, unsigned int old,
                  unsigned int begin, unsigned int end, bool dilation, bool yielding, bool nodes,
                  NodeNow&& node_now)
{
  laid.plane.push_back(cs.plane[old]);
  laid.gap.push_back(cs.gap[old]);
  laid.type.push_back(cs.type[old]);
  laid.material.push_back(cs.material[old]);
  laid.path_at_update.push_back(cs.path_at_update[old]);
  for (unsigned int k = begin; k < end; ++k)
  {
    laid.sc_contact.push_back(c);
    laid.sc_position.push_back(cs.sc_position[k]);
    laid.sc_area.push_back(cs.sc_area[k]);
    laid.sc_un.push_back(cs.sc_un[k]);
    laid.sc_fn.push_back(cs.sc_fn[k]);
    laid.sc_fs.insert(laid.sc_fs.end(), &cs.sc_fs[3 * k], &cs.sc_fs[3 * k] + 3);
    laid.sc_us.insert(laid.sc_us.end(), &cs.sc_us[3 * k], &cs.sc_us[3 * k] + 3);
    laid.sc_state.push_back(cs.sc_state[k]);
    laid.sc_material.push_back(cs.sc_material[k]);
    laid.sc_fresh.push_back(cs.sc_fresh[k]);
    if (dilation)
      laid.sc_dilation.push_back(cs.sc_dilation[k]);
    if (yielding)
      laid.sc_yield.insert(laid.sc_yield.end(), &cs.sc_yield[yield_state_size * k],
                           &cs.sc_yield[yield_state_size * k] + yield_state_size);
    if (nodes)
    {
      for (unsigned int n = 6 * k; n < 6 * k + 6; ++n)
        laid.sc_node.push_back(node_now(cs.sc_node[n]));
      laid.sc_weight.insert(laid.sc_weight.end(), &cs.sc_weight[6 * k], &cs.sc_weight[6 * k] + 6);
    }
  }
}

/// Reads one sub-contact's gridpoints (put_subcontact_nodes: by their
/// numbers in the whole mesh) into `laid`, each by the local number `held`
/// gives it; throws std::logic_error(`missing`) for one not held here.
inline void get_nodes_held(Reader& from, ContactSet& laid,
                           const std::unordered_map<unsigned int, int>& held, const char* missing)
{
  for (int n = 0; n < 6; ++n)
  {
    const int whole = from.get<int>();
    int node = -1;
    if (whole >= 0)
    {
      const auto it = held.find(static_cast<unsigned int>(whole));
      if (it == held.end())
        throw std::logic_error(missing);
      node = it->second;
    }
    laid.sc_node.push_back(node);
    laid.sc_weight.push_back(from.get<double>());
  }
}

} // namespace block_records

template <typename Visit>
void BlockMigration::visit_block_arrays(RigidSolver& s, Visit&& visit)
{
  visit(s.mass);
  visit(s.inertial_mass);
  visit(s.inertia);
  visit(s.velocity);
  visit(s.spin);
  visit(s.force);
  visit(s.moment);
  visit(s.displacement);
  visit(s.rotation);
  visit(s.fixed);
  visit(s.applied_force);
  visit(s.applied_force_rate);
  visit(s.prescribed);
  visit(s.moved);
  visit(s.path);
  visit(s.last_force_);
  visit(s.last_moment_);
  visit(s.motion_dx_);
  visit(s.motion_dtheta_);
  visit(s.damping_force_);
  visit(s.damping_moment_);
  visit(s.is_deformable_);
  visit(s.removed_);
  visit(s.true_inertia_);
  visit(s.envelopes_);
  if (s.s_.principal_inertia)
  {
    visit(s.principal_moments);
    visit(s.axes);
    visit(s.true_principal_);
  }
  if (!s.timed_force_.empty())
  {
    visit(s.timed_force_);
    visit(s.timed_velocity_);
    visit(s.timed_held_);
  }
}

} // namespace talus
