// A unit cube B standing on a corner (its body diagonal vertical), its lowest
// vertex a known height g above
//   1. the top face of a large box A: vertex-face (also with A and B swapped),
//   2. the top edge of a cube A turned 45 degrees about x: vertex-edge,
//   3. the top vertex of a cube A standing on its corner: vertex-vertex,
//      here with B's vertex off to the side so that the normal is the
//      (tilted) vertex-to-vertex direction.
// Checks normal, gap, reference point (eq. 9: on the lower-dimensional
// feature, or midway between two vertices) and type; then an existing
// contact after B comes closer; then the whole of Table 1.

#include <talus/contact/common_plane.h>
#include <talus/geometry/convex_polyhedron.h>

#include <Eigen/Geometry>

#include "../tests.h"

using namespace talus;

namespace
{

std::vector<Vec3> cube(const Eigen::Matrix3d& R, const Vec3& centre)
{
  const ConvexPolyhedron box = ConvexPolyhedron::box(Vec3(-0.5, -0.5, -0.5), Vec3(0.5, 0.5, 0.5));
  std::vector<Vec3> v;
  for (const Vec3& x : box.vertices())
    v.push_back(R * x + centre);
  return v;
}

Vec3 mean(const std::vector<Vec3>& v)
{
  Vec3 m = Vec3::Zero();
  for (const Vec3& x : v)
    m += x;
  return m / v.size();
}

double angle(const Vec3& a, const Vec3& b)
{
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

void check_case(const std::string& name, const std::vector<Vec3>& a, const std::vector<Vec3>& b,
                const Vec3& normal, double gap, const Vec3& reference, ContactType type)
{
  const CommonPlaneSettings settings;
  CommonPlane cp = initial_common_plane(mean(a), mean(b));
  const CommonPlaneResult r =
      update_common_plane(cp, a.data(), a.size(), b.data(), b.size(), settings, true);
  talus_test::check(name + ": normal angle error (rad)", angle(cp.normal, normal), 0.0, 1e-9);
  talus_test::check(name + ": gap", r.gap, gap, 1e-9);
  talus_test::check(name + ": reference point error", (cp.reference - reference).norm(), 0.0, 1e-9);
  std::printf("%s: type %s (exact %s) %s, touching %u + %u, iterations <= 60: %s\n", name.c_str(),
              to_string(r.type), to_string(type), r.type == type ? "OK" : "WRONG", r.n_touching_a,
              r.n_touching_b, r.iterations <= 60 ? "OK" : "WRONG");

  // Existing contact: B comes 0.01 closer along the normal.
  std::vector<Vec3> b2 = b;
  for (Vec3& x : b2)
    x -= 0.01 * normal;
  const CommonPlaneResult r2 =
      update_common_plane(cp, a.data(), a.size(), b2.data(), b2.size(), settings, false);
  talus_test::check(name + ", B closer by 0.01: normal angle error (rad)", angle(cp.normal, normal),
                    0.0, 1e-9);
  talus_test::check(name + ", B closer by 0.01: gap", r2.gap, gap - 0.01, 1e-9);
  std::printf("%s, B closer by 0.01: type %s, iterations %u, scans %u\n", name.c_str(),
              to_string(r2.type), r2.iterations, r2.evaluations);
}

} // namespace

int main()
{
  const double s2 = std::sqrt(2.0), s3 = std::sqrt(3.0);
  // Turns the body diagonal (1, 1, 1) of a cube to point down (corner down)
  // or up (corner up); a cube's vertex is then sqrt(3)/2 from its centre.
  const Eigen::Matrix3d corner_down =
      Eigen::Quaterniond::FromTwoVectors(Vec3(1, 1, 1), Vec3(0, 0, -1)).toRotationMatrix();
  const Eigen::Matrix3d corner_up =
      Eigen::Quaterniond::FromTwoVectors(Vec3(1, 1, 1), Vec3(0, 0, 1)).toRotationMatrix();
  const double g = 0.04;

  {
    const ConvexPolyhedron slab = ConvexPolyhedron::box(Vec3(-2, -2, -1), Vec3(2, 2, 0));
    const std::vector<Vec3> a = slab.vertices();
    const std::vector<Vec3> b = cube(corner_down, Vec3(0.3, -0.2, 0.5 * s3 + g));
    check_case("vertex on face", a, b, Vec3::UnitZ(), g, Vec3(0.3, -0.2, 0.5 * g),
               ContactType::vertex_face);
    // The same with the roles of A and B swapped: the normal turns round.
    check_case("face under vertex", b, a, -Vec3::UnitZ(), g, Vec3(0.3, -0.2, 0.5 * g),
               ContactType::vertex_face);
  }
  {
    const std::vector<Vec3> a =
        cube(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitX()).toRotationMatrix(), Vec3::Zero());
    const std::vector<Vec3> b = cube(corner_down, Vec3(0.1, 0.0, 0.5 * s2 + 0.5 * s3 + g));
    check_case("vertex on edge", a, b, Vec3::UnitZ(), g, Vec3(0.1, 0.0, 0.5 * s2 + 0.5 * g),
               ContactType::vertex_edge);
  }
  {
    // Top vertex of A at (0, 0, sqrt(3)/2), bottom vertex of B at that point
    // plus d = (0.02, -0.01, 0.1): the normal is d / |d| (12.6 degrees from
    // vertical, inside both vertices' normal cones, which reach at least
    // 35 degrees from the diagonal), the gap |d| = sqrt(0.0105).
    const Vec3 d(0.02, -0.01, 0.1);
    const Vec3 top(0, 0, 0.5 * s3);
    const std::vector<Vec3> a = cube(corner_up, Vec3::Zero());
    const std::vector<Vec3> b = cube(corner_down, top + d + Vec3(0, 0, 0.5 * s3));
    check_case("vertex on vertex", a, b, d.normalized(), d.norm(), top + 0.5 * d,
               ContactType::vertex_vertex);
  }

  // Table 1: touching vertices of A and B -> contact type.
  for (unsigned int n_a = 0; n_a <= 4; ++n_a)
  {
    std::printf("table 1, touching vertices of A = %u:", n_a);
    for (unsigned int n_b = 0; n_b <= 4; ++n_b)
      std::printf(" %s", to_string(classify_contact(n_a, n_b)));
    std::printf("\n");
  }
}
