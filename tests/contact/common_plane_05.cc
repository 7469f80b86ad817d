// Overlapping blocks: the common plane minimises the largest overlap, so the
// gap is minus the overlap depth along the normal.
//   1. Two unit cubes overlapping face to face by 0.02 (B offset sideways):
//      normal +x, gap -0.02, face-face; then, as an existing contact, B goes
//      0.01 deeper: gap -0.03 after one round.
//   2. A cube standing on a corner pushed 0.03 into a large box: normal +z,
//      gap -0.03, vertex-face (only B's lowest vertex is beyond the plane).
//   3. Two crossed edges (cubes turned 45 degrees about x and about y)
//      pushed 0.03 into each other: normal +z, gap -0.03, edge-edge.
// For touching blocks the reference point only moves along the normal onto
// the mid-plane. Each case also runs in a rotated, shifted frame.

#include <talus/contact/common_plane.h>
#include <talus/geometry/convex_polyhedron.h>

#include <Eigen/Geometry>

#include "../tests.h"

using namespace talus;

namespace
{

std::vector<Vec3> box(const Vec3& lo, const Vec3& hi)
{
  return ConvexPolyhedron::box(lo, hi).vertices();
}

std::vector<Vec3> cube(const Eigen::Matrix3d& R, const Vec3& centre)
{
  std::vector<Vec3> v;
  for (const Vec3& x : box(Vec3(-0.5, -0.5, -0.5), Vec3(0.5, 0.5, 0.5)))
    v.push_back(R * x + centre);
  return v;
}

std::vector<Vec3> moved(const std::vector<Vec3>& v, const Eigen::Matrix3d& R, const Vec3& t)
{
  std::vector<Vec3> out;
  for (const Vec3& x : v)
    out.push_back(R * x + t);
  return out;
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

/// `plane_point` is a point of the exact mid-plane.
CommonPlane check_case(const std::string& name, const std::vector<Vec3>& a,
                       const std::vector<Vec3>& b, const Vec3& normal, double gap,
                       const Vec3& plane_point, ContactType type)
{
  const CommonPlaneSettings settings;
  CommonPlane cp = initial_common_plane(mean(a), mean(b));
  const Vec3 start = cp.reference;
  const CommonPlaneResult r =
      update_common_plane(cp, a.data(), a.size(), b.data(), b.size(), settings, true);
  talus_test::check(name + ": normal angle error (rad)", angle(cp.normal, normal), 0.0, 1e-9);
  talus_test::check(name + ": gap", r.gap, gap, 1e-9);
  talus_test::check(name + ": reference point off the mid-plane",
                    normal.dot(cp.reference - plane_point), 0.0, 1e-9);
  talus_test::check(name + ": reference point moved sideways",
                    (cp.reference - start - normal.dot(cp.reference - start) * normal).norm(), 0.0,
                    1e-9);
  std::printf("%s: type %s (exact %s) %s, touching %u + %u, iterations <= 60: %s\n", name.c_str(),
              to_string(r.type), to_string(type), r.type == type ? "OK" : "WRONG", r.n_touching_a,
              r.n_touching_b, r.iterations <= 60 ? "OK" : "WRONG");
  return cp;
}

} // namespace

int main()
{
  const double s2 = std::sqrt(2.0), s3 = std::sqrt(3.0);
  const Eigen::Matrix3d frame_R =
      Eigen::AngleAxisd(2.0, Vec3(0.3, -1.0, 0.8).normalized()).toRotationMatrix();
  const Vec3 frame_t(55.0, 8.0, -31.0);
  const Eigen::Matrix3d corner_down =
      Eigen::Quaterniond::FromTwoVectors(Vec3(1, 1, 1), Vec3(0, 0, -1)).toRotationMatrix();

  for (const bool rotated : {false, true})
  {
    const Eigen::Matrix3d R = rotated ? frame_R : Eigen::Matrix3d::Identity();
    const Vec3 t = rotated ? frame_t : Vec3::Zero();
    const std::string f = rotated ? "rotated " : "plain ";
    const auto place = [&](const Vec3& x) { return Vec3(R * x + t); };
    {
      const double d = 0.02;
      const std::vector<Vec3> a = moved(box(Vec3(0, 0, 0), Vec3(1, 1, 1)), R, t);
      const std::vector<Vec3> b = moved(box(Vec3(1 - d, 0.2, 0.1), Vec3(2 - d, 1.2, 1.1)), R, t);
      CommonPlane cp = check_case(f + "face-face overlap 0.02", a, b, R * Vec3::UnitX(), -d,
                                  place(Vec3(1 - 0.5 * d, 0, 0)), ContactType::face_face);
      const std::vector<Vec3> b2 = moved(b, Eigen::Matrix3d::Identity(), R * Vec3(-0.01, 0, 0));
      const CommonPlaneResult r = update_common_plane(cp, a.data(), a.size(), b2.data(), b2.size(),
                                                      CommonPlaneSettings(), false);
      talus_test::check(f + "face-face, 0.01 deeper: normal angle error (rad)",
                        angle(cp.normal, R * Vec3::UnitX()), 0.0, 1e-9);
      talus_test::check(f + "face-face, 0.01 deeper: gap", r.gap, -0.03, 1e-9);
      talus_test::check(f + "face-face, 0.01 deeper: reference point off the mid-plane",
                        cp.normal.dot(cp.reference - place(Vec3(1 - 0.015, 0, 0))), 0.0, 1e-9);
      std::printf("%sface-face, 0.01 deeper: type %s, iterations %u, scans %u\n", f.c_str(),
                  to_string(r.type), r.iterations, r.evaluations);
    }
    {
      const double d = 0.03;
      const std::vector<Vec3> a = moved(box(Vec3(-2, -2, -1), Vec3(2, 2, 0)), R, t);
      const std::vector<Vec3> b = cube(R * corner_down, place(Vec3(0.3, -0.2, 0.5 * s3 - d)));
      check_case(f + "vertex into face 0.03", a, b, R * Vec3::UnitZ(), -d,
                 place(Vec3(0, 0, -0.5 * d)), ContactType::vertex_face);
    }
    {
      const double d = 0.03;
      const std::vector<Vec3> a =
          cube(R * Eigen::AngleAxisd(M_PI / 4, Vec3::UnitX()).toRotationMatrix(), t);
      const std::vector<Vec3> b =
          cube(R * Eigen::AngleAxisd(M_PI / 4, Vec3::UnitY()).toRotationMatrix(),
               place(Vec3(0.1, -0.15, s2 - d)));
      check_case(f + "edge into edge 0.03", a, b, R * Vec3::UnitZ(), -d,
                 place(Vec3(0, 0, 0.5 * (s2 - d))), ContactType::edge_edge);
    }
  }
}
