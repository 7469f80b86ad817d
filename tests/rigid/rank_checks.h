#pragma once

// Shared by the tests of a rigid model split among ranks: the comparison of
// a rank's blocks with the serial run's, bit for bit.

#include <talus/contact/block_decomposition.h>
#include <talus/model/block_model.h>
#include <talus/solver/rigid_solver.h>

#include <cstring>

namespace talus_test
{

inline bool same_bits(const talus::Vec3& a, const talus::Vec3& b)
{
  return std::memcmp(a.data(), b.data(), 3 * sizeof(double)) == 0;
}

inline bool same_bits(double a, double b)
{
  return std::memcmp(&a, &b, sizeof(double)) == 0;
}

/// Whether local block i of a rank (`solver` on `local`) has the velocity,
/// spin, centroid and vertices of global block g of the serial run
/// (`serial` on `whole`), bit for bit.
inline bool same_block(const talus::RigidSolver& solver, const talus::BlockModel& local,
                       unsigned int i, const talus::RigidSolver& serial,
                       const talus::BlockModel& whole, unsigned int g)
{
  bool same = same_bits(solver.velocity[i], serial.velocity[g]) &&
              same_bits(solver.spin[i], serial.spin[g]) &&
              same_bits(local.centroid[i], whole.centroid[g]);
  for (unsigned int v = 0; v < local.vertex_start[i + 1] - local.vertex_start[i]; ++v)
    same &=
        same_bits(local.vertex[local.vertex_start[i] + v], whole.vertex[whole.vertex_start[g] + v]);
  return same;
}

} // namespace talus_test
