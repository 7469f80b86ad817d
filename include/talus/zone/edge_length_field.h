#pragma once

#include <talus/geometry/region.h>

#include <algorithm>
#include <vector>

namespace talus
{

/// The target zone edge length over the model (m): `coarse` everywhere, or
/// graded from `fine` at the regions it is refined around (excavations, or
/// a box) up to `coarse` at `distance` from them, linearly in between, so
/// that a model is fine only where the stresses change quickly.
struct EdgeLengthField
{
  EdgeLengthField() = default;
  /// Uniform: `h` everywhere (m).
  EdgeLengthField(double h) : coarse(h) {}

  double coarse = 1.0;            ///< m, away from the regions
  double fine = 0.0;              ///< m, at the regions (0: no grading)
  double distance = 0.0;          ///< m, over which the length grows to `coarse`
  std::vector<ConvexRegion> near; ///< refined around these

  bool graded() const { return fine > 0.0 && fine < coarse && !near.empty(); }

  /// Edge length at x (m).
  double at(const Vec3& x) const
  {
    if (!graded())
      return coarse;
    double d = 1e300;
    for (const ConvexRegion& r : near)
    {
      // The largest signed distance to the region's planes: 0 inside, the
      // true distance off a face, a little less off an edge or corner.
      double outside = 0.0;
      for (const Plane& p : r.planes)
        outside = std::max(outside, p.signed_distance(x));
      d = std::min(d, outside);
    }
    if (d >= distance)
      return d > 0.0 ? coarse : fine;
    return fine + (coarse - fine) * d / distance;
  }

  /// The smallest edge length anywhere (m).
  double smallest() const { return graded() ? fine : coarse; }
};

} // namespace talus
