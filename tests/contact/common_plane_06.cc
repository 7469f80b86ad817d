// The common plane against the direct tests of the theory manual (eq. 3) on
// 400 random pairs of convex blocks (boxes, tetrahedra, prisms with 3 to 8
// sides, turned at random), placed at random distances so that some are apart
// and some overlap.
//  - Apart: the largest gap over all planes is the distance between the
//    blocks, found directly as the least vertex-face and edge-edge distance;
//    the normal is the direction of the closest points.
//  - Overlapping: the smallest overlap over all planes is found among the
//    face normals of both blocks and the cross products of their edges (the
//    separating-axis candidates). The hill-climb starts from the
//    centroid-to-centroid guess and may settle on a local optimum; the
//    test counts how often it finds the global one and checks that it never
//    claims more than the global optimum.
// Then every pair moves a little (B shifted by up to 0.01 and turned by 0.5
// degree) and is updated as an existing contact.

#include <talus/contact/common_plane.h>
#include <talus/geometry/convex_polyhedron.h>

#include <Eigen/Geometry>

#include <random>

#include "../tests.h"

using namespace talus;

namespace
{

/// Uniform numbers from a fixed-seed engine, with a mapping of our own so
/// that the sequence is the same with every standard library.
class Random
{
public:
  double uniform(double lo, double hi)
  {
    return lo + (hi - lo) * double(engine() >> 11) * (1.0 / 9007199254740992.0);
  }
  Vec3 unit_vector()
  {
    while (true)
    {
      const Vec3 v(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
      if (v.squaredNorm() > 1e-4 && v.squaredNorm() <= 1.0)
        return v.normalized();
    }
  }
  Eigen::Matrix3d rotation()
  {
    while (true)
    {
      Eigen::Quaterniond q(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
      if (q.squaredNorm() > 1e-4 && q.squaredNorm() <= 1.0)
        return q.normalized().toRotationMatrix();
    }
  }

private:
  std::mt19937_64 engine{20240611};
};

ConvexPolyhedron transformed(const ConvexPolyhedron& p, const Eigen::Matrix3d& R, const Vec3& t)
{
  std::vector<Vec3> v;
  for (const Vec3& x : p.vertices())
    v.push_back(R * x + t);
  return ConvexPolyhedron(v, p.face_start(), p.face_vertices());
}

ConvexPolyhedron random_block(Random& random)
{
  ConvexPolyhedron p;
  const int kind = int(random.uniform(0, 3));
  if (kind == 0)
  {
    const Vec3 h(random.uniform(0.15, 0.75), random.uniform(0.15, 0.75),
                 random.uniform(0.15, 0.75));
    p = ConvexPolyhedron::box(-h, h);
  }
  else if (kind == 1)
  {
    while (true)
    {
      Vec3 c[4];
      for (Vec3& x : c)
        x = random.unit_vector() * random.uniform(0.4, 0.8);
      p = ConvexPolyhedron::tetrahedron(c[0], c[1], c[2], c[3]);
      if (p.volume() > 0.04)
        break;
    }
  }
  else
  {
    const int sides = 3 + int(random.uniform(0, 6));
    std::vector<double> angles;
    for (int i = 0; i < sides; ++i) // spread out: no side shorter than ~0.3 rad
      angles.push_back(2 * M_PI * (i + random.uniform(0.0, 0.6)) / sides);
    const double r = random.uniform(0.3, 0.8);
    std::vector<Vec3> base;
    for (const double a : angles)
      base.push_back(Vec3(r * std::cos(a), r * std::sin(a), 0.0));
    p = ConvexPolyhedron::prism(base, Vec3(0, 0, random.uniform(0.3, 1.2)));
  }
  return transformed(p, random.rotation(), -p.vertex_mean());
}

/// Closest points of segments p0-p1 and q0-q1 (Ericson, Real-Time Collision
/// Detection, 5.1.9); returns the squared distance.
double segment_segment(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1, Vec3& cp,
                       Vec3& cq)
{
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s, t;
  const double c = d1.dot(r), b = d1.dot(d2), denom = a * e - b * b;
  s = denom > 1e-14 * a * e ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  t = (b * s + f) / e;
  if (t < 0.0)
  {
    t = 0.0;
    s = std::clamp(-c / a, 0.0, 1.0);
  }
  else if (t > 1.0)
  {
    t = 1.0;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  cp = p0 + s * d1;
  cq = q0 + t * d2;
  return (cp - cq).squaredNorm();
}

/// Least distance of the vertices of `p` to the faces of `q` (where the foot
/// of the perpendicular falls inside the face); updates best, a_point on A,
/// b_point on B (`p_is_a` tells which is which).
void vertex_face(const ConvexPolyhedron& p, const ConvexPolyhedron& q, bool p_is_a, double& best,
                 Vec3& a_point, Vec3& b_point)
{
  for (const Vec3& x : p.vertices())
    for (unsigned int f = 0; f < q.n_faces(); ++f)
    {
      const Plane& plane = q.face_plane(f);
      const double h = plane.signed_distance(x);
      if (h < 0.0)
        continue; // behind the face: another feature is nearer
      const Vec3 foot = x - h * plane.normal;
      bool inside = true;
      for (unsigned int k = 0; k < q.face_size(f) && inside; ++k)
      {
        const Vec3& v0 = q.vertex(q.face_vertex(f, k));
        const Vec3& v1 = q.vertex(q.face_vertex(f, (k + 1) % q.face_size(f)));
        inside = (v1 - v0).cross(foot - v0).dot(plane.normal) >= 0.0;
      }
      if (inside && h < best)
      {
        best = h;
        a_point = p_is_a ? x : foot;
        b_point = p_is_a ? foot : x;
      }
    }
}

/// Distance between two separate convex polyhedra by the direct tests.
double direct_distance(const ConvexPolyhedron& a, const ConvexPolyhedron& b, Vec3& normal)
{
  double best = std::numeric_limits<double>::infinity();
  Vec3 pa, pb;
  vertex_face(a, b, true, best, pa, pb);
  vertex_face(b, a, false, best, pa, pb);
  double best_sq = best * best;
  for (const auto& [i, j] : a.edges())
    for (const auto& [k, l] : b.edges())
    {
      Vec3 cp, cq;
      const double d = segment_segment(a.vertex(i), a.vertex(j), b.vertex(k), b.vertex(l), cp, cq);
      if (d < best_sq)
      {
        best_sq = d;
        pa = cp;
        pb = cq;
      }
    }
  normal = (pb - pa).normalized();
  return std::sqrt(best_sq);
}

double gap_along(const Vec3& n, const ConvexPolyhedron& a, const ConvexPolyhedron& b)
{
  double a_max = -std::numeric_limits<double>::infinity();
  double b_min = std::numeric_limits<double>::infinity();
  for (const Vec3& x : a.vertices())
    a_max = std::max(a_max, n.dot(x));
  for (const Vec3& x : b.vertices())
    b_min = std::min(b_min, n.dot(x));
  return b_min - a_max;
}

/// Largest gap over the separating-axis candidates, both senses.
double best_axis_gap(const ConvexPolyhedron& a, const ConvexPolyhedron& b)
{
  double best = -std::numeric_limits<double>::infinity();
  const auto consider = [&](const Vec3& axis)
  {
    if (axis.squaredNorm() < 1e-20)
      return;
    const Vec3 n = axis.normalized();
    best = std::max({best, gap_along(n, a, b), gap_along(-n, a, b)});
  };
  for (unsigned int f = 0; f < a.n_faces(); ++f)
    consider(a.face_plane(f).normal);
  for (unsigned int f = 0; f < b.n_faces(); ++f)
    consider(b.face_plane(f).normal);
  for (const auto& [i, j] : a.edges())
    for (const auto& [k, l] : b.edges())
      consider((a.vertex(j) - a.vertex(i)).cross(b.vertex(l) - b.vertex(k)));
  return best;
}

double angle(const Vec3& a, const Vec3& b)
{
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

struct Tally
{
  unsigned int apart = 0, apart_exact = 0, overlap = 0, overlap_global = 0, overlap_above = 0;
  double apart_gap_error = 0.0, apart_normal_error = 0.0, apart_above = 0.0;
  double overlap_gap_error = 0.0;
  unsigned int iterations = 0, max_iterations = 0, polished = 0;

  void add(const CommonPlaneResult& r, const CommonPlane& cp, const ConvexPolyhedron& a,
           const ConvexPolyhedron& b)
  {
    iterations += r.iterations;
    max_iterations = std::max(max_iterations, r.iterations);
    polished += r.polished;
    const double axis_gap = best_axis_gap(a, b);
    if (axis_gap > 0.0)
    {
      ++apart;
      Vec3 normal;
      const double distance = direct_distance(a, b, normal);
      const double error = std::abs(r.gap - distance);
      apart_above = std::max(apart_above, r.gap - distance);
      if (error < 1e-9)
      {
        ++apart_exact;
        apart_gap_error = std::max(apart_gap_error, error);
        apart_normal_error = std::max(apart_normal_error, angle(cp.normal, normal));
      }
    }
    else
    {
      ++overlap;
      overlap_above += r.gap > axis_gap + 1e-12;
      if (std::abs(r.gap - axis_gap) < 1e-9)
      {
        ++overlap_global;
        overlap_gap_error = std::max(overlap_gap_error, std::abs(r.gap - axis_gap));
      }
    }
  }

  void print(const std::string& name, unsigned int pairs) const
  {
    std::printf("%s: %u pairs apart, the gap equal to the direct distance (1e-9) for %u\n",
                name.c_str(), apart, apart_exact);
    talus_test::check(name + ": apart, largest gap error of those", apart_gap_error, 0.0, 1e-9);
    talus_test::check(name + ": apart, largest normal angle error of those (rad)",
                      apart_normal_error, 0.0, 1e-7);
    std::printf("%s: apart, gap never above the distance: %s\n", name.c_str(),
                apart_above <= 1e-12 ? "OK" : "WRONG");
    std::printf("%s: %u pairs overlapping, the least overlap found for %u, more than the least "
                "claimed for %u (exact 0) %s\n",
                name.c_str(), overlap, overlap_global, overlap_above,
                overlap_above == 0 ? "OK" : "WRONG");
    const double limit = name == "new" ? 40.0 : 2.0;
    std::printf("%s: mean iterations below %g: %s, largest below 100: %s, polished: %s\n",
                name.c_str(), limit, double(iterations) / pairs < limit ? "OK" : "WRONG",
                max_iterations < 100 ? "OK" : "WRONG",
                polished == pairs ? "all" : (polished >= 0.9 * pairs ? "90% or more" : "fewer"));
  }
};

} // namespace

int main()
{
  Random random;
  const unsigned int pairs = 400;
  Tally first, second;
  const CommonPlaneSettings settings;
  for (unsigned int i = 0; i < pairs; ++i)
  {
    const ConvexPolyhedron a0 = random_block(random), b0 = random_block(random);
    double r_a = 0.0, r_b = 0.0;
    for (const Vec3& x : a0.vertices())
      r_a = std::max(r_a, x.norm());
    for (const Vec3& x : b0.vertices())
      r_b = std::max(r_b, x.norm());
    const Vec3 offset = random.unit_vector() * random.uniform(0.5, 1.05) * (r_a + r_b);
    const ConvexPolyhedron a = transformed(a0, Eigen::Matrix3d::Identity(), Vec3(3, -1, 2));
    const ConvexPolyhedron b =
        transformed(b0, Eigen::Matrix3d::Identity(), Vec3(3, -1, 2) + offset);

    CommonPlane cp = initial_common_plane(a.vertex_mean(), b.vertex_mean());
    const CommonPlaneResult r =
        update_common_plane(cp, a.vertices().data(), a.n_vertices(), b.vertices().data(),
                            b.n_vertices(), settings, true);
    first.add(r, cp, a, b);

    // A small motion of B about its centroid, then an update of the
    // existing contact.
    const Eigen::Matrix3d turn =
        Eigen::AngleAxisd(0.5 * M_PI / 180.0, random.unit_vector()).toRotationMatrix();
    const Vec3 c = b.vertex_mean();
    const ConvexPolyhedron b2 =
        transformed(b, turn, c - turn * c + 0.01 * random.uniform(0, 1) * random.unit_vector());
    const CommonPlaneResult r2 =
        update_common_plane(cp, a.vertices().data(), a.n_vertices(), b2.vertices().data(),
                            b2.n_vertices(), settings, false);
    second.add(r2, cp, a, b2);
  }
  first.print("new", pairs);
  second.print("existing", pairs);
}
