// Excavations remove exactly their volume: a 16-sided tunnel through a
// jointed 10 m cube (prism area 8 r^2 sin(pi/8) cos(pi/8) ... = 0.5 n r^2
// sin(2 pi / n) times length) and a box that cuts across joint blocks.

#include <talus/geometry/block_generator.h>

#include "../tests.h"

using namespace talus;

BlockGenerator jointed_cube()
{
  BlockGenerator g(ConvexPolyhedron::box(Vec3(0, 0, 0), Vec3(10, 10, 10)), {});
  g.cut_joint_set({0.0, 0.0, 1.0, Vec3(0, 0, 0), 0, false, {}});
  g.cut_joint_set({90.0, 0.0, 1.0, Vec3(0, 0, 0), 0, false, {}});
  g.cut_joint_set({90.0, 90.0, 1.0, Vec3(0, 0, 0), 0, false, {}});
  return g;
}

double total(const BlockGenerator& g)
{
  double sum = 0.0;
  for (const ConvexPolyhedron& b : g.blocks())
  {
    b.validate("block");
    sum += b.volume();
  }
  return sum;
}

int main()
{
  {
    BlockGenerator g = jointed_cube();
    const ConvexRegion tunnel = ConvexRegion::cylinder(Vec3(5.2, 0, 4.9), Vec3(5.2, 10, 4.9), 3.0, 16);
    const double exact = 0.5 * 16 * 9.0 * std::sin(2 * M_PI / 16) * 10.0;
    const double removed = g.excavate(tunnel);
    talus_test::check("tunnel region volume", tunnel.volume, exact, 1e-14);
    talus_test::check("tunnel volume removed", removed, exact, 1e-12);
    talus_test::check("volume left", total(g), 1000.0 - exact, 1e-12);
    std::printf("tunnel: %zu blocks left\n", g.blocks().size());
    // No block centroid is left inside the tunnel.
    unsigned int inside = 0;
    for (const ConvexPolyhedron& b : g.blocks())
      inside += tunnel.contains(b.vertex_mean(), -1e-9);
    std::printf("tunnel: %u blocks inside the excavation\n", inside);
  }
  {
    BlockGenerator g = jointed_cube();
    const double removed = g.excavate(ConvexRegion::box({Vec3(2.5, 3.25, -1), Vec3(6.5, 7.0, 4.4)}));
    const double exact = 4.0 * 3.75 * 4.4;
    talus_test::check("box volume removed", removed, exact, 1e-12);
    talus_test::check("volume left", total(g), 1000.0 - exact, 1e-12);
    std::printf("box: %zu blocks left\n", g.blocks().size());
  }
}
