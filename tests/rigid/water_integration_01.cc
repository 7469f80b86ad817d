// The water pressure over one triangle (integrate_water) against closed
// forms, gamma = 1:
// 1. a vertical triangle (0,0,0), (1,0,0), (0,0,1) wholly under a level
//    z_w = 2: the force A (z_w - z_c) = 5/6, its first moment, and the
//    consistent corner shares A/12 (d_k + sum d) = (7, 7, 6)/24;
// 2. the same triangle cut by a level z_w = 0.5: the integral of
//    (0.5 - z)(1 - z) over 0 < z < 0.5, 5/48, and the point of action;
// 3. the same triangle above a level z_w = -0.1: nothing;
// 4. a horizontal triangle (0,0,-1), (1,0,-1), (0,1,-1) under the table
//    z_w = x y (heights 0, 0, 0, 1 on the unit grid, bilinear): the
//    integral of (1 + x y), 1/2 + 1/24, and its first moment in x, 11/60
//    (a linear clip would miss the twist x y by 1.2e-3; the rule of degree
//    3 on each piece is exact in a grid cell);
// 5. the same on a grid of four cells (the pieces lie in one cell each).

#include <talus/solver/water_loads.h>

#include <cmath>
#include <cstdio>

#include "../tests.h"

using namespace talus;

int main()
{
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 0, 1);
  {
    TriangleWater w;
    integrate_water(WaterTable::level(2.0), 1.0, a, b, c, w);
    talus_test::check_within("1. force (N)", w.force, 5.0 / 6.0, 1e-14);
    // First moment: the integral of (2 - z) x; by z: A/12 (sum d_i z_i + sum d sum z).
    talus_test::check_within("1. first moment, z (N m)", w.first_moment.z(), 0.5 / 12 * (1 + 5),
                             1e-14);
    talus_test::check_within("1. corner share of (0,0,1) (N)", w.corner[2], 6.0 / 24.0, 1e-14);
    talus_test::check_within("1. corner share of (0,0,0) (N)", w.corner[0], 7.0 / 24.0, 1e-14);
  }
  {
    TriangleWater w;
    integrate_water(WaterTable::level(0.5), 1.0, a, b, c, w);
    talus_test::check_within("2. force, the wet part only (N)", w.force, 5.0 / 48.0, 1e-14);
    // The centre of pressure's height: the integral of (0.5 - z)(1 - z) z
    // over 0 < z < 0.5, 1/64, over the force.
    talus_test::check_within("2. centre of pressure, z (m)", w.first_moment.z() / w.force,
                             (1.0 / 64.0) / (5.0 / 48.0), 1e-13);
    talus_test::check_within("2. corner shares sum to the force (N)",
                             w.corner[0] + w.corner[1] + w.corner[2], w.force, 1e-14);
  }
  {
    TriangleWater w;
    integrate_water(WaterTable::level(-0.1), 1.0, a, b, c, w);
    std::printf("3. above the surface: %s\n", talus_test::verdict(w.force == 0.0));
  }
  {
    TriangleWater w;
    const WaterTable xy = WaterTable::grid({0, 1}, {0, 1}, {0, 0, 0, 1});
    integrate_water(xy, 1.0, Vec3(0, 0, -1), Vec3(1, 0, -1), Vec3(0, 1, -1), w);
    talus_test::check_within("4. force under a bilinear table (N)", w.force, 0.5 + 1.0 / 24.0,
                             1e-14);
    talus_test::check_within("4. first moment, x (N m)", w.first_moment.x(), 11.0 / 60.0, 1e-14);
    talus_test::check_within("4. corner shares sum to the force (N)",
                             w.corner[0] + w.corner[1] + w.corner[2], w.force, 1e-14);
    std::printf("4. table height at (0.5, 0.25): %s\n",
                talus_test::verdict(std::abs(xy.height(0.5, 0.25) - 0.125) < 1e-15));
    std::printf("4. clamped outside the grid, at (2, 3): %s\n",
                talus_test::verdict(xy.height(2, 3) == 1.0));
  }
  {
    // 5. The same surface on a 3 x 3 grid (x y is bilinear in each cell).
    TriangleWater w;
    const WaterTable xy =
        WaterTable::grid({0, 0.5, 1}, {0, 0.5, 1}, {0, 0, 0, 0, 0.25, 0.5, 0, 0.5, 1});
    integrate_water(xy, 1.0, Vec3(0, 0, -1), Vec3(1, 0, -1), Vec3(0, 1, -1), w);
    talus_test::check_within("5. force, four grid cells (N)", w.force, 0.5 + 1.0 / 24.0, 1e-13);
  }
}
