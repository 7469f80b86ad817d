#pragma once

#include <talus/contact/common_plane.h>
#include <talus/joint/joint_properties.h>
#include <talus/model/block_model.h>
#include <talus/model/initial_stress.h>

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace talus
{

class CheckpointReader;
class CheckpointWriter;
struct JointMaterialRule;

struct ContactSettings
{
  double tolerance = 0.01;         ///< CTOL, m: contacts exist while the gap is at most this
  unsigned int update_period = 10; ///< steps between common-plane and sub-contact updates
  double rotation_constant = 0.0;  ///< K_T of eq. 12, m
  /// Area given to a sub-contact of a vertex or edge contact (no face on
  /// one side), as a fraction of the smaller block's volume^(2/3).
  double point_area_fraction = 0.01;
  /// A contact whose two blocks together moved less than this fraction of
  /// the tolerance since its last update keeps its plane and sub-contacts
  /// (their forces still change every step): no work for blocks at rest.
  double update_motion_fraction = 0.01;
  /// Whether sub-contacts keep a normal offset (sc_dilation): joints that
  /// dilate, or that start under an initial stress.
  bool dilation = false;
  /// Whether sub-contacts keep the state of continuously yielding joints
  /// (sc_yield): some joint material is of that model.
  bool yielding = false;
  /// When set, new sub-contacts start with the forces of this stress field
  /// on their plane, the normal force held by a normal offset of
  /// F^n / (kn A) (kn in Pa/m): joints of a model under in-situ stress.
  /// Used for the contacts that exist at the start.
  const InitialStress* initial_stress = nullptr;
  /// kn of each joint material (Pa/m), for that normal offset.
  std::vector<double> kn;
  /// The joint materials (null: all Coulomb slip): a continuously
  /// yielding one takes the closure of its own normal law for that offset.
  const std::vector<JointProperties>* joints = nullptr;
  /// Which joint material a new contact takes (null: material 0 for all).
  const JointMaterialRule* materials = nullptr;
  CommonPlaneSettings common_plane;
};

class ContactSet;
struct RankBlocks;

/// How a rank's share of a model split among ranks (issue 24) has each
/// contact across ranks computed once, by one of its two ranks
/// (RankBlocks::computes_contact): ContactSet::update calls send() once the
/// contacts across ranks this rank computes are updated, then receive() for
/// those the other ranks compute, before it lays everything out in pair
/// order. Called once per update, never per contact.
class ContactTrade
{
public:
  virtual ~ContactTrade() = default;
  /// The blocks this rank holds, owns and computes contacts of.
  virtual const RankBlocks& blocks() const = 0;
  /// Sends contacts `slots` of `cs` (pair order) to the ranks that hold
  /// their computing block as a ghost, with their planes, state and
  /// sub-contacts: those of slots[i] are [begin[i], end[i]) of cs.
  virtual void send(const ContactSet& cs, const std::vector<unsigned int>& slots,
                    const std::vector<unsigned int>& begin,
                    const std::vector<unsigned int>& end) = 0;
  /// Appends to the empty `taken` (ContactSet::append_slot, blocks by
  /// local number, pair order) the contacts across ranks that others
  /// compute, as they sent them, with their sub-contacts.
  virtual void receive(ContactSet& taken) = 0;
};

/// Every contact between blocks (one common plane per pair) and their
/// sub-contacts, in flat arrays. Contacts live in slots that are reused
/// through a free list; sub-contacts are rebuilt at each update, each
/// taking the shear stress of the nearest old sub-contact of its contact,
/// so that neither the shear force nor its energy jumps. Sub-contacts lie
/// in the order of their contacts' block pairs (a, b), whatever slots the
/// contacts hold: every block then sums its contact forces in one order
/// that does not depend on the history of contact detection, which is what
/// lets a run split among ranks give the serial answer to the last bit.
class ContactSet
{
public:
  /// Creates the contact of a candidate pair if the gap is within the
  /// tolerance (no-op when the pair already has one).
  void try_create(unsigned int a, unsigned int b, const BlockModel& blocks,
                  const ContactSettings& settings);

  /// Updates the common planes (deleting contacts whose gap exceeds the
  /// tolerance) and rebuilds the sub-contacts of every contact whose blocks
  /// have moved: `path[b]` is the distance block b's vertices have travelled
  /// since the start (m, never reset). Without `path`, every contact.
  /// With `trade` (a model split among ranks), a contact across ranks that
  /// another rank computes is taken from it, and one this rank computes is
  /// updated first and sent (source/contact/contact_trade.cc).
  void update(const BlockModel& blocks, const ContactSettings& settings,
              const std::vector<double>* path = nullptr, ContactTrade* trade = nullptr);

  /// Deletes the contacts of the blocks with `gone[b]` (excavated); their
  /// sub-contacts go at the next update().
  void remove_contacts_of(const std::vector<char>& gone);
  /// Deletes the contacts between two blocks both marked in `among`, with
  /// their sub-contacts now; the others stay as they are, in their order.
  /// A rank's share of a split model (issue 24) keeps no contact between
  /// two of its ghosts: no owned block feels it.
  void drop_contacts_among(const std::vector<char>& among);

  /// Deformable blocks take part through their surface gridpoints:
  /// `is_deformable` per block, `vertex_gridpoint` per vertex of the block
  /// model (see use_zone_surfaces). Both must outlive the contact set.
  void set_deformable(const std::vector<char>* is_deformable,
                      const std::vector<int>* vertex_gridpoint)
  {
    is_deformable_ = is_deformable;
    vertex_gridpoint_ = vertex_gridpoint;
  }
  bool has_deformable() const { return is_deformable_ != nullptr; }

  unsigned int n_contacts() const { return n_alive_; }
  unsigned int n_slots() const { return static_cast<unsigned int>(block_a.size()); }
  unsigned int n_subcontacts() const { return static_cast<unsigned int>(sc_contact.size()); }
  /// The sub-contacts of each of the first `n` slots, [begin[c], end[c]):
  /// contiguous, in block-pair order (empty for a slot without any).
  void subcontact_ranges(unsigned int n, std::vector<unsigned int>& begin,
                         std::vector<unsigned int>& end) const;
  /// Common planes computed by this set (a candidate pair's search, an
  /// update's), since it was made: its share of the contact work.
  unsigned long planes_computed() const { return planes_computed_; }

  // Contacts (slot-indexed; `alive` says which slots hold one).
  std::vector<unsigned int> block_a, block_b;
  std::vector<CommonPlane> plane;
  std::vector<double> gap;
  std::vector<ContactType> type;
  std::vector<char> alive;
  std::vector<unsigned char> material; ///< joint material (JointMaterialRule)
  std::vector<double> path_at_update;  ///< path[a] + path[b] when last updated

  // Sub-contacts.
  std::vector<unsigned int> sc_contact; ///< contact slot
  std::vector<Vec3> sc_position;        ///< m, on the common plane
  std::vector<double> sc_area;          ///< m^2
  std::vector<double> sc_un;            ///< normal displacement, m (negative = closure)
  std::vector<double> sc_fn;            ///< normal force, N
  std::vector<double> sc_fs;            ///< shear force, 3 per sub-contact, N
  /// Normal offset, m: opening from dilation (eq. 42) plus the closure that
  /// carries an initial stress; empty unless needed.
  std::vector<double> sc_dilation;
  std::vector<double> sc_us; ///< total shear displacement U^s, 3 per sub-contact, m
  std::vector<unsigned char> sc_state;
  /// Continuously yielding joints: yield_state_size doubles per
  /// sub-contact (plastic shear displacement, reversal ratio, loading
  /// direction; continuously_yielding.h); empty unless needed.
  std::vector<double> sc_yield;
  std::vector<unsigned char> sc_material; ///< its contact's joint material
  /// 1 while un was just measured from the geometry: the next force
  /// calculation must not add the last step's motion to it a second time.
  std::vector<unsigned char> sc_fresh;
  /// Only with deformable blocks: what carries the sub-contact on each side,
  /// 3 gridpoints and weights for side A, then 3 for side B (eqs. 16-19,
  /// 33). A gridpoint sub-contact has its own gridpoint with weight 1 on its
  /// side; a point on a deformable face has the face's three gridpoints with
  /// barycentric weights; a rigid side has -1 (its motion is the block's).
  std::vector<int> sc_node;
  std::vector<double> sc_weight;

  /// Checkpoints (source/io/checkpoint.cc): every contact and sub-contact
  /// with its state, and the slot bookkeeping, so that slots are reused in
  /// the same order after a restart.
  void save_state(CheckpointWriter& out) const;
  void load_state(CheckpointReader& in, unsigned int n_blocks);

  /// The key of block pair (a, b) in pair order: a << 32 | b.
  static std::uint64_t pair_key(unsigned int a, unsigned int b)
  {
    return (static_cast<std::uint64_t>(a) << 32) | b;
  }
  /// Appends a live contact slot for the block pair `key` (a << 32 | b),
  /// its plane, state and sub-contacts still to be appended by the caller:
  /// how a set is laid out again from records, in pair order (blocks
  /// changing rank, contacts computed on another rank). Returns the slot.
  unsigned int append_slot(std::uint64_t key);

private:
  /// Lays contacts out again when blocks move between ranks (block_migration.h).
  friend class BlockMigration;
  void remove(unsigned int c);
  /// Sets the previous sub-contacts aside (old_*) for carry-over.
  void set_old_subcontacts_aside();
  /// One live contact of update(): its plane and sub-contacts again, or
  /// their old ones kept when its blocks have not moved, or its removal.
  void update_contact(unsigned int c, const BlockModel& blocks, const ContactSettings& settings,
                      const CommonPlaneSettings& planes, const std::vector<double>* path);
  /// update() with a ContactTrade (contact_trade.cc).
  void update_across_ranks(const BlockModel& blocks, const ContactSettings& settings,
                           const CommonPlaneSettings& planes, const std::vector<double>* path,
                           ContactTrade& trade);
  /// Appends sub-contacts [begin, end) of `from` (laid out alike) as
  /// sub-contacts of contact c.
  void append_subcontacts(const ContactSet& from, unsigned int begin, unsigned int end,
                          unsigned int c);
  void clear_subcontacts();
  void build_subcontacts(unsigned int c, const BlockModel& blocks, const ContactSettings& settings,
                         const Vec3& old_normal);

  std::unordered_map<std::uint64_t, unsigned int> slot_of_pair_;
  std::vector<unsigned int> free_;
  /// Live slots in the order of their block pairs, with those removed since
  /// the sort left in it dead; and whether a contact was made since.
  std::vector<unsigned int> pair_order_;
  bool pair_order_stale_ = true;
  void sort_by_pair();
  unsigned int n_alive_ = 0;
  unsigned long planes_computed_ = 0;
  // Sub-contacts of the previous update, indexed by contact slot, for carry-over.
  std::vector<unsigned int> old_start_, old_end_;
  std::vector<double> old_un_, old_fn_, old_fs_, old_us_, old_dilation_, old_yield_;
  std::vector<unsigned char> old_state_;
  std::vector<Vec3> old_normal_, old_position_;
  std::vector<double> old_area_, old_weight_;
  std::vector<int> old_node_;
  const std::vector<char>* is_deformable_ = nullptr;
  const std::vector<int>* vertex_gridpoint_ = nullptr;
};

} // namespace talus
