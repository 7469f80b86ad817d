#pragma once

#include <talus/geometry/convex_polyhedron.h>
#include <talus/geometry/region.h>

#include <functional>
#include <string>
#include <vector>

namespace talus
{

/// A family of parallel joints (geologists' convention, see normal_from_dip).
struct JointSetSpec
{
  double dip = 0.0;           ///< degrees, 0..90
  double dip_direction = 0.0; ///< degrees clockwise from north (+y), 0..360
  double spacing = 1.0;       ///< m, normal distance between joints
  Vec3 origin = Vec3::Zero(); ///< m, a point on one joint of the set
  /// Number of joints starting at the one through `origin` and continuing
  /// along the upward normal; 0 means the set fills the whole model.
  unsigned int count = 0;
  /// When set, only blocks whose centroid lies in `extent` are cut.
  bool limited = false;
  Box extent;
};

/// Settings shared by every cutting operation.
/// The default 'Minimum block volume' as a share of the starting brick's
/// volume: jointing leaves pieces this small only where a joint passes a
/// hair from a corner or edge, and one such sliver would set the stable
/// time step (eqs. 84, 87) of the whole model.
constexpr double relative_minimum_block_volume = 1e-7;

struct CuttingSettings
{
  /// Vertices closer to a cutting plane than this times the block size
  /// count as lying on it.
  double relative_tolerance = 1e-9;
  /// A cut that would leave a piece smaller than this (m^3) is not made; it
  /// is counted and reported instead.
  double minimum_volume = 0.0;
};

/// What happened while cutting: reported in the run summary.
struct CuttingReport
{
  unsigned long cuts = 0;            ///< successful plane cuts
  unsigned long skipped_slivers = 0; ///< cuts refused by the minimum volume
  double smallest_refused = 0.0;     ///< m^3, smallest piece refused
  Vec3 smallest_refused_at = Vec3::Zero();
};

/// One cutting operation as data: a joint set, a single plane (limited to
/// the blocks whose centroids lie in `extent` when `limited`), an
/// excavation, or a cut along a region kept for a later stage. Each acts
/// on every block alone, so a piece can be taken through all of them in
/// turn (BlockGenerator::cut_depth_first).
struct CutOperation
{
  enum class Kind
  {
    joint_set,
    plane,
    excavate,
    cut_along
  };
  Kind kind = Kind::plane;
  JointSetSpec set;     ///< joint_set
  Plane plane;          ///< plane
  bool limited = false; ///< plane: only blocks whose centroid lies in `extent`
  Box extent;
  ConvexRegion region; ///< excavate, cut_along
  int origin = 0;      ///< carried by the faces the cuts make

  static CutOperation joint_set(const JointSetSpec& set, int origin = 0);
  static CutOperation single_plane(const Plane& plane, const Box* extent = nullptr, int origin = 0);
  static CutOperation excavation(const ConvexRegion& region);
  static CutOperation along(const ConvexRegion& region);
};

/// What one operation did: its cuts and refused cuts (as CuttingReport), and
/// for an excavation the volume removed, for a cut along a region the
/// volume inside it (m^3).
struct OperationTally
{
  CuttingReport cutting;
  double volume = 0.0;
};

/// Builds a block model: a starting brick (or polyhedron) cut by joint sets
/// and single joints, with regions excavated. Only blocks that straddle a
/// plane are cut, so each operation costs time linear in the number of blocks.
class BlockGenerator
{
public:
  BlockGenerator(ConvexPolyhedron start, CuttingSettings settings);

  /// Cuts every block crossed by a joint of the set; the faces made carry
  /// `origin` (ConvexPolyhedron::face_origin).
  void cut_joint_set(const JointSetSpec& set, int origin = 0);

  /// Cuts every block crossed by one plane; with `extent`, only blocks whose
  /// centroid lies in it. The faces made carry `origin`.
  void cut_plane(const Plane& plane, const Box* extent = nullptr, int origin = 0);

  /// Removes the part of the model inside `region`; blocks crossing its
  /// boundary are cut so that exactly the region's volume goes. Returns the
  /// volume removed (m^3).
  double excavate(const ConvexRegion& region);
  /// Cuts the blocks that the boundary of `region` crosses along it, as
  /// excavate() does, and keeps every piece: a region to be removed later
  /// (a stage's excavation). Returns the volume of the pieces inside (m^3).
  double cut_along(const ConvexRegion& region);

  /// Applies one operation to every block; returns its volume (excavate()
  /// and cut_along(); 0 for the others).
  double apply(const CutOperation& op);

  /// Takes the generator's blocks (the starting polyhedron, or what earlier
  /// operations made of it) through `ops` one piece at a time, depth first,
  /// and hands each final block to `visit` with its number, holding no more
  /// than one branch of pieces: a rank that keeps only the blocks near its
  /// region needs memory for those alone (issue 24). Every operation acts
  /// on each piece alone and keeps its pieces in order, so the blocks,
  /// their numbers and each operation's tally (`tally`, one per operation)
  /// are those that apply() in turn gives, bit for bit: the pieces reach
  /// each operation in the same order, so its volumes are summed in the
  /// same order. The generator itself is left as it was.
  void cut_depth_first(const std::vector<CutOperation>& ops,
                       const std::function<void(unsigned long, ConvexPolyhedron&)>& visit,
                       std::vector<OperationTally>& tally) const;

  const std::vector<ConvexPolyhedron>& blocks() const { return blocks_; }
  std::vector<ConvexPolyhedron> take_blocks() { return std::move(blocks_); }
  const CuttingReport& report() const { return report_; }

private:
  double tolerance_for(const ConvexPolyhedron& block) const;
  /// The pieces `op` makes of `block`, appended to `out` in order; the cuts
  /// are counted in `report`, an excavation's or cut's volume added to
  /// `volume`.
  void cut_piece(const CutOperation& op, ConvexPolyhedron&& block,
                 std::vector<ConvexPolyhedron>& out, CuttingReport& report, double& volume) const;
  void cut_by_set(const JointSetSpec& set, int origin, ConvexPolyhedron&& block,
                  std::vector<ConvexPolyhedron>& out, CuttingReport& report) const;
  /// excavate() and cut_along(): the pieces inside are kept with `keep`.
  void split_by(const ConvexRegion& region, bool keep, ConvexPolyhedron&& block,
                std::vector<ConvexPolyhedron>& out, CuttingReport& report, double& volume) const;
  /// Cuts `block` by `plane`; false (block untouched) when the plane misses
  /// it or a piece would be below the minimum volume.
  /// The cap faces made carry `origin`.
  bool try_cut(const ConvexPolyhedron& block, const Plane& plane, ConvexPolyhedron& above,
               ConvexPolyhedron& below, int origin, CuttingReport& report) const;

  std::vector<ConvexPolyhedron> blocks_;
  CuttingSettings settings_;
  CuttingReport report_;
};

/// The operations' reports summed as applying them in turn sums them
/// (BlockGenerator::report() after those operations, from a new generator).
CuttingReport total_report(const std::vector<OperationTally>& tally);

} // namespace talus
