#pragma once

#include <talus/base/exact_sum.h>
#include <talus/model/block_model.h>
#include <talus/model/water_table.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

namespace talus
{

/// The water on one triangle: the resultant of the pressure, its first
/// moment, and the consistent shares of its corners.
struct TriangleWater
{
  double force = 0.0;               ///< integral of p dA, N
  Vec3 first_moment = Vec3::Zero(); ///< integral of p x dA, N m
  std::array<double, 3> corner{
      {0, 0, 0}}; ///< integral of N_k p dA (N_k: corner k's shape function), N
};

/// Adds to `out` the hydrostatic pressure p = gamma (z_w(x, y) - z), where
/// positive, over the triangle (a, b, c). The part below the surface is
/// clipped off exactly where z_w - z is linear over the triangle (a plane
/// surface); there p is linear and its integrals are closed-form. Under a
/// table the triangle is first divided into 4^L similar ones of edge at
/// most a quarter of the grid spacing (L at most 6); one wholly under
/// water takes a rule of degree 3 (exact where it lies in one grid cell),
/// one that the surface crosses is clipped with z_w - z taken linear
/// through its corners.
void integrate_water(const WaterTable& table, double gamma, const Vec3& a, const Vec3& b,
                     const Vec3& c, TriangleWater& out);

/// The water pressure (Pa) at point x: gamma (z_w - z), or 0 above the surface.
inline double water_pressure(const WaterTable& table, double gamma, const Vec3& x)
{
  return table.empty() ? 0.0 : gamma * std::max(0.0, table.height(x.x(), x.y()) - x.z());
}

/// The summary's line: "Water: <surface>, rho_w <density> kg/m^3, N faces
/// below it, water force on the free blocks (fx, fy, fz) N".
std::string water_summary(const WaterSpec& water, unsigned int faces_below, const Vec3& force);

/// Water pressure on every face of the rigid blocks `loaded[b] != 0` (the
/// free ones; fixed blocks need none) below the phreatic surface, taken
/// anew each step in the blocks' current geometry: the face turns and
/// moves with its block through the still water. Every face is loaded,
/// whether in contact or not: across a joint both faces carry the joint's
/// water pressure, which pushes the blocks apart, so that the joint's
/// springs carry only the effective normal force (see coulomb_slip.cc).
/// A face made by a joint set or joint with a pressure of its own
/// (WaterSpec::fixed_pressure) carries that pressure, uniform, instead.
/// The force's work counts as work of boundaries, as RigidFaceLoads'.
class WaterLoads
{
public:
  WaterLoads() = default;
  WaterLoads(const WaterSpec& water, double gravity, const std::vector<char>& loaded);

  bool empty() const { return block_.empty(); }

  /// Adds the water forces and their moments about each block's centroid
  /// (N, N m) in the blocks' current geometry to `force` and `moment`, and
  /// keeps them, with the velocity and spin before the motion, for account().
  void add(const BlockModel& blocks, std::vector<Vec3>& force, std::vector<Vec3>& moment,
           const std::vector<Vec3>& velocity, const std::vector<Vec3>& spin);
  /// As RigidFaceLoads::account.
  void account(const std::vector<Vec3>& velocity, const std::vector<Vec3>& spin, double h,
               double dt, ExactSum& boundary_work, ExactSum& kinetic) const;

  /// Of the last add(): faces with a part below the surface, and the sum of
  /// the water forces on the blocks (N).
  unsigned int faces_below() const { return faces_below_; }
  /// The blocks loaded (ascending) and the water force on each at the last
  /// add() (N): on ranks, for the summary's sum in the serial order.
  const std::vector<unsigned int>& blocks() const { return block_; }
  const std::vector<Vec3>& forces() const { return force_; }
  Vec3 total_force() const;

private:
  WaterSpec water_;
  double gamma_ = 0.0;           ///< rho_w g, N/m^3
  bool fixed_pressures_ = false; ///< some joint has a water pressure of its own
  std::vector<unsigned int> block_;
  std::vector<Vec3> force_, moment_, velocity_before_, spin_before_;
  unsigned int faces_below_ = 0;
};

} // namespace talus
