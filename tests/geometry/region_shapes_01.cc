// The regions of excavations and groups against their closed forms:
// 1. a half-space within a 10 m cube: the half above z = 5 (500 m^3), and
//    the part above the plane x + z = 10 (a 45 degree slope: 500 m^3);
// 2. a polyhedron of four planes: the corner x + y + z <= 3 (4.5 m^3);
// 3. a prism of a regular hexagon (circumradius 2 m) along a skew axis of
//    length 10 m: 3 sqrt(3) / 2 x 4 x 10 m^3, the same clockwise and
//    counter-clockwise, and which points it holds;
// 4. profiles that are no convex polygon are refused.

#include <talus/geometry/region.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "../tests.h"

using namespace talus;

int main()
{
  const Box cube{Vec3(0, 0, 0), Vec3(10, 10, 10)};
  const ConvexRegion upper = ConvexRegion::half_space(Vec3(0, 0, 5), Vec3(0, 0, 1), cube);
  talus_test::check_within("1. upper half (m^3)", upper.volume, 500.0, 1e-12);
  talus_test::check_within("   its lowest z (m)", upper.bounds.lo.z(), 5.0, 1e-12);
  std::printf("   holds (5, 5, 6), not (5, 5, 4): %s\n",
              talus_test::verdict(upper.contains(Vec3(5, 5, 6)) && !upper.contains(Vec3(5, 5, 4))));
  const ConvexRegion slope = ConvexRegion::half_space(Vec3(10, 0, 0), Vec3(1, 0, 1), cube);
  talus_test::check_within("   above x + z = 10 (m^3)", slope.volume, 500.0, 1e-12);

  const ConvexRegion corner = ConvexRegion::polyhedron({{Vec3(3, 0, 0), Vec3(1, 1, 1)},
                                                        {Vec3(0, 0, 0), Vec3(-1, 0, 0)},
                                                        {Vec3(0, 0, 0), Vec3(0, -1, 0)},
                                                        {Vec3(0, 0, 0), Vec3(0, 0, -1)}},
                                                       cube);
  talus_test::check_within("2. corner x + y + z <= 3 (m^3)", corner.volume, 4.5, 1e-12);

  std::vector<std::pair<double, double>> hexagon;
  for (int k = 0; k < 6; ++k)
    hexagon.emplace_back(2 * std::cos(k * M_PI / 3), 2 * std::sin(k * M_PI / 3));
  const Vec3 a(1, 2, 3), axis = Vec3(1, 2, 2) / 3.0, b = a + 10.0 * axis;
  const ConvexRegion prism = ConvexRegion::prism(a, b, hexagon);
  const std::vector<std::pair<double, double>> clockwise(hexagon.rbegin(), hexagon.rend());
  const ConvexRegion same = ConvexRegion::prism(a, b, clockwise);
  talus_test::check_within("3. hexagonal prism (m^3)", prism.volume, 1.5 * std::sqrt(3.0) * 4 * 10,
                           1e-12);
  talus_test::check_within("   given clockwise (m^3)", same.volume, prism.volume, 1e-12);
  // On the axis, inside; 1.9 m off it along the corner direction (u),
  // inside; 1.9 m along the edge-centre direction (v; apothem sqrt(3)), out.
  const Vec3 up = (Vec3::UnitZ() - axis.z() * axis).normalized(), right = axis.cross(up);
  const Vec3 mid = a + 5.0 * axis;
  const bool holds = prism.contains(mid) && prism.contains(mid + 1.9 * right) &&
                     !prism.contains(mid + 1.9 * up) && same.contains(mid + 1.9 * right) &&
                     !same.contains(mid + 1.9 * up) && !prism.contains(a - 0.1 * axis);
  std::printf("   holds the axis and 1.9 m towards a corner, not 1.9 m towards an edge's "
              "middle nor beyond an end: %s\n",
              talus_test::verdict(holds));

  unsigned int refused = 0;
  for (const auto& profile :
       {std::vector<std::pair<double, double>>{{0, 0}, {2, 0}, {1, 0.5}, {2, 2}, {0, 2}},
        std::vector<std::pair<double, double>>{{0, 0}, {1, 1}},
        std::vector<std::pair<double, double>>{{0, 0}, {1, 1}, {2, 2}}})
    try
    {
      ConvexRegion::prism(a, b, profile);
    }
    catch (const std::invalid_argument& e)
    {
      std::printf("   refused: the polygon %s\n", e.what());
      ++refused;
    }
  std::printf("4. a notched, a two-cornered and a flat profile refused: %s\n",
              talus_test::verdict(refused == 3));

  // 5. A sphere of radius 2 about (5, 5, 5) by tangent planes: never inside
  // the sphere (every point within it is held), its volume above the
  // sphere's and falling towards it as the facets grow (the excess of a
  // circumscribed polyhedron of n about equal facets goes as 1/n).
  const Box brick{Vec3(0, 0, 0), Vec3(10, 10, 10)};
  const Vec3 c(5, 5, 5);
  const double ball = 4.0 / 3.0 * M_PI * 8.0;
  double last_excess = 1.0;
  bool falling = true, holds_ball = true;
  for (const unsigned int facets : {48u, 192u, 768u})
  {
    const ConvexRegion s = ConvexRegion::sphere(c, 2.0, facets, brick);
    const double excess = s.volume / ball - 1.0;
    std::fprintf(stderr, "sphere of %u facets: volume %.6g m^3, %.3g above the sphere's\n", facets,
                 s.volume, excess);
    falling &= excess > 0.0 && excess < last_excess;
    last_excess = excess;
    for (int k = 0; k < 2000 && holds_ball; ++k)
    {
      // Points just inside the sphere in every direction.
      const double z = 1.0 - (2.0 * k + 1.0) / 2000, rho = std::sqrt(1.0 - z * z);
      const Vec3 d(rho * std::cos(2.4 * k), rho * std::sin(2.4 * k), z);
      holds_ball &= s.contains(c + 1.999 * d);
    }
    holds_ball &= !s.contains(c + Vec3(2.2, 0, 0)) && !s.contains(c - Vec3(0, 0, 2.0 * 1.1));
  }
  std::printf("5. sphere by tangent planes: holds the ball, not beyond 1.1 r: %s; volume above the "
              "ball's and falling with the facets (48, 192, 768): %s; at 768 facets within 1 %%: "
              "%s\n",
              talus_test::verdict(holds_ball), talus_test::verdict(falling),
              talus_test::verdict(last_excess < 0.01));
}
