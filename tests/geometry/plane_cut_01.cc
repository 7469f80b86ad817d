// Cutting a unit cube by planes: oblique cuts conserve volume and give convex
// pieces with the exact closed-form volumes; planes through vertices, edges
// and faces, or within the tolerance of them, do not create slivers.

#include <talus/geometry/plane_cut.h>

#include "../tests.h"

using namespace talus;

void cut_and_report(const std::string& name, const Plane& plane, double expected_below)
{
  const ConvexPolyhedron cube = ConvexPolyhedron::box(Vec3(0, 0, 0), Vec3(1, 1, 1));
  const PlaneCut cut = cut_by_plane(cube, plane, 1e-9);
  std::printf("%s: intersects %s\n", name.c_str(), cut.intersects ? "yes" : "no");
  if (!cut.intersects)
    return;
  cut.above.validate(name + " piece above");
  cut.below.validate(name + " piece below");
  std::printf("%s: pieces have %u and %u faces, %u and %u vertices\n", name.c_str(),
              cut.above.n_faces(), cut.below.n_faces(), cut.above.n_vertices(),
              cut.below.n_vertices());
  talus_test::check(name + " volume sum", cut.above.volume() + cut.below.volume(), 1.0, 1e-14);
  talus_test::check(name + " volume below", cut.below.volume(), expected_below, 1e-13);
  // Every vertex of each piece lies on its side of the plane.
  double worst = 0.0;
  for (const Vec3& v : cut.above.vertices())
    worst = std::max(worst, -plane.signed_distance(v));
  for (const Vec3& v : cut.below.vertices())
    worst = std::max(worst, plane.signed_distance(v));
  std::printf("%s: vertices on the wrong side: %s\n", name.c_str(), worst <= 1e-12 ? "none" : "SOME");
}

int main()
{
  const Vec3 diag = Vec3(1, 1, 1).normalized();
  // x + y + z = 1.5 halves the cube through a regular hexagon.
  cut_and_report("hexagonal cut", Plane(diag, 1.5 / std::sqrt(3.0)), 0.5);
  // x + y + z = 0.5 cuts off a corner tetrahedron of volume 0.5^3 / 6.
  cut_and_report("corner cut", Plane(diag, 0.5 / std::sqrt(3.0)), 0.125 / 6.0);
  // A general oblique plane through the centre, by symmetry halving the cube.
  cut_and_report("oblique through centre", Plane::through(Vec3(0.5, 0.5, 0.5), Vec3(0.3, -0.7, 0.2)),
                 0.5);
  // z = 0.3 + 0.2 x: a trapezoidal prism of volume 0.3 + 0.1 below.
  cut_and_report("inclined", Plane::through(Vec3(0, 0, 0.3), Vec3(-0.2, 0, 1)), 0.4);
  // x + y = 1 passes through two vertical edges: two triangular prisms.
  cut_and_report("through edges", Plane(Vec3(1, 1, 0).normalized(), 1 / std::sqrt(2.0)), 0.5);
  // x + y + z = 1 passes through three vertices: a tetrahedron of 1/6.
  cut_and_report("through vertices", Plane(diag, 1 / std::sqrt(3.0)), 1.0 / 6.0);
  // Planes that only touch the cube, or pass within the tolerance.
  cut_and_report("on a face", Plane(Vec3(1, 0, 0), 0.0), 0.0);
  cut_and_report("within tolerance of a face", Plane(Vec3(1, 0, 0), 1e-12), 0.0);
  cut_and_report("through one vertex only", Plane(diag, 0.0), 0.0);
  cut_and_report("missing the cube", Plane(Vec3(0, 0, 1), 2.0), 0.0);
}
