#include <talus/contact/common_plane.h>

#include <algorithm>
#include <cassert>
#include <cmath>

namespace talus
{

ContactType classify_contact(unsigned int n_a, unsigned int n_b)
{
  // Table 1: 1 touching vertex = a vertex, 2 = an edge, 3 or more = a face.
  if (n_a == 0 || n_b == 0)
    return ContactType::none;
  const unsigned int lo = std::min(std::min(n_a, n_b), 3u);
  const unsigned int hi = std::min(std::max(n_a, n_b), 3u);
  if (lo == 1)
    return hi == 1 ? ContactType::vertex_vertex
                   : (hi == 2 ? ContactType::vertex_edge : ContactType::vertex_face);
  if (lo == 2)
    return hi == 2 ? ContactType::edge_edge : ContactType::edge_face;
  return ContactType::face_face;
}

const char* to_string(ContactType type)
{
  switch (type)
  {
  case ContactType::vertex_face:
    return "vertex-face";
  case ContactType::edge_edge:
    return "edge-edge";
  case ContactType::edge_face:
    return "edge-face";
  case ContactType::face_face:
    return "face-face";
  case ContactType::vertex_edge:
    return "vertex-edge";
  case ContactType::vertex_vertex:
    return "vertex-vertex";
  case ContactType::none:
    return "none";
  }
  return "none";
}

CommonPlane initial_common_plane(const Vec3& centroid_a, const Vec3& centroid_b)
{
  // eq. 5: midway between the centroids, normal along Z = B - A.
  CommonPlane cp;
  cp.reference = 0.5 * (centroid_a + centroid_b);
  const Vec3 z = centroid_b - centroid_a;
  const double length = z.norm();
  cp.normal = length > 0.0 ? Vec3(z / length) : Vec3(Vec3::UnitZ());
  return cp;
}

namespace
{

/// The nearest vertices of both blocks along a normal n, in raw coordinates
/// n . V (the gap does not depend on where the plane is): a_max = d_A of eq. 7
/// and b_min = d_B of eq. 6 up to the common shift n . C.
struct Extremes
{
  double a_max;
  double b_min;
  unsigned int i_a;
  unsigned int i_b;

  double gap() const { return b_min - a_max; }
};

/// Scans both vertex sets along n. `e` holds, on entry, the indices of the
/// vertices that were nearest last time; they are scanned first so that a
/// trial normal that cannot beat `bound` is usually rejected after a few
/// vertices (the gap only shrinks as the scan goes on). Returns true, with
/// `e` filled, only when the scan completed and the gap exceeds `bound`.
inline bool scan(const Vec3& n, const Vec3* va, unsigned int na, const Vec3* vb, unsigned int nb,
                 double bound, Extremes& e)
{
  unsigned int i_a = e.i_a, i_b = e.i_b;
  double a_max = n.dot(va[i_a]);
  double b_min = n.dot(vb[i_b]);
  if (b_min - a_max <= bound)
    return false;
  for (unsigned int i = 0; i < na; ++i)
  {
    const double s = n.dot(va[i]);
    if (s > a_max)
    {
      a_max = s;
      i_a = i;
      if (b_min - a_max <= bound)
        return false;
    }
  }
  for (unsigned int i = 0; i < nb; ++i)
  {
    const double s = n.dot(vb[i]);
    if (s < b_min)
    {
      b_min = s;
      i_b = i;
      if (b_min - a_max <= bound)
        return false;
    }
  }
  e = Extremes{a_max, b_min, i_a, i_b};
  return true;
}

/// Two unit vectors p, q with (p, q, n) orthonormal, without branches on
/// near-zero components (Duff et al. 2017); any such pair serves as the
/// perturbation axes of eq. 10.
inline void orthonormal_basis(const Vec3& n, Vec3& p, Vec3& q)
{
  const double sign = std::copysign(1.0, n.z());
  const double a = -1.0 / (sign + n.z());
  const double b = n.x() * n.y() * a;
  p = Vec3(1.0 + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  q = Vec3(b, sign + n.y() * n.y() * a, -n.y());
}

/// State of one update: the current normal, its perturbation axes and the
/// nearest vertices along it.
class Search
{
public:
  Search(const Vec3& normal, const Vec3* va_, unsigned int na_, const Vec3* vb_, unsigned int nb_,
         const CommonPlaneSettings& settings_, CommonPlaneResult& result_)
      : n(normal.normalized()), va(va_), na(na_), vb(vb_), nb(nb_), settings(settings_),
        result(result_), k_min(std::tan(settings_.k_min_degrees * M_PI / 180.0)),
        k_max(std::tan(settings_.k_max_degrees * M_PI / 180.0))
  {
    orthonormal_basis(n, p, q);
    cur = Extremes{0.0, 0.0, 0, 0};
    ++result.evaluations;
    scan(n, va, na, vb, nb, -std::numeric_limits<double>::infinity(), cur);
  }

  bool too_far() const { return cur.gap() > settings.contact_tolerance; }

  /// One round of eq. 10: the four normals (n +- k P) / z, (n +- k Q) / z with
  /// z^2 = 1 + k^2, where (P, Q) are (p, q) or, on alternate rounds, (p, q)
  /// turned by 45 degrees about n so that a ridge of the gap function that
  /// runs diagonally to one pair is not taken for a summit. Moves to the best
  /// of the four if it increases the gap; returns whether it did.
  bool round(double k, bool turned)
  {
    ++result.iterations;
    Vec3 P = p, Q = q;
    if (turned)
    {
      P = M_SQRT1_2 * (p + q);
      Q = M_SQRT1_2 * (q - p);
    }
    const double inv_z = 1.0 / std::sqrt(1.0 + k * k);
    const Vec3 trial[4] = {inv_z * (n + k * P), inv_z * (n - k * P), inv_z * (n + k * Q),
                           inv_z * (n - k * Q)};
    int best = -1;
    Extremes best_e = cur;
    for (int j = 0; j < 4; ++j)
    {
      Extremes e = cur; // nearest vertices of the current normal as hints
      ++result.evaluations;
      if (scan(trial[j], va, na, vb, nb, best_e.gap(), e))
      {
        best = j;
        best_e = e;
      }
    }
    if (best < 0)
      return false;
    // The chosen axis turns with the normal; the other one stays orthogonal.
    const Vec3& axis = best < 2 ? P : Q;
    n = trial[best].normalized();
    p = (axis - axis.dot(n) * n).normalized();
    q = n.cross(p);
    cur = best_e;
    return true;
  }

  /// The hill-climb of Figure 10: keep k while some perturbation helps,
  /// halve it when none does, stop when none helps at k_min or when the gap
  /// exceeds the contact tolerance. Before k is halved, a step of the same
  /// size along the ridge the normal may sit on is tried (ridge_step).
  void climb()
  {
    double k = k_max;
    bool turned = false;
    // A ridge step shorter than k has reached the top along its direction;
    // repeating it would only creep (the pieces in the band of k need not be
    // level yet), so the next failure of round() halves k instead.
    bool ridge = true;
    while (result.iterations < settings.max_iterations)
    {
      bool moved = round(k, turned);
      if (moved)
        ridge = true;
      else if (ridge && ridge_step(k))
      {
        moved = true;
        ridge = ridge_step_was_full;
      }
      if (moved)
      {
        if (too_far())
          return;
      }
      else
      {
        if (k <= k_min)
          return;
        k = std::max(0.5 * k, k_min);
        ridge = true;
      }
      turned = !turned;
    }
  }

  /// The gap, as a function of the normal, is the lower envelope of one
  /// linear piece per pair (vertex of A, vertex of B). Where several pieces
  /// meet it has a sharp ridge, and when the ridge runs in none of the eight
  /// directions of round() the hill-climb stalls there, sometimes far from
  /// the summit (tests/contact/common_plane_06 met errors of 0.6 rad in the
  /// normal). This is an addition to the manual's scheme: the steepest
  /// ascent direction among the vertices that a turn of k can bring level
  /// with the nearest ones (the band of in_band() with k) is the unit
  /// vector towards the point of least norm of the convex hull of the
  /// differences b - a projected on the plane (found by Gilbert's algorithm
  /// in two dimensions); if the hull holds the origin there is no ascent.
  /// Tries one step of at most k that way; returns whether it raised the
  /// gap.
  bool ridge_step(double k)
  {
    constexpr unsigned int capacity = 32;
    double a_p[capacity], a_q[capacity], b_p[capacity], b_q[capacity];
    unsigned int m_a = 0, m_b = 0;
    double scale = 0.0; // of the projected offsets, for the tests below
    const Vec3 a0 = va[cur.i_a], b0 = vb[cur.i_b];
    for (unsigned int i = 0; i < na; ++i)
      if (in_band(cur.a_max - n.dot(va[i]), va[i] - a0, k))
      {
        if (m_a == capacity)
          return false;
        const Vec3 d = va[i] - a0;
        a_p[m_a] = p.dot(d);
        a_q[m_a] = q.dot(d);
        scale = std::max(scale, std::abs(a_p[m_a]) + std::abs(a_q[m_a]));
        ++m_a;
      }
    for (unsigned int i = 0; i < nb; ++i)
      if (in_band(n.dot(vb[i]) - cur.b_min, vb[i] - b0, k))
      {
        if (m_b == capacity)
          return false;
        const Vec3 d = vb[i] - a0;
        b_p[m_b] = p.dot(d);
        b_q[m_b] = q.dot(d);
        scale = std::max(scale, std::abs(b_p[m_b]) + std::abs(b_q[m_b]));
        ++m_b;
      }
    if (m_a * m_b < 2)
      return false; // one vertex each: round() has seen a smooth summit

    // Gilbert's algorithm: the point of the hull nearest the origin. The
    // support point in direction -v is (nearest b along v) - (farthest a).
    const auto support = [&](double vx, double vy, double& sx, double& sy)
    {
      unsigned int ia = 0, ib = 0;
      for (unsigned int i = 1; i < m_a; ++i)
        if (vx * a_p[i] + vy * a_q[i] > vx * a_p[ia] + vy * a_q[ia])
          ia = i;
      for (unsigned int i = 1; i < m_b; ++i)
        if (vx * b_p[i] + vy * b_q[i] < vx * b_p[ib] + vy * b_q[ib])
          ib = i;
      sx = b_p[ib] - a_p[ia];
      sy = b_q[ib] - a_q[ia];
    };
    double wx[3], wy[3]; // the simplex
    unsigned int m = 1;
    wx[0] = b_p[0] - a_p[0];
    wy[0] = b_q[0] - a_q[0];
    double vx = wx[0], vy = wy[0];
    for (int iteration = 0; iteration < 32; ++iteration)
    {
      double sx, sy;
      support(vx, vy, sx, sy);
      const double vv = vx * vx + vy * vy;
      if (vv <= 1e-18 * scale * scale)
        return false; // no ascent worth a step (the origin is on the hull)
      if (vv - (vx * sx + vy * sy) <= 1e-12 * vv)
        break; // v is the point of least norm
      wx[m] = sx;
      wy[m++] = sy;
      if (m == 3)
      {
        // Origin inside the triangle: no ascent direction.
        const auto side = [&](unsigned int i, unsigned int j)
        { return wx[i] * wy[j] - wy[i] * wx[j]; };
        const double s0 = side(0, 1), s1 = side(1, 2), s2 = side(2, 0);
        if ((s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0))
          return false;
      }
      // Nearest point of the simplex: the best over its points and edges.
      double best = std::numeric_limits<double>::infinity();
      unsigned int keep[2] = {0, 0}, n_keep = 1;
      for (unsigned int i = 0; i < m; ++i)
        for (unsigned int j = i; j < m; ++j)
        {
          double px = wx[i], py = wy[i];
          if (j != i)
          {
            const double ex = wx[j] - wx[i], ey = wy[j] - wy[i];
            const double ee = ex * ex + ey * ey;
            if (!(ee > 0.0))
              continue;
            const double t = -(wx[i] * ex + wy[i] * ey) / ee;
            if (t <= 0.0 || t >= 1.0)
              continue; // an end point: seen on its own
            px += t * ex;
            py += t * ey;
          }
          const double d = px * px + py * py;
          if (d < best)
          {
            best = d;
            vx = px;
            vy = py;
            keep[0] = i;
            keep[1] = j;
            n_keep = j != i ? 2 : 1;
          }
        }
      const double kx[2] = {wx[keep[0]], wx[keep[1]]}, ky[2] = {wy[keep[0]], wy[keep[1]]};
      for (unsigned int i = 0; i < n_keep; ++i)
      {
        wx[i] = kx[i];
        wy[i] = ky[i];
      }
      m = n_keep;
    }
    // Along the great circle n cos t + d sin t the pieces that meet at the
    // ridge give gap(t) = gap cos t + slope sin t, largest at
    // tan t = slope / gap: a longer step would climb over the top and zigzag
    // across the ridge for little gain. The step must keep a tenth of the
    // gain its slope promises, else the band of k was too coarse (k gets
    // halved).
    const double slope = std::sqrt(vx * vx + vy * vy);
    const double t_top = cur.gap() > 0.0 ? std::atan2(slope, cur.gap()) : k;
    const double t = std::min(k, t_top);
    ridge_step_was_full = t_top >= k;
    const Vec3 direction = (vx * p + vy * q) / slope;
    ++result.iterations;
    ++result.evaluations;
    const Vec3 trial = std::cos(t) * n + std::sin(t) * direction;
    Extremes e = cur;
    if (!scan(trial, va, na, vb, nb, cur.gap() + 0.1 * slope * std::sin(t), e))
      return false;
    n = trial.normalized();
    p = (direction - direction.dot(n) * n).normalized();
    q = n.cross(p);
    cur = e;
    return true;
  }

  /// Whether a vertex that lies `depth` behind its block's nearest level
  /// (depth >= 0 away from the other block) and at offset `d` from the
  /// block's nearest vertex is in the touching band: depth <= touch_tolerance
  /// + k_min |d|, the second term being what an error of k_min in the normal
  /// makes of the distance (no square root). `k` replaces k_min for the
  /// wider bands of polish().
  bool in_band(double depth, const Vec3& d, double k) const
  {
    const double x = depth - settings.touch_tolerance;
    return x <= 0.0 || x * x <= k * k * d.squaredNorm();
  }
  bool in_band(double depth, const Vec3& d) const { return in_band(depth, d, k_min); }

  /// The exact normal of the features that touch the plane now: the vertices
  /// of A within the band of A's nearest vertex, and likewise for B. If their
  /// offsets from the nearest vertex span a plane (a face, or two crossing
  /// edges) the normal is orthogonal to it; if they span a line (an edge
  /// against a vertex or a parallel edge) the normal is the part of the
  /// vertex-to-vertex vector orthogonal to it; if both blocks touch with one
  /// vertex it is the vertex-to-vertex direction. Kept when the gap does not
  /// get smaller. Three scans of the vertex sets per band.
  ///
  /// When the touching features have just changed (an existing contact whose
  /// blocks moved, e.g. two parallel edges becoming an edge against a face)
  /// the normal can be off by much more than k_min, and the band of k_min
  /// misses vertices of the new features. So on failure the band is widened
  /// (8, 64 and 512 times k_min, the last about k_max) before giving up.
  bool polish()
  {
    for (const double factor : {1.0, 8.0, 64.0, 512.0})
      if (polish(factor * k_min))
        return true;
    return false;
  }

  bool polish(double k_band)
  {
    const Vec3 a0 = va[cur.i_a], b0 = vb[cur.i_b];
    // First scan: the offset e1 of largest length.
    Vec3 e1 = Vec3::Zero();
    double e1_sq = 0.0;
    for (unsigned int i = 0; i < na; ++i)
      if (in_band(cur.a_max - n.dot(va[i]), va[i] - a0, k_band))
      {
        const Vec3 d = va[i] - a0;
        if (d.squaredNorm() > e1_sq)
        {
          e1 = d;
          e1_sq = d.squaredNorm();
        }
      }
    for (unsigned int i = 0; i < nb; ++i)
      if (in_band(n.dot(vb[i]) - cur.b_min, vb[i] - b0, k_band))
      {
        const Vec3 d = vb[i] - b0;
        if (d.squaredNorm() > e1_sq)
        {
          e1 = d;
          e1_sq = d.squaredNorm();
        }
      }
    const Vec3 ab = b0 - a0;
    Vec3 w;
    if (e1_sq == 0.0)
      w = ab; // vertex against vertex
    else
    {
      // Second scan: the offset farthest from the line of e1.
      Vec3 cross = Vec3::Zero();
      double cross_sq = 0.0;
      for (unsigned int i = 0; i < na; ++i)
        if (in_band(cur.a_max - n.dot(va[i]), va[i] - a0, k_band))
        {
          const Vec3 c = e1.cross(va[i] - a0);
          if (c.squaredNorm() > cross_sq)
          {
            cross = c;
            cross_sq = c.squaredNorm();
          }
        }
      for (unsigned int i = 0; i < nb; ++i)
        if (in_band(n.dot(vb[i]) - cur.b_min, vb[i] - b0, k_band))
        {
          const Vec3 c = e1.cross(vb[i] - b0);
          if (c.squaredNorm() > cross_sq)
          {
            cross = c;
            cross_sq = c.squaredNorm();
          }
        }
      // |e1 x d| / |e1| is the distance of d from the line of e1.
      if (cross_sq > 1e-18 * e1_sq * e1_sq)
        w = cross; // a face or two crossing edges
      else
        w = ab - (ab.dot(e1) / e1_sq) * e1; // an edge against a vertex or edge
    }
    const double w_norm = w.norm();
    if (!(w_norm > 0.0))
      return false;
    w /= w_norm;
    if (w.dot(n) < 0.0)
      w = -w;
    // Keep w unless it lowers the gap by more than round-off: when the
    // hill-climb already sits on the answer, w is the more exact of the two.
    const double round_off = 1e-15 * (std::abs(cur.a_max) + std::abs(cur.b_min));
    Extremes e = cur;
    ++result.evaluations;
    if (!scan(w, va, na, vb, nb, cur.gap() - round_off, e))
      return false;
    n = w;
    orthonormal_basis(n, p, q);
    cur = e;
    return true;
  }

  Vec3 n, p, q;
  Extremes cur;
  bool ridge_step_was_full = true;
  const Vec3* va;
  unsigned int na;
  const Vec3* vb;
  unsigned int nb;
  const CommonPlaneSettings& settings;
  CommonPlaneResult& result;
  const double k_min, k_max;
};

} // namespace

CommonPlaneResult update_common_plane(CommonPlane& cp, const Vec3* va, unsigned int na,
                                      const Vec3* vb, unsigned int nb,
                                      const CommonPlaneSettings& settings, bool new_contact)
{
  assert(na > 0 && nb > 0);
  assert(settings.k_min_degrees > 0.0 && settings.k_min_degrees <= settings.k_max_degrees);
  CommonPlaneResult result;
  Search s(cp.normal, va, na, vb, nb, settings, result);

  if (!s.too_far())
  {
    if (new_contact)
    {
      s.climb();
      if (settings.polish && !s.too_far())
        result.polished = s.polish();
    }
    else
    {
      // An existing contact: the normal is usually right or nearly so. The
      // exact solve for the touching features (if enabled) follows small
      // motions; then the four k_min perturbations (and a k_min step along a
      // ridge) decide whether the full hill-climb is needed at all.
      if (settings.polish)
        result.polished = s.polish();
      if (!s.too_far() && (s.round(s.k_min, false) || s.ridge_step(s.k_min)))
      {
        result.polished = false;
        if (!s.too_far())
          s.climb();
        if (settings.polish && !s.too_far())
          result.polished = s.polish();
      }
    }
  }

  const Vec3& n = s.n;
  const Extremes& e = s.cur;
  result.gap = e.gap();
  result.within_tolerance = !s.too_far();
  cp.normal = n;
  // eqs. 6-8: the plane goes midway between the nearest vertices of A and B.
  const double mid = 0.5 * (e.a_max + e.b_min);
  cp.reference += (mid - n.dot(cp.reference)) * n;
  if (!result.within_tolerance)
    return result;

  // Touching vertices: those within the band of the nearest level of their
  // block or, for overlapping blocks, of the plane itself. The first two of
  // each block are kept for the crossing point of two edges.
  const Vec3 a0 = va[e.i_a], b0 = vb[e.i_b];
  const double level_a = std::min(e.a_max, mid), level_b = std::max(e.b_min, mid);
  Vec3 sum_a = Vec3::Zero(), sum_b = Vec3::Zero();
  unsigned int first_a[2] = {0, 0}, first_b[2] = {0, 0};
  for (unsigned int i = 0; i < na; ++i)
    if (s.in_band(level_a - n.dot(va[i]), va[i] - a0))
    {
      if (result.n_touching_a < 2)
        first_a[result.n_touching_a] = i;
      ++result.n_touching_a;
      sum_a += va[i];
    }
  for (unsigned int i = 0; i < nb; ++i)
    if (s.in_band(n.dot(vb[i]) - level_b, vb[i] - b0))
    {
      if (result.n_touching_b < 2)
        first_b[result.n_touching_b] = i;
      ++result.n_touching_b;
      sum_b += vb[i];
    }
  result.type = classify_contact(result.n_touching_a, result.n_touching_b);

  if (result.gap > 0.0)
  {
    // eq. 9: midway between the nearest vertices. When a block has several
    // equally near vertices (an edge or a face) this is made definite, and
    // closer to where the blocks will touch: a vertex or an edge facing a
    // face or an edge of higher dimension gives its own centre; two crossing
    // edges give the midpoint of their closest points; otherwise the mean
    // of both sides. Then the point is put back on the mid-plane.
    const unsigned int dim_a = std::min(result.n_touching_a, 3u);
    const unsigned int dim_b = std::min(result.n_touching_b, 3u);
    const Vec3 mean_a = sum_a / result.n_touching_a, mean_b = sum_b / result.n_touching_b;
    Vec3 reference = 0.5 * (mean_a + mean_b);
    if (dim_a < dim_b)
      reference = mean_a;
    else if (dim_b < dim_a)
      reference = mean_b;
    else if (dim_a == 2)
    {
      // Closest points of the lines p + s u and r + t v.
      const Vec3 &p0 = va[first_a[0]], &r0 = vb[first_b[0]];
      const Vec3 u = va[first_a[1]] - p0, v = vb[first_b[1]] - r0, w = p0 - r0;
      const double uu = u.dot(u), uv = u.dot(v), vv = v.dot(v), uw = u.dot(w), vw = v.dot(w);
      const double det = uu * vv - uv * uv;
      if (det > 1e-12 * uu * vv) // not parallel
      {
        const double s_a = std::clamp((uv * vw - vv * uw) / det, 0.0, 1.0);
        const double t_b = std::clamp((uu * vw - uv * uw) / det, 0.0, 1.0);
        reference = 0.5 * (p0 + s_a * u + r0 + t_b * v);
      }
    }
    cp.reference = reference + (mid - n.dot(reference)) * n;
  }
  return result;
}

} // namespace talus
