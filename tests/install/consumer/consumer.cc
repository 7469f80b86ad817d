// Uses the installed talus library: cuts a brick by one joint and prints
// the blocks' volumes (0.25 and 0.75 m^3).
#include <talus/geometry/convex_polyhedron.h>
#include <talus/geometry/plane_cut.h>

#include <cstdio>

int main()
{
  using namespace talus;
  const ConvexPolyhedron brick = ConvexPolyhedron::box(Vec3(0, 0, 0), Vec3(1, 1, 1));
  const PlaneCut cut = cut_by_plane(brick, Plane(Vec3(0, 0, 1), 0.25), 1e-9);
  std::printf("installed talus: pieces of %g and %g m^3\n", cut.below.volume(),
              cut.above.volume());
}
