#include <talus/contact/contact_polygon.h>

#include <algorithm>
#include <cmath>

namespace talus
{

std::vector<Point2> convex_hull(std::vector<Point2> p, double eps)
{
  // Andrew's monotone chain; only strict left turns stay, and the clean-up
  // below takes what round-off leaves nearly straight.
  std::sort(p.begin(), p.end(),
            [](const Point2& a, const Point2& b)
            { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3)
  {
    remove_spurious_vertices(p, eps);
    return p;
  }
  std::vector<Point2> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    while (k >= 2 && cross2(h[k - 2], h[k - 1], p[i]) <= 0.0)
      --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i)
  {
    while (k >= t && cross2(h[k - 2], h[k - 1], p[i - 1]) <= 0.0)
      --k;
    h[k++] = p[i - 1];
  }
  h.resize(k - 1);
  remove_spurious_vertices(h, eps);
  return h;
}

void remove_spurious_vertices(std::vector<Point2>& p, double eps)
{
  bool changed = true;
  while (changed && p.size() >= 2)
  {
    changed = false;
    // A vertex on top of the one before it.
    for (std::size_t i = 0; i < p.size() && p.size() >= 2;)
    {
      const std::size_t next = (i + 1) % p.size();
      if ((p[next] - p[i]).norm() <= eps)
      {
        p.erase(p.begin() + static_cast<std::ptrdiff_t>(next));
        changed = true;
        if (next < i)
          break; // the first one went: start over
      }
      else
        ++i;
    }
    // A vertex within eps of the chord of its neighbours: on a straight
    // edge, or a notch (a right turn) that round-off made.
    for (std::size_t i = 0; i < p.size() && p.size() >= 3;)
    {
      const std::size_t n = p.size();
      const Point2& before = p[(i + n - 1) % n];
      const Point2& after = p[(i + 1) % n];
      const double chord = (after - before).norm();
      // Counter-clockwise: a vertex that sticks out lies right of the chord.
      if (!(chord > eps) || -cross2(before, after, p[i]) <= eps * chord)
      {
        p.erase(p.begin() + static_cast<std::ptrdiff_t>(i));
        changed = true;
      }
      else
        ++i;
    }
  }
}

std::vector<Point2> clip_convex(std::vector<Point2> subject, const std::vector<Point2>& clip,
                                double eps)
{
  for (std::size_t e = 0; e < clip.size() && !subject.empty(); ++e)
  {
    const Point2& a = clip[e];
    const Point2& b = clip[(e + 1) % clip.size()];
    const double length = (b - a).norm();
    if (!(length > 0.0))
      continue;
    // Signed distances from the edge's line, positive inside.
    const std::size_t n = subject.size();
    std::vector<double> d(n);
    for (std::size_t i = 0; i < n; ++i)
      d[i] = cross2(a, b, subject[i]) / length;
    std::vector<Point2> out;
    for (std::size_t i = 0; i < n; ++i)
    {
      const std::size_t j = (i + 1) % n;
      if (d[i] >= -eps)
        out.push_back(subject[i]);
      // A crossing only between a point clearly inside and one clearly
      // outside; a segment has one side, not two.
      const bool crosses = (d[i] > eps && d[j] < -eps) || (d[i] < -eps && d[j] > eps);
      if (n > 1 && crosses && !(n == 2 && i == 1))
        out.push_back(subject[i] + (subject[j] - subject[i]) * (d[i] / (d[i] - d[j])));
    }
    subject = std::move(out);
  }
  remove_spurious_vertices(subject, eps);
  return subject;
}

double polygon_size(const std::vector<Point2>& a, const std::vector<Point2>& b)
{
  if (a.empty() && b.empty())
    return 0.0;
  Point2 lo = a.empty() ? b[0] : a[0], hi = lo;
  for (const std::vector<Point2>* set : {&a, &b})
    for (const Point2& p : *set)
    {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  return (hi - lo).norm();
}

double polygon_area(const std::vector<Point2>& p)
{
  double a = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    a += cross2(p[0], p[i], p[(i + 1) % p.size()]);
  return 0.5 * a;
}

Point2 polygon_centroid(const std::vector<Point2>& p)
{
  // Fan from the first vertex: each triangle's centroid by its area.
  Point2 sum = Point2::Zero();
  double twice_area = 0.0;
  for (std::size_t i = 1; i + 1 < p.size(); ++i)
  {
    const double t = cross2(p[0], p[i], p[i + 1]);
    sum += t * (p[i] + p[i + 1] - 2.0 * p[0]);
    twice_area += t;
  }
  return p[0] + sum / (3.0 * twice_area);
}

std::vector<double> vertex_areas(const std::vector<Point2>& p)
{
  std::vector<double> w(p.size(), 0.0);
  if (p.size() < 3 || !(polygon_area(p) > 0.0))
    return w;
  const Point2 centre = polygon_centroid(p);
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const std::size_t j = (i + 1) % p.size();
    const double t = 0.5 * std::abs(cross2(centre, p[i], p[j]));
    w[i] += 0.5 * t;
    w[j] += 0.5 * t;
  }
  return w;
}

} // namespace talus
