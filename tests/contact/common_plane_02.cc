// Edge-to-edge: cube A (unit, centred at the origin) turned 45 degrees about
// x has a top edge along x at height sqrt(2)/2; cube B turned 45 degrees
// about y (and then 0 or 30 degrees about z) and centred at (0.1, -0.15, h)
// has a bottom edge at height h - sqrt(2)/2 that crosses A's edge. The
// common plane must be horizontal, the gap h - sqrt(2), the reference point
// midway between the crossing points of the two edges (eq. 9) and the type
// edge-edge. Runs in the plain frame and in a rotated, shifted one; then as
// an existing contact after B moves.

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

Eigen::Matrix3d rotation(double degrees, const Vec3& axis)
{
  return Eigen::AngleAxisd(degrees * M_PI / 180.0, axis.normalized()).toRotationMatrix();
}

} // namespace

int main()
{
  const double s2 = std::sqrt(2.0);
  const Eigen::Matrix3d frame_R = rotation(40.0, Vec3(-1, 2, 0.5));
  const Vec3 frame_t(-12.0, 30.0, 7.5);
  const CommonPlaneSettings settings;

  for (const double skew : {0.0, 30.0})
    for (const double gap : {0.03, 0.0})
      for (const bool rotated : {false, true})
      {
        const Eigen::Matrix3d R = rotated ? frame_R : Eigen::Matrix3d::Identity();
        const Vec3 t = rotated ? frame_t : Vec3::Zero();
        const double h = s2 + gap;
        const std::vector<Vec3> a = cube(R * rotation(45, Vec3::UnitX()), t);
        const std::vector<Vec3> b =
            cube(R * rotation(skew, Vec3::UnitZ()) * rotation(45, Vec3::UnitY()),
                 R * Vec3(0.1, -0.15, h) + t);
        // B's edge runs along (-sin skew, cos skew, 0) through (0.1, -0.15):
        // it meets y = 0 at x = 0.1 - 0.15 tan(skew).
        const Vec3 crossing(0.1 - 0.15 * std::tan(skew * M_PI / 180.0), 0.0, 0.5 * h);

        CommonPlane cp = initial_common_plane(mean(a), mean(b));
        const CommonPlaneResult r =
            update_common_plane(cp, a.data(), a.size(), b.data(), b.size(), settings, true);
        char name[64];
        std::snprintf(name, sizeof(name), "skew %g, gap %g, %s", skew, gap,
                      rotated ? "rotated" : "plain");
        const std::string n(name);
        talus_test::check(n + ": normal angle error (rad)", angle(cp.normal, R * Vec3::UnitZ()),
                          0.0, 1e-9);
        talus_test::check(n + ": gap", r.gap, gap, 1e-9);
        if (gap > 0.0)
          talus_test::check(n + ": reference point error",
                            (cp.reference - (R * crossing + t)).norm(), 0.0, 1e-9);
        else
          talus_test::check(n + ": reference point off the mid-plane",
                            cp.normal.dot(cp.reference - (R * crossing + t)), 0.0, 1e-9);
        std::printf("%s: type %s (exact edge-edge) %s, touching %u + %u, iterations <= 60: %s\n",
                    name, to_string(r.type), r.type == ContactType::edge_edge ? "OK" : "WRONG",
                    r.n_touching_a, r.n_touching_b, r.iterations <= 60 ? "OK" : "WRONG");

        if (skew == 30.0 && gap > 0.0)
        {
          // Existing contact: B comes 0.01 closer and slides by (0.05, 0.02);
          // the edges still cross, so the normal stays and the gap is 0.02.
          std::vector<Vec3> b2 = b;
          for (Vec3& x : b2)
            x += R * Vec3(0.05, 0.02, -0.01);
          const CommonPlaneResult r2 =
              update_common_plane(cp, a.data(), a.size(), b2.data(), b2.size(), settings, false);
          talus_test::check(n + ", B moved: normal angle error (rad)",
                            angle(cp.normal, R * Vec3::UnitZ()), 0.0, 1e-9);
          talus_test::check(n + ", B moved: gap", r2.gap, gap - 0.01, 1e-9);
          std::printf("%s, B moved: type %s, iterations %u, scans %u\n", name, to_string(r2.type),
                      r2.iterations, r2.evaluations);
        }
      }
}
