// The contact region of two faces that share edges (contact_polygon.h).
// 1. A unit square clipped by a 10 x 1 rectangle that shares its two long
//    edges and one short one, both turned by a random angle and shifted far
//    from the origin (so that every coordinate carries round-off), then
//    turned by a little more than round-off: the region must be the square,
//    four vertices of 0.25 each, for all 2000 trials.
// 2. Two copies of one face (coincident polygons): the face itself.
// 3. A trapezoid, and the same with vertices added on its edges and next to
//    its corners: the vertices' areas add up to the area and their centre is
//    the area centroid; the added vertices are removed.

#include <talus/contact/contact_polygon.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <random>

#include "../tests.h"

using namespace talus;

namespace
{

std::vector<Point2> moved(const std::vector<Point2>& p, double angle, const Point2& shift)
{
  const Eigen::Rotation2Dd turn(angle);
  std::vector<Point2> q;
  for (const Point2& x : p)
    q.push_back(turn * x + shift);
  return q;
}

/// The area-weighted centre of the vertices' shares.
Point2 share_centre(const std::vector<Point2>& p, const std::vector<double>& w)
{
  Point2 c = Point2::Zero();
  double total = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    c += w[i] * p[i];
    total += w[i];
  }
  return c / total;
}

} // namespace

int main()
{
  std::mt19937 random(20);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * M_PI), far(-3000.0, 3000.0),
      tiny(-1e-13, 1e-13);
  const std::vector<Point2> square = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const std::vector<Point2> base = {{0, 0}, {10, 0}, {10, 1}, {0, 1}};

  // 1. Shared edges under round-off.
  // Without the tolerance (eps = 0, as the clipping was before) most trials
  // gain vertices: on standard error.
  unsigned int good = 0, good_without = 0, trials = 2000, most = 0;
  double worst_area = 0.0;
  for (unsigned int t = 0; t < trials; ++t)
  {
    const double turn = angle(random);
    const Point2 shift(far(random), far(random));
    const std::vector<Point2> a = moved(base, turn, shift);
    const std::vector<Point2> b = moved(square, turn + tiny(random), shift);
    const double eps = contact_polygon_relative_tolerance * polygon_size(a, b);
    const std::vector<Point2> region = clip_convex(convex_hull(a, eps), convex_hull(b, eps), eps);
    const std::vector<double> w = vertex_areas(region);
    double error = 0.0;
    for (const double x : w)
      error = std::max(error, std::abs(x - 0.25));
    most = std::max(most, static_cast<unsigned int>(region.size()));
    worst_area = std::max(worst_area, error);
    good += region.size() == 4 && error < 1e-9;
    const std::vector<Point2> without = clip_convex(convex_hull(a, 0.0), convex_hull(b, 0.0), 0.0);
    good_without += without.size() == 4;
  }
  std::fprintf(stderr, "without a tolerance: %u of %u with four vertices\n", good_without, trials);
  std::fprintf(stderr, "shared edges: %u of %u good, at most %u vertices, area error %.3g\n", good,
               trials, most, worst_area);
  std::printf("square on a rectangle sharing three edges, turned and shifted, %u trials: four "
              "vertices of 0.25: %s\n",
              trials, talus_test::verdict(good == trials));

  // 2. Coincident faces.
  {
    const std::vector<Point2> face =
        moved({{0, 0}, {2, 0}, {2.5, 1}, {0.3, 1.4}}, 0.7, Point2(1234.5, -987.6));
    const double eps = contact_polygon_relative_tolerance * polygon_size(face, face);
    const std::vector<Point2> region = clip_convex(face, face, eps);
    std::fprintf(stderr, "coincident faces: %zu vertices, area %.12g of %.12g\n", region.size(),
                 polygon_area(region), polygon_area(face));
    std::printf("coincident faces: the face itself: %s\n",
                talus_test::verdict(region.size() == 4 &&
                                    std::abs(polygon_area(region) - polygon_area(face)) < 1e-9));
  }

  // 3. Shares of a trapezoid, without and with spurious vertices.
  {
    const std::vector<Point2> trapezoid = {{0, 0}, {4, 0}, {3, 1}, {1, 1}};
    const double area = polygon_area(trapezoid);
    const Point2 centroid = polygon_centroid(trapezoid); // (2, 4/9)
    const std::vector<double> w = vertex_areas(trapezoid);
    const Point2 c = share_centre(trapezoid, w);
    std::printf("trapezoid: shares add up to the area and centre on (2, 4/9): %s\n",
                talus_test::verdict(std::abs(w[0] + w[1] + w[2] + w[3] - area) < 1e-12 &&
                                    (c - Point2(2.0, 4.0 / 9.0)).norm() < 1e-12 &&
                                    (centroid - Point2(2.0, 4.0 / 9.0)).norm() < 1e-12));
    std::vector<Point2> spurious = {{0, 0}, {1.3, 0},         {4, 0}, {4 - 1e-12, 1e-12},
                                    {3, 1}, {2.2, 1 + 1e-13}, {1, 1}, {0.5, 0.5}};
    remove_spurious_vertices(spurious, 1e-9 * 4.0);
    std::printf("trapezoid with vertices on its edges and at a corner: they are removed: %s\n",
                talus_test::verdict(spurious.size() == 4 &&
                                    std::abs(polygon_area(spurious) - area) < 1e-9));
  }
}
