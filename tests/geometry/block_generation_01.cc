// A 10 x 10 x 10 brick cut by three orthogonal joint sets of spacing 1 gives
// 1000 unit cubes; an oblique set crossed by a vertical one gives the
// product of their slab counts; three oblique sets conserve volume and give
// exactly one block per non-empty joint cell.

#include <talus/geometry/block_generator.h>
#include <talus/geometry/mass_properties.h>

#include <set>
#include <tuple>

#include "../tests.h"

using namespace talus;

int main()
{
  {
    BlockGenerator g(ConvexPolyhedron::box(Vec3(0, 0, 0), Vec3(10, 10, 10)), {});
    g.cut_joint_set({0.0, 0.0, 1.0, Vec3(0, 0, 0), 0, false, {}});  // horizontal
    g.cut_joint_set({90.0, 0.0, 1.0, Vec3(0, 0, 0), 0, false, {}}); // normal +y
    g.cut_joint_set({90.0, 90.0, 1.0, Vec3(0, 0, 0), 0, false, {}}); // normal +x
    std::printf("orthogonal sets: %zu blocks\n", g.blocks().size());
    double worst = 0.0, total = 0.0;
    unsigned int cubes = 0;
    for (const ConvexPolyhedron& b : g.blocks())
    {
      b.validate("block");
      worst = std::max(worst, std::abs(b.volume() - 1.0));
      total += b.volume();
      cubes += (b.n_faces() == 6 && b.n_vertices() == 8);
    }
    std::printf("orthogonal sets: %u blocks are hexahedra, largest |volume - 1| %s 1e-12\n", cubes,
                worst < 1e-12 ? "<" : ">=");
    talus_test::check("orthogonal sets total volume", total, 1000.0, 1e-13);
  }
  {
    // Set 1: dip 30 towards east, normal (0.5, 0, cos 30); over the brick
    // n.x runs from 0 to 5 + 10 cos 30 = 13.66, so joints at 1.5 k, k = 1..9,
    // leave 10 slabs. Set 2: vertical, normal +y, spacing 2: 5 slabs.
    BlockGenerator g(ConvexPolyhedron::box(Vec3(0, 0, 0), Vec3(10, 10, 10)), {});
    g.cut_joint_set({30.0, 90.0, 1.5, Vec3(0, 0, 0), 0, false, {}});
    g.cut_joint_set({90.0, 0.0, 2.0, Vec3(0, 0, 0), 0, false, {}});
    std::printf("oblique x vertical: %zu blocks (expected 10 x 5 = 50)\n", g.blocks().size());
    double total = 0.0;
    for (const ConvexPolyhedron& b : g.blocks())
      total += b.volume();
    talus_test::check("oblique x vertical total volume", total, 1000.0, 1e-13);
  }
  {
    // Three oblique sets: every block must lie in one joint cell of each set,
    // and no two blocks may share a cell (cells are convex, so each non-empty
    // cell inside the brick is exactly one block).
    const JointSetSpec sets[] = {{20.0, 45.0, 1.3, Vec3(0.1, 0.2, 0.3), 0, false, {}},
                                 {70.0, 150.0, 1.7, Vec3(0, 0, 0), 0, false, {}},
                                 {85.0, 260.0, 2.1, Vec3(0.5, 0, 0), 0, false, {}}};
    BlockGenerator g(ConvexPolyhedron::box(Vec3(0, 0, 0), Vec3(8, 9, 10)), {});
    for (const auto& s : sets)
      g.cut_joint_set(s);
    std::set<std::tuple<long, long, long>> cells;
    unsigned int straddling = 0;
    double total = 0.0;
    for (const ConvexPolyhedron& b : g.blocks())
    {
      b.validate("oblique block");
      total += b.volume();
      long k[3];
      for (int s = 0; s < 3; ++s)
      {
        const Plane ref = Plane::through(sets[s].origin, normal_from_dip(sets[s].dip, sets[s].dip_direction));
        const Vec3 c = compute_mass_properties(b).centroid;
        k[s] = static_cast<long>(std::floor(ref.signed_distance(c) / sets[s].spacing));
        const auto [lo, hi] = b.extent_along(ref);
        straddling += (lo < k[s] * sets[s].spacing - 1e-9 || hi > (k[s] + 1) * sets[s].spacing + 1e-9);
      }
      cells.insert({k[0], k[1], k[2]});
    }
    std::printf("three oblique sets: %zu blocks, %zu distinct joint cells, %u blocks crossing a joint\n",
                g.blocks().size(), cells.size(), straddling);
    talus_test::check("three oblique sets total volume", total, 720.0, 1e-12);
  }
}
