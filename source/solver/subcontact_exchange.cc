#include <talus/base/wall_clock.h>
#include <talus/contact/contact_set.h>
#include <talus/joint/continuously_yielding.h>
#include <talus/solver/subcontact_exchange.h>

#include "block_arrays.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace talus
{

namespace
{
constexpr int header_tag = 2402, state_tag = 2403, layout_tag = 2404;

/// Doubles per sub-contact in a swap: position (3), normal displacement,
/// normal force, shear force (3), shear displacement (3), state; then the
/// dilation, the yield state and the relative velocity when kept.
std::size_t record_width(const ContactSet& cs, bool velocity)
{
  return 12 + (cs.sc_dilation.empty() ? 0 : 1) + (cs.sc_yield.empty() ? 0 : yield_state_size) +
         (velocity ? 3 : 0);
}

void wait_all(std::vector<MPI_Request>& requests)
{
  if (MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE) !=
      MPI_SUCCESS)
    throw std::runtime_error("SubContactExchange: a message between ranks failed");
}
} // namespace

std::vector<unsigned int> SubContactExchange::owners() const
{
  std::vector<unsigned int> owner(blocks_.local.size(), blocks_.rank);
  for (const auto& [from, ghosts] : blocks_.receive)
    for (unsigned int i : ghosts)
      owner[i] = from;
  return owner;
}

std::vector<unsigned int> SubContactExchange::neighbour_ranks() const
{
  // The relation is symmetric: both sides of each pair expect a message.
  std::vector<unsigned int> ranks;
  for (const auto& [to, mine] : blocks_.send)
    ranks.push_back(to);
  for (const auto& [from, theirs] : blocks_.receive)
    ranks.push_back(from);
  std::sort(ranks.begin(), ranks.end());
  ranks.erase(std::unique(ranks.begin(), ranks.end()), ranks.end());
  return ranks;
}

void SubContactExchange::match(const ContactSet& cs)
{
  const std::vector<unsigned int> owner = owners();
  const auto ghost = [&](unsigned int b) { return blocks_.owned[b] == 0; };

  // Every rank that sends ghosts here or takes ghosts from here.
  const std::vector<unsigned int> ranks = neighbour_ranks();
  neighbours_.assign(ranks.size(), Neighbour{});
  for (std::size_t k = 0; k < ranks.size(); ++k)
    neighbours_[k].rank = ranks[k];
  const auto neighbour = [&](unsigned int rank) -> Neighbour&
  { return neighbours_[std::lower_bound(ranks.begin(), ranks.end(), rank) - ranks.begin()]; };

  std::vector<unsigned int> begin, end;
  cs.subcontact_ranges(cs.n_slots(), begin, end);
  n_received_ = 0;
  sent_first_.clear();
  computed_after_.assign(cs.n_subcontacts(), 0);
  computed_.assign(cs.n_subcontacts(), 0);
  for (unsigned int k = 0; k < cs.n_subcontacts(); ++k)
  {
    const unsigned int c = cs.sc_contact[k];
    const unsigned int a = cs.block_a[c], b = cs.block_b[c];
    computed_after_[k] = !ghost(a) && !ghost(b);
    const bool sent = ghost(a) != ghost(b) && blocks_.computes_contact(a, b);
    if (sent)
      sent_first_.push_back(k);
    computed_[k] = computed_after_[k] | sent;
  }
  // The contacts across ranks in pair order (local order is global order).
  std::vector<std::array<unsigned int, 3>> cut;
  for (unsigned int c = 0; c < cs.n_slots(); ++c)
    if (cs.alive[c] && ghost(cs.block_a[c]) != ghost(cs.block_b[c]))
      cut.push_back({{cs.block_a[c], cs.block_b[c], c}});
  std::sort(cut.begin(), cut.end());
  std::vector<std::vector<unsigned long long>> expected(ranks.size());
  std::vector<std::vector<unsigned long long>> told(ranks.size());
  for (const auto& [a, b, c] : cut)
  {
    const bool sending = blocks_.computes_contact(a, b);
    const unsigned int other = owner[ghost(a) ? a : b];
    if (other == blocks_.rank)
      throw std::logic_error("SubContactExchange: a ghost on rank " + std::to_string(other) +
                             " that no other rank sends");
    Neighbour& n = neighbour(other);
    std::vector<unsigned int>& list = sending ? n.send : n.receive;
    for (unsigned int k = begin[c]; k < end[c]; ++k)
      list.push_back(k);
    if (!sending)
      n_received_ += end[c] - begin[c];
    const std::size_t slot = &n - neighbours_.data();
    std::vector<unsigned long long>& heads = sending ? told[slot] : expected[slot];
    heads.insert(heads.end(), {blocks_.local[a], blocks_.local[b], end[c] - begin[c]});
  }

  // Each side tells the other what it will send; the receiver checks it.
  std::vector<MPI_Request> requests(ranks.size());
  for (std::size_t k = 0; k < ranks.size(); ++k)
    MPI_Isend(told[k].data(), static_cast<int>(told[k].size()), MPI_UNSIGNED_LONG_LONG,
              static_cast<int>(ranks[k]), header_tag, comm_, &requests[k]);
  std::string disagreement;
  for (std::size_t k = 0; k < ranks.size(); ++k)
  {
    MPI_Status status;
    MPI_Probe(static_cast<int>(ranks[k]), header_tag, comm_, &status);
    int count = 0;
    MPI_Get_count(&status, MPI_UNSIGNED_LONG_LONG, &count);
    std::vector<unsigned long long> heard(static_cast<std::size_t>(count));
    MPI_Recv(heard.data(), count, MPI_UNSIGNED_LONG_LONG, static_cast<int>(ranks[k]), header_tag,
             comm_, MPI_STATUS_IGNORE);
    if (heard != expected[k] && disagreement.empty())
    {
      std::size_t i = 0;
      while (i + 3 <= heard.size() && i + 3 <= expected[k].size() &&
             std::equal(heard.begin() + long(i), heard.begin() + long(i + 3),
                        expected[k].begin() + long(i)))
        i += 3;
      std::ostringstream text;
      text << "ranks " << blocks_.rank << " and " << ranks[k]
           << " hold different contacts across their boundary (" << expected[k].size() / 3
           << " expected, " << heard.size() / 3 << " announced; first difference at contact "
           << i / 3 << ")";
      disagreement = text.str();
    }
  }
  wait_all(requests);
  if (!disagreement.empty())
    throw std::logic_error("SubContactExchange: " + disagreement);
}

void SubContactExchange::send_layout(const ContactSet& cs, const std::vector<unsigned int>& slots,
                                     const std::vector<unsigned int>& begin,
                                     const std::vector<unsigned int>& end, bool dilation,
                                     bool yielding, const GridpointShare* gridpoints)
{
  using block_records::Bytes;
  // Records carry gridpoints exactly when the zones are split.
  const bool nodes = gridpoints != nullptr;
  if (nodes != cs.has_deformable())
    throw std::logic_error("SubContactExchange: sub-contacts with gridpoints need the zones' "
                           "split, and only they have it");
  const std::vector<unsigned int> owner = owners();
  // Only the neighbours talk (a rank without ghosts has none); each hears
  // from each, if only an empty message.
  layout_ranks_ = neighbour_ranks();
  const auto slot_of = [&](unsigned int rank)
  {
    return std::size_t(std::lower_bound(layout_ranks_.begin(), layout_ranks_.end(), rank) -
                       layout_ranks_.begin());
  };
  std::vector<Bytes> out(layout_ranks_.size());
  for (std::size_t i = 0; i < slots.size(); ++i)
  {
    const unsigned int c = slots[i], a = cs.block_a[c], b = cs.block_b[c];
    block_records::put_contact(out[slot_of(owner[blocks_.owned[a] ? b : a])], cs, c,
                               blocks_.local[a], blocks_.local[b], begin[i], end[i], dilation,
                               yielding,
                               [&](Bytes& to, unsigned int k)
                               {
                                 if (nodes)
                                   block_records::put_subcontact_nodes(to, cs, k, *gridpoints);
                               });
  }
  layout_out_.resize(out.size());
  layout_requests_.assign(out.size(), MPI_REQUEST_NULL);
  for (std::size_t k = 0; k < out.size(); ++k)
  {
    layout_out_[k] = std::move(out[k].data);
    MPI_Isend(layout_out_[k].data(), static_cast<int>(layout_out_[k].size()), MPI_CHAR,
              static_cast<int>(layout_ranks_[k]), layout_tag, comm_, &layout_requests_[k]);
  }
}

void SubContactExchange::receive_layout(ContactSet& taken, bool dilation, bool yielding,
                                        const GridpointShare* gridpoints)
{
  using block_records::Reader;
  const bool nodes = gridpoints != nullptr;
  const std::vector<unsigned int> owner = owners();
  const auto ghost = [&](unsigned int b) { return blocks_.owned[b] == 0; };
  std::vector<std::vector<char>> got(layout_ranks_.size());
  const auto waiting = std::chrono::steady_clock::now();
  for (std::size_t k = 0; k < layout_ranks_.size(); ++k)
  {
    MPI_Status status;
    MPI_Probe(static_cast<int>(layout_ranks_[k]), layout_tag, comm_, &status);
    int count = 0;
    MPI_Get_count(&status, MPI_CHAR, &count);
    got[k].resize(static_cast<std::size_t>(count));
    MPI_Recv(got[k].data(), count, MPI_CHAR, static_cast<int>(layout_ranks_[k]), layout_tag, comm_,
             MPI_STATUS_IGNORE);
  }
  wait_all(layout_requests_);
  layout_wait_ += seconds_since(waiting);

  // What arrived, by local pair, in pair order.
  const auto local_of = [&](unsigned int g)
  {
    const auto it = std::lower_bound(blocks_.local.begin(), blocks_.local.end(), g);
    return it != blocks_.local.end() && *it == g ? static_cast<long>(it - blocks_.local.begin())
                                                 : -1l;
  };
  std::vector<std::pair<std::uint64_t, const char*>> records;
  for (std::size_t k = 0; k < layout_ranks_.size(); ++k)
  {
    const unsigned int r = layout_ranks_[k];
    Reader in{got[k].data()};
    const char* const stop = got[k].data() + got[k].size();
    while (in.at < stop)
    {
      const char* record = in.at;
      const unsigned int ga = in.get<unsigned int>(), gb = in.get<unsigned int>();
      in.at += block_records::contact_head_size - sizeof(unsigned int);
      const unsigned int n_sc = in.get<unsigned int>();
      in.at += n_sc * block_records::subcontact_size(dilation, yielding, nodes);
      const long a = local_of(ga), b = local_of(gb);
      // Its computing block must be the sender's, a ghost here; the other
      // this rank's own.
      const long computing = RankBlocks::contact_computed_by_first(ga, gb) ? a : b,
                 other = computing == a ? b : a;
      if (a < 0 || b < 0 || !ghost(static_cast<unsigned int>(computing)) ||
          ghost(static_cast<unsigned int>(other)) || owner[std::size_t(computing)] != r)
        throw std::logic_error("SubContactExchange: rank " + std::to_string(r) +
                               " sent a contact of blocks " + std::to_string(ga) + " and " +
                               std::to_string(gb) + " that rank " + std::to_string(blocks_.rank) +
                               " does not hold as the sender's ghost and its own");
      records.emplace_back(ContactSet::pair_key(unsigned(a), unsigned(b)), record);
    }
  }
  std::sort(records.begin(), records.end());
  contacts_taken_ = records.size();

  std::unordered_map<unsigned int, int> held;
  if (nodes)
    for (std::size_t i = 0; i < gridpoints->whole_gridpoint.size(); ++i)
      held[gridpoints->whole_gridpoint[i]] = static_cast<int>(i);
  for (const auto& [key, record] : records)
  {
    Reader in{record + 2 * sizeof(unsigned int)};
    block_records::get_contact(in, taken, taken.append_slot(key), dilation, yielding,
                               [&](Reader& from)
                               {
                                 if (nodes)
                                   block_records::get_nodes_held(
                                       from, taken, held,
                                       "SubContactExchange: a contact's gridpoint is not held "
                                       "on the rank that takes it");
                               });
  }
}

void SubContactExchange::start(const ContactSet& cs, const std::vector<double>* velocity)
{
  const std::size_t w = record_width(cs, velocity != nullptr);
  const bool dilation = !cs.sc_dilation.empty(), yielding = !cs.sc_yield.empty();
  std::vector<MPI_Request>& requests = requests_;
  requests.clear();
  requests.reserve(2 * neighbours_.size());
  for (Neighbour& n : neighbours_)
  {
    n.in.resize(w * n.receive.size());
    requests.emplace_back();
    MPI_Irecv(n.in.data(), static_cast<int>(n.in.size()), MPI_DOUBLE, static_cast<int>(n.rank),
              state_tag, comm_, &requests.back());
  }
  sent_ = 0;
  for (Neighbour& n : neighbours_)
  {
    n.out.resize(w * n.send.size());
    double* at = n.out.data();
    for (unsigned int k : n.send)
    {
      const Vec3& p = cs.sc_position[k];
      *at++ = p[0];
      *at++ = p[1];
      *at++ = p[2];
      *at++ = cs.sc_un[k];
      *at++ = cs.sc_fn[k];
      for (int d = 0; d < 3; ++d)
        *at++ = cs.sc_fs[3 * k + d];
      for (int d = 0; d < 3; ++d)
        *at++ = cs.sc_us[3 * k + d];
      *at++ = cs.sc_state[k];
      if (dilation)
        *at++ = cs.sc_dilation[k];
      if (yielding)
        for (unsigned int y = 0; y < yield_state_size; ++y)
          *at++ = cs.sc_yield[yield_state_size * k + y];
      if (velocity != nullptr)
        for (int d = 0; d < 3; ++d)
          *at++ = (*velocity)[3 * k + d];
    }
    sent_ += n.out.size();
    requests.emplace_back();
    MPI_Isend(n.out.data(), static_cast<int>(n.out.size()), MPI_DOUBLE, static_cast<int>(n.rank),
              state_tag, comm_, &requests.back());
  }
}

void SubContactExchange::finish(ContactSet& cs, std::vector<double>* velocity)
{
  const bool dilation = !cs.sc_dilation.empty(), yielding = !cs.sc_yield.empty();
  const auto waiting = std::chrono::steady_clock::now();
  wait_all(requests_);
  state_wait_ += seconds_since(waiting);
  for (Neighbour& n : neighbours_)
  {
    const double* at = n.in.data();
    for (unsigned int k : n.receive)
    {
      cs.sc_position[k] = Vec3(at[0], at[1], at[2]);
      at += 3;
      cs.sc_un[k] = *at++;
      cs.sc_fn[k] = *at++;
      for (int d = 0; d < 3; ++d)
        cs.sc_fs[3 * k + d] = *at++;
      for (int d = 0; d < 3; ++d)
        cs.sc_us[3 * k + d] = *at++;
      cs.sc_state[k] = static_cast<unsigned char>(*at++);
      cs.sc_fresh[k] = 0;
      if (dilation)
        cs.sc_dilation[k] = *at++;
      if (yielding)
        for (unsigned int y = 0; y < yield_state_size; ++y)
          cs.sc_yield[yield_state_size * k + y] = *at++;
      if (velocity != nullptr)
        for (int d = 0; d < 3; ++d)
          (*velocity)[3 * k + d] = *at++;
    }
  }
}

} // namespace talus
