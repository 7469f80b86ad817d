#pragma once

#include <talus/base/exact_sum.h>
#include <talus/geometry/plane.h>
#include <talus/geometry/region.h>
#include <talus/model/block_model.h>
#include <talus/model/time_history.h>
#include <talus/model/wave_signal.h>

#include <array>
#include <vector>

namespace talus
{

/// A load on the boundary faces in a region ('Boundary N' with a pressure
/// or traction condition): a normal pressure (Pa, positive pushing into the
/// block) and a traction (Pa, a force per unit area in global axes). Zones
/// of deformable blocks take it on their boundary faces whose centroid lies
/// in the region; rigid blocks on the part of each face inside a box, or
/// on each face wholly inside a region of another shape (RigidFaceLoads).
struct FacePressure
{
  ConvexRegion region;
  double pressure = 0.0;
  Vec3 traction = Vec3::Zero();
  /// 'Condition = quiet' (dynamic runs, zone faces only): viscous
  /// dashpots on the faces (Lysmer and Kuhlemeyer), and `wave`, the
  /// stress of an incident wave put in through them; pressure and
  /// traction are then zero. Rigid blocks take nothing of it.
  bool quiet = false;
  WaveSignal wave;
  /// The unit direction of the incident wave's traction on the faces (a
  /// direction along them makes a shear wave); zero: their inward normal.
  Vec3 wave_direction = Vec3::Zero();
  /// Both in model time t: times motion.scale(t); none: constant.
  TimeFunction motion;
};

/// The part of a rigid block's face inside a region, tied to the face so
/// that it moves and turns with the block: its area (which a rigid motion
/// keeps) and its centroid as an affine combination of three of the face's
/// vertices, x0 + alpha (x1 - x0) + beta (x2 - x0).
struct FacePatch
{
  unsigned int block = 0, face = 0;
  std::array<unsigned int, 3> corner{}; ///< global vertex numbers x0, x1, x2
  double alpha = 0.0, beta = 0.0;
  double area = 0.0; ///< m^2
};

/// The parts of the faces of blocks `rigid[b] != 0` that lie in `region`,
/// those of positive area only. A box clips each face polygon; across its
/// thinnest extent only faces that lie wholly within it count, so that a
/// thin box around a face (or a band of it) takes no strips of the faces
/// that meet it at its edges. A region of another shape takes the faces
/// that lie wholly inside it (to 1e-9 of its size), whole: the faces on
/// an excavation's boundary, say, with a region a little larger than it,
/// and none of the faces that leave it.
std::vector<FacePatch> face_patches_in(const BlockModel& blocks, const std::vector<char>& rigid,
                                       const ConvexRegion& region);

/// Pressures and tractions on the faces of rigid blocks: each region loads
/// the part of every face inside it at the start, with -p A n + t A (n the
/// face's outward normal now) at that part's centroid, so that the block
/// takes a force and the moment of it about its centroid; the load turns
/// with the face. Where regions overlap on a face, both loads act there.
/// The loads' work counts as work of boundaries in the energy account,
/// as the constant forces of 'Load N' do.
class RigidFaceLoads
{
public:
  RigidFaceLoads() = default;
  RigidFaceLoads(const BlockModel& blocks, const std::vector<char>& rigid,
                 const std::vector<FacePressure>& loads);
  /// The same from the parts each load selects (`patches`, one list per
  /// load; a quiet load's is not used).
  RigidFaceLoads(const std::vector<std::vector<FacePatch>>& patches,
                 const std::vector<FacePressure>& loads);

  bool empty() const { return patch_.empty(); }

  /// A model split among ranks (issue 24): these loads, selected on the
  /// whole model `blocks`, with each patch's face and corners counted from
  /// its block's first face and vertex, so that they hold on any copy of
  /// the block however the blocks are numbered (a table every rank keeps).
  RigidFaceLoads relative_to(const BlockModel& blocks) const;
  /// From a table of relative_to: the loads of the blocks a rank holds in
  /// `model`, whose global numbers are `global_of_local` (ascending), those
  /// with `take[i]` only (the blocks it owns: ghosts move with their
  /// owners), in the order of the table, so that each block's force is
  /// summed as on one rank.
  RigidFaceLoads localized(const BlockModel& model,
                           const std::vector<unsigned int>& global_of_local,
                           const std::vector<char>& take) const;
  unsigned int n_patches() const { return static_cast<unsigned int>(patch_.size()); }

  /// Adds the loads in the blocks' current geometry to `force` and
  /// `moment` (N, N m about each block's centroid) and keeps them, with
  /// each loaded block's velocity and spin before its motion, for
  /// account().
  /// `time`: the model time, for loads that vary in it.
  void add(const BlockModel& blocks, std::vector<Vec3>& force, std::vector<Vec3>& moment,
           const std::vector<Vec3>& velocity, const std::vector<Vec3>& spin, double time = 0.0);

  /// After the motion of a step (`h`: the velocity update's time span,
  /// `dt` the step): adds the loads' work, F . reach + M . turn over the
  /// mean of the half-step velocities on either side (as for 'Load N'), to
  /// `boundary_work`, and to `kinetic` the half of F . dx + M . dtheta that
  /// the kinetic term took off with the contact forces (it is not a
  /// contact force). Blocks that are `fixed` take no work.
  void account(const std::vector<char>& fixed, const std::vector<Vec3>& velocity,
               const std::vector<Vec3>& spin, double h, double dt, ExactSum& boundary_work,
               ExactSum& kinetic) const;

private:
  struct Load
  {
    FacePatch patch;
    unsigned int slot; ///< its block's place in loaded_block_
    double pressure;
    Vec3 traction;
    int function; ///< its place in functions_ (-1: constant)
  };
  std::vector<Load> patch_;
  std::vector<TimeFunction> functions_;    ///< of the loads that vary in time
  std::vector<double> scale_;              ///< each one's factor at this step
  std::vector<unsigned int> loaded_block_; ///< blocks with a load, each once
  /// Per loaded block, this step: force, moment, velocity and spin before.
  std::vector<Vec3> force_, moment_, velocity_before_, spin_before_;
};

} // namespace talus
