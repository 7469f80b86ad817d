#pragma once

#include <talus/contact/block_decomposition.h>

#include <mpi.h>

#include <cstddef>
#include <vector>

namespace talus
{

class ContactSet;
struct GridpointShare;

/// A model split among ranks computes each contact once (issue 24): of a
/// contact across two ranks, one (RankBlocks::computes_contact, about half
/// of them each) finds it, updates its common plane and builds its
/// sub-contacts, then runs them through the displacement increments and
/// the joint model at every step; the other takes the contact from it: its
/// plane and sub-contacts at each update (send_layout, receive_layout),
/// their new state at each step (start, finish), one message per neighbour
/// rank each way. The sub-contacts' force sums then
/// run on both ranks over the same numbers, in the same order as one rank
/// would, so that the answer is still the serial one, bit for bit.
///
/// Both ranks hold such a contact with the same sub-contacts; match()
/// checks that and throws when not.
class SubContactExchange
{
public:
  SubContactExchange(const RankBlocks& blocks, MPI_Comm comm) : blocks_(blocks), comm_(comm) {}

  /// The lists of sub-contacts to send and to receive, made again from
  /// `cs`; every rank calls it at the same step (after a contact search or
  /// update, a migration, a stage's change, a restart). Sends each
  /// neighbour the pairs (global numbers) and sub-contact counts it will
  /// receive, and throws std::logic_error when they are not those it holds.
  void match(const ContactSet& cs);

  /// The two halves of a ContactSet::update's ContactTrade (every rank
  /// with neighbours calls both at the same update; one message to each
  /// neighbour each way). send_layout posts, for each neighbour, the
  /// contacts `slots` of `cs` whose second block it owns, with their planes,
  /// state and sub-contacts [begin[i], end[i]); receive_layout appends to
  /// `taken` those the neighbours sent, in pair order, and throws
  /// std::logic_error for one whose blocks are not held here as its
  /// sender's ghost and this rank's own. `gridpoints`: the split zones'
  /// share, when the sub-contacts have gridpoints.
  void send_layout(const ContactSet& cs, const std::vector<unsigned int>& slots,
                   const std::vector<unsigned int>& begin, const std::vector<unsigned int>& end,
                   bool dilation, bool yielding, const GridpointShare* gridpoints);
  void receive_layout(ContactSet& taken, bool dilation, bool yielding,
                      const GridpointShare* gridpoints);
  /// Contacts this rank took from its neighbours at the last receive_layout.
  std::size_t contacts_taken() const { return contacts_taken_; }

  /// Of the matched layout: the sub-contacts this rank computes and sends
  /// (of a contact across ranks that it computes), ascending, which go
  /// through the joint model first (a list: they are a few percent, and a
  /// pass over a mask of all cost more than their model); and per
  /// sub-contact 1 for the others it computes (both blocks owned), which
  /// go through it while the messages travel.
  const std::vector<unsigned int>& sent_first() const { return sent_first_; }
  const std::vector<unsigned char>& computed_after() const { return computed_after_; }
  /// Per sub-contact: 1 for all those this rank computes (either of the
  /// two above), 0 for those it takes from a neighbour or that lie
  /// between two ghosts.
  const std::vector<unsigned char>& computed() const { return computed_; }

  /// Once the sub-contacts of sent_first() went through the joint model:
  /// posts the receives and sends the state of those sub-contacts
  /// (position, normal displacement, forces, shear displacement, state,
  /// and dilation, yield state and, with `velocity` (3 per sub-contact),
  /// the relative velocity, when kept).
  void start(const ContactSet& cs, const std::vector<double>* velocity);
  /// Waits for the messages start() posted and writes what arrived into
  /// the sub-contacts this rank does not compute.
  void finish(ContactSet& cs, std::vector<double>* velocity);

  /// The blocks this rank holds (kept by the caller, changed in place).
  const RankBlocks& blocks() const { return blocks_; }

  /// Doubles sent by this rank at the last start().
  std::size_t sent() const { return sent_; }
  /// Sub-contacts this rank takes from its neighbours (matched layout).
  std::size_t received() const { return n_received_; }
  /// Seconds this rank has waited for its neighbours' messages, in all:
  /// for the sub-contacts' state (finish) and for their layout
  /// (receive_layout). A rank that waits is ahead of the other.
  double seconds_waiting_for_state() const { return state_wait_; }
  double seconds_waiting_for_layout() const { return layout_wait_; }

private:
  struct Neighbour
  {
    unsigned int rank = 0;
    std::vector<unsigned int> send, receive; ///< sub-contact indices, in pair order
    std::vector<double> out, in;
  };
  const RankBlocks& blocks_;
  MPI_Comm comm_;
  std::vector<Neighbour> neighbours_;
  std::vector<unsigned int> sent_first_;
  std::vector<unsigned char> computed_after_, computed_;
  std::vector<MPI_Request> requests_;
  std::size_t sent_ = 0, n_received_ = 0, contacts_taken_ = 0;
  double state_wait_ = 0.0, layout_wait_ = 0.0;
  /// Per block held: the rank that owns it.
  std::vector<unsigned int> owners() const;
  /// The ranks that send ghosts here or take ghosts from here, ascending.
  std::vector<unsigned int> neighbour_ranks() const;
  std::vector<unsigned int> layout_ranks_; ///< the neighbours at the last send_layout
  std::vector<std::vector<char>> layout_out_;
  std::vector<MPI_Request> layout_requests_;
};

} // namespace talus
