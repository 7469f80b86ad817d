#include <talus/solver/water_loads.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace talus
{

namespace
{
/// A corner of a piece of the triangle: its point, its depth below the
/// surface z_w - z (m) and its barycentric coordinates in the whole triangle.
struct Corner
{
  Vec3 x;
  double depth;
  Vec3 bary;
};

/// The integrals over a triangle on which the depth is linear: p = gamma
/// depth and the shape functions are linear too, so that for linear f and
/// g, the integral of f g over a triangle of area A is
/// A / 12 (sum f_i g_i + sum f_i sum g_i).
void add_linear_piece(double gamma, const Corner& p, const Corner& q, const Corner& r,
                      TriangleWater& out)
{
  const double area = 0.5 * (q.x - p.x).cross(r.x - p.x).norm();
  if (!(area > 0.0))
    return;
  const double sum_d = p.depth + q.depth + r.depth;
  const double w = gamma * area / 12.0;
  out.force += gamma * area * sum_d / 3.0;
  out.first_moment +=
      w * (p.depth * p.x + q.depth * q.x + r.depth * r.x + sum_d * (p.x + q.x + r.x));
  for (int k = 0; k < 3; ++k)
    out.corner[k] += w * (p.depth * p.bary[k] + q.depth * q.bary[k] + r.depth * r.bary[k] +
                          sum_d * (p.bary[k] + q.bary[k] + r.bary[k]));
}

/// The part of a triangle with linear depth below the surface (depth >= 0):
/// one clip of the polygon by the zero line of the depth, then a fan.
void add_linear(double gamma, const Corner& a, const Corner& b, const Corner& c, TriangleWater& out)
{
  if (a.depth <= 0.0 && b.depth <= 0.0 && c.depth <= 0.0)
    return;
  if (a.depth >= 0.0 && b.depth >= 0.0 && c.depth >= 0.0)
  {
    add_linear_piece(gamma, a, b, c, out);
    return;
  }
  const Corner* loop[3] = {&a, &b, &c};
  Corner wet[4];
  int n = 0;
  for (int i = 0; i < 3; ++i)
  {
    const Corner& s = *loop[i];
    const Corner& e = *loop[(i + 1) % 3];
    if (s.depth >= 0.0)
      wet[n++] = s;
    if ((s.depth > 0.0 && e.depth < 0.0) || (s.depth < 0.0 && e.depth > 0.0))
    {
      const double t = s.depth / (s.depth - e.depth);
      wet[n++] = Corner{s.x + t * (e.x - s.x), 0.0, s.bary + t * (e.bary - s.bary)};
    }
  }
  for (int i = 1; i + 1 < n; ++i)
    add_linear_piece(gamma, wet[0], wet[i], wet[i + 1], out);
}

/// A piece of a triangle under a table: where the water covers it all,
/// the 7-point rule of degree 3 (corners 1/20, edge midpoints 2/15,
/// centroid 9/20) with the depth evaluated at each point, exact within a
/// grid cell (there the depth is quadratic, and its moments and corner
/// shares cubic); where the surface crosses it, the depth taken linear
/// through its corners and clipped.
void add_leaf(const WaterTable& table, double gamma, const Corner& a, const Corner& b,
              const Corner& c, TriangleWater& out)
{
  if (!(a.depth >= 0.0 && b.depth >= 0.0 && c.depth >= 0.0))
  {
    add_linear(gamma, a, b, c, out);
    return;
  }
  const auto at = [&](const Corner& p, const Corner& q, const Corner& r, double wp, double wq)
  {
    const Vec3 x = wp * p.x + wq * q.x + (1 - wp - wq) * r.x;
    return Corner{x, table.height(x.x(), x.y()) - x.z(),
                  wp * p.bary + wq * q.bary + (1 - wp - wq) * r.bary};
  };
  const Corner inner[4] = {at(a, b, c, 0.5, 0.5), at(b, c, a, 0.5, 0.5), at(c, a, b, 0.5, 0.5),
                           at(a, b, c, 1.0 / 3.0, 1.0 / 3.0)};
  for (const Corner& p : inner)
    if (p.depth < 0.0)
    {
      add_linear(gamma, a, b, c, out);
      return;
    }
  const double area = 0.5 * (b.x - a.x).cross(c.x - a.x).norm();
  const Corner* point[7] = {&a, &b, &c, &inner[0], &inner[1], &inner[2], &inner[3]};
  const double weight[7] = {1.0 / 20, 1.0 / 20, 1.0 / 20, 2.0 / 15, 2.0 / 15, 2.0 / 15, 9.0 / 20};
  for (int i = 0; i < 7; ++i)
  {
    const double p = gamma * area * weight[i] * point[i]->depth;
    out.force += p;
    out.first_moment += p * point[i]->x;
    for (int k = 0; k < 3; ++k)
      out.corner[k] += p * point[i]->bary[k];
  }
}

/// Under a table: halves the edges `level` more times, then integrates
/// each piece (add_leaf).
void add_divided(const WaterTable& table, double gamma, const Corner& a, const Corner& b,
                 const Corner& c, int level, TriangleWater& out)
{
  if (level == 0)
  {
    add_leaf(table, gamma, a, b, c, out);
    return;
  }
  const auto middle = [&](const Corner& p, const Corner& q)
  {
    const Vec3 x = 0.5 * (p.x + q.x);
    return Corner{x, table.height(x.x(), x.y()) - x.z(), 0.5 * (p.bary + q.bary)};
  };
  const Corner ab = middle(a, b), bc = middle(b, c), ca = middle(c, a);
  add_divided(table, gamma, a, ab, ca, level - 1, out);
  add_divided(table, gamma, ab, b, bc, level - 1, out);
  add_divided(table, gamma, ca, bc, c, level - 1, out);
  add_divided(table, gamma, ab, bc, ca, level - 1, out);
}
} // namespace

void integrate_water(const WaterTable& table, double gamma, const Vec3& a, const Vec3& b,
                     const Vec3& c, TriangleWater& out)
{
  if (table.empty())
    return;
  const auto corner = [&](const Vec3& x, int k) {
    return Corner{x, table.height(x.x(), x.y()) - x.z(), Vec3::Unit(k)};
  };
  const Corner ca = corner(a, 0), cb = corner(b, 1), cc = corner(c, 2);
  int level = 0;
  if (!table.linear() && table.spacing() > 0.0)
  {
    // A triangle wholly above the surface's highest point has no water.
    if (std::min({a.z(), b.z(), c.z()}) >= table.highest())
      return;
    const double edge = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    while (level < 6 && edge > 0.25 * table.spacing() * double(1 << level))
      ++level;
  }
  add_divided(table, gamma, ca, cb, cc, level, out);
}

WaterLoads::WaterLoads(const WaterSpec& water, double gravity, const std::vector<char>& loaded)
    : water_(water), gamma_(water.density * gravity), fixed_pressures_(water.has_fixed_pressures())
{
  if (!water.active())
    return;
  for (unsigned int b = 0; b < loaded.size(); ++b)
    if (loaded[b])
      block_.push_back(b);
  force_.resize(block_.size());
  moment_.resize(block_.size());
  velocity_before_.resize(block_.size());
  spin_before_.resize(block_.size());
}

void WaterLoads::add(const BlockModel& m, std::vector<Vec3>& force, std::vector<Vec3>& moment,
                     const std::vector<Vec3>& velocity, const std::vector<Vec3>& spin)
{
  faces_below_ = 0;
  const double highest = water_.table.highest();
  for (std::size_t k = 0; k < block_.size(); ++k)
  {
    const unsigned int b = block_[k];
    velocity_before_[k] = velocity[b];
    spin_before_[k] = spin[b];
    Vec3 f = Vec3::Zero(), mo = Vec3::Zero();
    const Vec3& centre = m.centroid[b];
    for (unsigned int face = m.face_start[b]; face < m.face_start[b + 1]; ++face)
    {
      const unsigned int first = m.face_loop_start[face], last = m.face_loop_start[face + 1];
      const Vec3& n = m.face_normal[face];
      const double fixed = fixed_pressures_ && !m.face_origin.empty()
                               ? water_.fixed_pressure(m.face_origin[face])
                               : std::numeric_limits<double>::quiet_NaN();
      if (fixed == fixed) // a joint's own water pressure, uniform
      {
        if (fixed == 0.0)
          continue;
        double area = 0.0;
        Vec3 at = Vec3::Zero();
        const Vec3& x0 = m.vertex[m.face_vertex[first]];
        for (unsigned int i = first + 1; i + 1 < last; ++i)
        {
          const Vec3& x1 = m.vertex[m.face_vertex[i]];
          const Vec3& x2 = m.vertex[m.face_vertex[i + 1]];
          const double t = 0.5 * (x1 - x0).cross(x2 - x0).dot(n);
          area += t;
          at += t * (x0 + x1 + x2) / 3.0;
        }
        if (!(area > 0.0))
          continue;
        ++faces_below_;
        const Vec3 load = -fixed * area * n;
        f += load;
        mo += (at / area - centre).cross(load);
        continue;
      }
      double lowest = 1e300;
      for (unsigned int i = first; i < last; ++i)
        lowest = std::min(lowest, m.vertex[m.face_vertex[i]].z());
      if (lowest >= highest)
        continue;
      // The face polygon as a fan of triangles from its first corner.
      TriangleWater w;
      const Vec3& x0 = m.vertex[m.face_vertex[first]];
      for (unsigned int i = first + 1; i + 1 < last; ++i)
        integrate_water(water_.table, gamma_, x0, m.vertex[m.face_vertex[i]],
                        m.vertex[m.face_vertex[i + 1]], w);
      if (!(w.force > 0.0))
        continue;
      ++faces_below_;
      // -p n over the face: the force and, about the centroid, the moment
      // of it at the centre of pressure, (integral of p x - c P) x (-n).
      f -= w.force * n;
      mo -= (w.first_moment - w.force * centre).cross(n);
    }
    force_[k] = f;
    moment_[k] = mo;
    force[b] += f;
    moment[b] += mo;
  }
}

void WaterLoads::account(const std::vector<Vec3>& velocity, const std::vector<Vec3>& spin, double h,
                         double dt, ExactSum& boundary_work, ExactSum& kinetic) const
{
  for (std::size_t k = 0; k < block_.size(); ++k)
  {
    const unsigned int b = block_[k];
    const Vec3 reach = 0.5 * h * (velocity_before_[k] + velocity[b]);
    const Vec3 turn = 0.5 * h * (spin_before_[k] + spin[b]);
    boundary_work += force_[k].dot(reach) + moment_[k].dot(turn);
    kinetic += 0.5 * (force_[k].dot(velocity[b]) + moment_[k].dot(spin[b])) * dt;
  }
}

std::string water_summary(const WaterSpec& water, unsigned int faces_below, const Vec3& force)
{
  char text[160];
  std::snprintf(text, sizeof text,
                ", %g kg/m^3; %u faces below it; water force on the free blocks %.6g, %.6g, "
                "%.6g N",
                water.density, faces_below, force[0], force[1], force[2]);
  return "Water:        " + water.table.description() + text;
}

Vec3 WaterLoads::total_force() const
{
  Vec3 sum = Vec3::Zero();
  for (const Vec3& f : force_)
    sum += f;
  return sum;
}

} // namespace talus
