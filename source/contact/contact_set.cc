#include <talus/contact/contact_set.h>
#include <talus/contact/joint_material_rule.h>
#include <talus/joint/continuously_yielding.h>

#include <talus/contact/contact_polygon.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <tuple>

namespace talus
{

namespace
{

/// The side of one block facing the common plane.
struct FacingSide
{
  std::vector<Point2> hull; ///< touching vertices projected, convex hull
  bool has_face = false;    ///< a face lies on the plane
  Vec3 face_normal;         ///< that face's outward normal
  double face_offset = 0.0;
  double deepest = 0.0; ///< height of the vertex nearest the other block
};

FacingSide facing_side(const BlockModel& m, unsigned int block, const Vec3& n, const Vec3& c,
                       const Vec3& u, const Vec3& v, double band, double sign, bool rigid)
{
  // sign = +1 for block A (below the plane), -1 for B.
  FacingSide s;
  std::vector<Point2> points;
  s.deepest = -sign * 1e300;
  for (unsigned int i = m.vertex_start[block]; i < m.vertex_start[block + 1]; ++i)
  {
    const Vec3 r = m.vertex[i] - c;
    const double h = n.dot(r);
    if (sign * h >= -band)
    {
      points.emplace_back(u.dot(r), v.dot(r));
      s.deepest = sign > 0 ? std::max(s.deepest, h) : std::min(s.deepest, h);
    }
  }
  s.hull = convex_hull(points, contact_polygon_relative_tolerance * polygon_size(points, {}));
  // The face most nearly facing the other block, if it lies on the plane.
  double best = 0.0;
  unsigned int best_face = 0;
  for (unsigned int f = m.face_start[block]; f < m.face_start[block + 1]; ++f)
  {
    const double d = sign * m.face_normal[f].dot(n);
    if (d > best)
    {
      best = d;
      best_face = f;
    }
  }
  // A rigid block's face nearly on the plane faces it whole, its far
  // vertices open: the region then turns with the block. Taking only the
  // vertices within the band made the region jump whenever a vertex of a
  // tilted face crossed it, and the sub-contacts' areas (so their forces
  // at the same overlap) jump with it, which creates or destroys energy
  // (deep in an overlap, tens of percent of it). A deformable block's
  // faces are its boundary triangles: its side stays the band's vertices.
  if (rigid && !points.empty() && best > 0.99)
  {
    points.clear();
    for (unsigned int k = m.face_loop_start[best_face]; k < m.face_loop_start[best_face + 1]; ++k)
    {
      const Vec3 r = m.vertex[m.face_vertex[k]] - c;
      points.emplace_back(u.dot(r), v.dot(r));
    }
    s.hull = convex_hull(points, contact_polygon_relative_tolerance * polygon_size(points, {}));
  }
  if (s.hull.size() >= 3 && best > 0.99)
  {
    s.has_face = true;
    s.face_normal = m.face_normal[best_face];
    s.face_offset = s.face_normal.dot(m.vertex[m.face_vertex[m.face_loop_start[best_face]]]);
  }
  return s;
}

/// Height along n (from the reference point) of a block's surface above the
/// plane point q = c + x u + y v.
double surface_height(const FacingSide& s, const Vec3& n, const Vec3& point)
{
  if (!s.has_face)
    return s.deepest;
  return (s.face_offset - s.face_normal.dot(point)) / s.face_normal.dot(n);
}

/// The best of the separating-axis candidates of two convex blocks (face
/// normals of either, cross products of their edges) as the starting plane
/// of a new contact, when it beats the centroid line of eq. 5. The
/// hill-climb of eq. 10 then starts next to the answer: from the centroid
/// line alone it can stop on a plane that makes touching slivers overlap.
/// Returns whether `cp` was changed.
bool separating_axis_start(const BlockModel& m, unsigned int a, unsigned int b, CommonPlane& cp)
{
  const auto gap_along = [&](const Vec3& n, double& top_a, double& bottom_b)
  {
    top_a = -1e300;
    bottom_b = 1e300;
    for (unsigned int v = m.vertex_start[a]; v < m.vertex_start[a + 1]; ++v)
      top_a = std::max(top_a, n.dot(m.vertex[v]));
    for (unsigned int v = m.vertex_start[b]; v < m.vertex_start[b + 1]; ++v)
      bottom_b = std::min(bottom_b, n.dot(m.vertex[v]));
    return bottom_b - top_a;
  };
  double top_a, bottom_b;
  double best = gap_along(cp.normal, top_a, bottom_b);
  Vec3 best_n = cp.normal;
  const Vec3 ab = m.centroid[b] - m.centroid[a];
  const auto consider = [&](Vec3 n)
  {
    const double length = n.norm();
    if (length < 1e-12)
      return;
    n /= length;
    if (n.dot(ab) < 0.0)
      n = -n;
    double ta, bb;
    const double g = gap_along(n, ta, bb);
    if (g > best)
    {
      best = g;
      best_n = n;
    }
  };
  for (unsigned int f = m.face_start[a]; f < m.face_start[a + 1]; ++f)
    consider(m.face_normal[f]);
  for (unsigned int f = m.face_start[b]; f < m.face_start[b + 1]; ++f)
    consider(m.face_normal[f]);
  const auto edges = [&](unsigned int blk)
  {
    std::vector<Vec3> e;
    for (unsigned int f = m.face_start[blk]; f < m.face_start[blk + 1]; ++f)
      for (unsigned int k = m.face_loop_start[f]; k < m.face_loop_start[f + 1]; ++k)
      {
        const unsigned int next = k + 1 < m.face_loop_start[f + 1] ? k + 1 : m.face_loop_start[f];
        e.push_back(m.vertex[m.face_vertex[next]] - m.vertex[m.face_vertex[k]]);
      }
    return e;
  };
  const std::vector<Vec3> ea = edges(a), eb = edges(b);
  if (ea.size() * eb.size() <= 4096) // rigid polyhedra; not the surface of a meshed block
    for (const Vec3& x : ea)
      for (const Vec3& y : eb)
        consider(x.cross(y));
  if (best_n == cp.normal)
    return false;
  gap_along(best_n, top_a, bottom_b);
  const Vec3 mid = 0.5 * (m.centroid[a] + m.centroid[b]);
  cp.normal = best_n;
  cp.reference = mid + (0.5 * (top_a + bottom_b) - best_n.dot(mid)) * best_n;
  return true;
}

} // namespace

void ContactSet::try_create(unsigned int a, unsigned int b, const BlockModel& m,
                            const ContactSettings& settings)
{
  if (slot_of_pair_.count(pair_key(a, b)))
    return;
  CommonPlane cp = initial_common_plane(m.centroid[a], m.centroid[b]);
  // From a separating-axis start the plane is already close: refine it as
  // an existing contact's (exact solve and fine steps first).
  const bool near = separating_axis_start(m, a, b, cp);
  CommonPlaneSettings cps = settings.common_plane;
  cps.contact_tolerance = settings.tolerance;
  ++planes_computed_;
  const CommonPlaneResult r = update_common_plane(
      cp, &m.vertex[m.vertex_start[a]], m.vertex_start[a + 1] - m.vertex_start[a],
      &m.vertex[m.vertex_start[b]], m.vertex_start[b + 1] - m.vertex_start[b], cps, !near);
  if (!r.within_tolerance || r.gap > settings.tolerance)
    return;
  unsigned int c;
  if (!free_.empty())
  {
    c = free_.back();
    free_.pop_back();
    block_a[c] = a;
    block_b[c] = b;
    plane[c] = cp;
    gap[c] = r.gap;
    type[c] = r.type;
    alive[c] = 1;
    material[c] = 0;
    path_at_update[c] = -1.0;
  }
  else
  {
    c = n_slots();
    block_a.push_back(a);
    block_b.push_back(b);
    plane.push_back(cp);
    gap.push_back(r.gap);
    type.push_back(r.type);
    alive.push_back(1);
    material.push_back(0);
    path_at_update.push_back(-1.0);
  }
  if (settings.materials != nullptr)
    material[c] = settings.materials->material(m, *this, c);
  slot_of_pair_[pair_key(a, b)] = c;
  ++n_alive_;
  pair_order_stale_ = true;
}

void ContactSet::remove(unsigned int c)
{
  slot_of_pair_.erase(pair_key(block_a[c], block_b[c]));
  alive[c] = 0;
  free_.push_back(c);
  --n_alive_;
  // The order stays sorted with the slot dead in it: every reader skips
  // dead slots, and a slot is only reused by a new contact, which sorts.
}

void ContactSet::sort_by_pair()
{
  if (!pair_order_stale_)
    return;
  std::vector<std::pair<std::uint64_t, unsigned int>> keyed;
  keyed.reserve(n_alive_);
  for (unsigned int c = 0; c < n_slots(); ++c)
    if (alive[c])
      keyed.emplace_back(pair_key(block_a[c], block_b[c]), c);
  std::sort(keyed.begin(), keyed.end());
  pair_order_.clear();
  for (const auto& [key, c] : keyed)
    pair_order_.push_back(c);
  pair_order_stale_ = false;
}

void ContactSet::remove_contacts_of(const std::vector<char>& gone)
{
  for (unsigned int c = 0; c < n_slots(); ++c)
    if (alive[c] && (gone[block_a[c]] || gone[block_b[c]]))
      remove(c);
}

unsigned int ContactSet::append_slot(std::uint64_t key)
{
  const unsigned int c = n_slots();
  block_a.push_back(static_cast<unsigned int>(key >> 32));
  block_b.push_back(static_cast<unsigned int>(key & 0xffffffffu));
  alive.push_back(1);
  slot_of_pair_[key] = c;
  ++n_alive_;
  pair_order_stale_ = true;
  return c;
}

void ContactSet::set_old_subcontacts_aside()
{
  old_start_.assign(n_slots(), 0);
  old_end_.assign(n_slots(), 0);
  for (unsigned int i = 0; i < n_subcontacts(); ++i)
  {
    const unsigned int c = sc_contact[i];
    if (old_end_[c] == 0)
      old_start_[c] = i;
    old_end_[c] = i + 1;
  }
  // Swapped with the arrays of the last update, which keep their memory.
  std::swap(old_un_, sc_un);
  std::swap(old_fn_, sc_fn);
  std::swap(old_fs_, sc_fs);
  std::swap(old_us_, sc_us);
  std::swap(old_dilation_, sc_dilation);
  std::swap(old_yield_, sc_yield);
  std::swap(old_state_, sc_state);
  std::swap(old_position_, sc_position);
  std::swap(old_area_, sc_area);
  std::swap(old_node_, sc_node);
  std::swap(old_weight_, sc_weight);
  old_normal_.resize(n_slots());
  for (unsigned int c = 0; c < n_slots(); ++c)
    old_normal_[c] = plane[c].normal;
  clear_subcontacts();
}

void ContactSet::clear_subcontacts()
{
  sc_contact.clear();
  sc_position.clear();
  sc_area.clear();
  sc_un.clear();
  sc_fn.clear();
  sc_fs.clear();
  sc_us.clear();
  sc_dilation.clear();
  sc_yield.clear();
  sc_state.clear();
  sc_material.clear();
  sc_fresh.clear();
  sc_node.clear();
  sc_weight.clear();
}

void ContactSet::update(const BlockModel& m, const ContactSettings& settings,
                        const std::vector<double>* path, ContactTrade* trade)
{
  set_old_subcontacts_aside();
  CommonPlaneSettings cps = settings.common_plane;
  cps.contact_tolerance = settings.tolerance;
  // In block-pair order (sort_by_pair); a removal leaves the slot dead in it.
  sort_by_pair();
  if (trade != nullptr)
  {
    update_across_ranks(m, settings, cps, path, *trade);
    return;
  }
  for (const unsigned int c : pair_order_)
    if (alive[c])
      update_contact(c, m, settings, cps, path);
}

void ContactSet::update_contact(unsigned int c, const BlockModel& m,
                                const ContactSettings& settings, const CommonPlaneSettings& cps,
                                const std::vector<double>* path)
{
  const unsigned int a = block_a[c], b = block_b[c];
  if (path != nullptr)
  {
    const double travelled = (*path)[a] + (*path)[b];
    if (path_at_update[c] >= 0.0 &&
        travelled - path_at_update[c] < settings.update_motion_fraction * settings.tolerance)
    {
      // Neither block has moved enough to change the plane: keep the
      // sub-contacts as they are.
      for (unsigned int o = old_start_[c]; o < old_end_[c]; ++o)
      {
        sc_contact.push_back(c);
        sc_position.push_back(old_position_[o]);
        sc_area.push_back(old_area_[o]);
        sc_un.push_back(old_un_[o]);
        sc_fn.push_back(old_fn_[o]);
        for (int d = 0; d < 3; ++d)
          sc_fs.push_back(old_fs_[3 * o + d]);
        for (int d = 0; d < 3; ++d)
          sc_us.push_back(old_us_[3 * o + d]);
        if (settings.dilation)
          sc_dilation.push_back(old_dilation_[o]);
        if (settings.yielding)
          for (unsigned int k = 0; k < yield_state_size; ++k)
            sc_yield.push_back(old_yield_[yield_state_size * o + k]);
        sc_state.push_back(old_state_[o]);
        sc_material.push_back(material[c]);
        sc_fresh.push_back(0);
        if (has_deformable())
          for (int k = 0; k < 6; ++k)
          {
            sc_node.push_back(old_node_[6 * o + k]);
            sc_weight.push_back(old_weight_[6 * o + k]);
          }
      }
      return;
    }
    path_at_update[c] = travelled;
  }
  ++planes_computed_;
  const CommonPlaneResult r = update_common_plane(
      plane[c], &m.vertex[m.vertex_start[a]], m.vertex_start[a + 1] - m.vertex_start[a],
      &m.vertex[m.vertex_start[b]], m.vertex_start[b + 1] - m.vertex_start[b], cps, false);
  gap[c] = r.gap;
  type[c] = r.type;
  if (!r.within_tolerance || r.gap > settings.tolerance)
  {
    remove(c);
    return;
  }
  // Eq. 13: keep the reference point on both blocks.
  Vec3& ref = plane[c].reference;
  const Vec3& n = plane[c].normal;
  for (unsigned int blk : {a, b})
    for (unsigned int f = m.face_start[blk]; f < m.face_start[blk + 1]; ++f)
    {
      const Vec3& nf = m.face_normal[f];
      const double d = nf.dot(ref - m.vertex[m.face_vertex[m.face_loop_start[f]]]);
      if (d > 0.0)
        ref += (n * n.dot(nf) - nf) * d;
    }
  const std::size_t first = sc_position.size();
  build_subcontacts(c, m, settings, old_normal_[c]);
  // Carry the shear over from the nearest old sub-contact of this contact.
  for (std::size_t i = first; i < sc_position.size(); ++i)
  {
    double best = 1e300;
    unsigned int match = 0;
    for (unsigned int o = old_start_[c]; o < old_end_[c]; ++o)
    {
      const double d = (old_position_[o] - sc_position[i]).squaredNorm();
      if (d < best)
      {
        best = d;
        match = o;
      }
    }
    if (old_end_[c] > old_start_[c] && best < 0.25 * sc_area[i])
    {
      // Eq. 23 in exact form: turn the shear force with the plane.
      const Eigen::Quaterniond turn = Eigen::Quaterniond::FromTwoVectors(old_normal_[c], n);
      Vec3 fs = turn * Vec3(old_fs_[3 * match], old_fs_[3 * match + 1], old_fs_[3 * match + 2]);
      fs -= n * n.dot(fs);
      // The shear stress is carried, not the force: the spring's energy
      // |fs|^2 / (2 ks A) then follows the area, so sub-contacts rebuilt
      // with other areas (or more of them) neither make nor lose energy
      // and the contact's total shear force follows its area.
      fs *= sc_area[i] / old_area_[match];
      Vec3 us = turn * Vec3(old_us_[3 * match], old_us_[3 * match + 1], old_us_[3 * match + 2]);
      us -= n * n.dot(us);
      for (int d = 0; d < 3; ++d)
      {
        sc_fs[3 * i + d] = fs[d];
        sc_us[3 * i + d] = us[d];
      }
      if (settings.dilation)
        sc_dilation[i] = old_dilation_[match];
      if (settings.yielding)
      {
        // The plastic shear and reversal ratio go with the shear; the
        // loading direction turns with the plane as the force does.
        const double* y = &old_yield_[yield_state_size * match];
        double* to = &sc_yield[yield_state_size * i];
        to[plastic_shear_displacement] = y[plastic_shear_displacement];
        to[reversal_ratio] = y[reversal_ratio];
        Vec3 dir =
            turn * Vec3(y[loading_direction], y[loading_direction + 1], y[loading_direction + 2]);
        dir -= n * n.dot(dir);
        const double length = dir.norm();
        for (int d = 0; d < 3; ++d)
          to[loading_direction + d] = length > 0.0 ? dir[d] / length : 0.0;
      }
      sc_state[i] = old_state_[match];
    }
  }
}

void ContactSet::build_subcontacts(unsigned int c, const BlockModel& m,
                                   const ContactSettings& settings, const Vec3&)
{
  const unsigned int a = block_a[c], b = block_b[c];
  const Vec3 n = plane[c].normal;
  const Vec3 ref = plane[c].reference;
  const Vec3 u = n.unitOrthogonal();
  const Vec3 v = n.cross(u);
  const double band = settings.tolerance;
  const bool rigid_a = !(has_deformable() && (*is_deformable_)[a]);
  const bool rigid_b = !(has_deformable() && (*is_deformable_)[b]);
  const FacingSide sa = facing_side(m, a, n, ref, u, v, band, +1.0, rigid_a);
  const FacingSide sb = facing_side(m, b, n, ref, u, v, band, -1.0, rigid_b);

  // The contact region on the plane: where the two facing sides overlap.
  // Faces in jointed rock share edges with their neighbours' faces: lengths
  // below a fraction of the faces' size are round-off (contact_polygon.h).
  const double eps = contact_polygon_relative_tolerance * polygon_size(sa.hull, sb.hull);
  std::vector<Point2> region;
  if (sb.hull.size() >= 3)
    region = clip_convex(sa.hull, sb.hull, eps);
  else if (sa.hull.size() >= 3)
    region = clip_convex(sb.hull, sa.hull, eps);
  else if (sa.hull.size() == 2 && sb.hull.size() == 2)
  {
    // Edge to edge: the crossing point of the two edges (or their nearest
    // points' midpoint when they do not cross in projection).
    const Point2 p = sa.hull[0], r = sa.hull[1] - sa.hull[0];
    const Point2 q = sb.hull[0], s = sb.hull[1] - sb.hull[0];
    const double den = r.x() * s.y() - r.y() * s.x();
    if (std::abs(den) > 1e-14 * r.norm() * s.norm())
    {
      const double t = ((q - p).x() * s.y() - (q - p).y() * s.x()) / den;
      const double w = ((q - p).x() * r.y() - (q - p).y() * r.x()) / den;
      if (t >= 0 && t <= 1 && w >= 0 && w <= 1)
        region.push_back(p + t * r);
    }
  }
  else if (!sa.hull.empty() && !sb.hull.empty())
    region.push_back(0.5 * (sa.hull[0] + sb.hull[0]));

  if (region.empty())
    return;
  // Each vertex of the region carries its share of the area, centred on
  // the region's area centroid (vertex_areas).
  std::vector<double> weight = vertex_areas(region);
  const double area = region.size() >= 3 ? polygon_area(region) : 0.0;
  if (!(region.size() >= 3 && area > 0.0))
  {
    const double point_area =
        settings.point_area_fraction * std::pow(std::min(m.volume[a], m.volume[b]), 2.0 / 3.0);
    std::fill(weight.begin(), weight.end(), point_area);
  }
  // What carries each sub-contact on side A and side B (deformable blocks
  // only): gridpoints and weights, -1 for a rigid side.
  struct Seed
  {
    Point2 at;
    double area;
    int node[6] = {-1, -1, -1, -1, -1, -1};
    double w[6] = {0, 0, 0, 0, 0, 0};
    Vec3 point[2]; ///< where the carrying gridpoints are, side A and B
  };
  std::vector<Seed> seeds;
  const bool da = has_deformable() && (*is_deformable_)[a];
  const bool db = has_deformable() && (*is_deformable_)[b];
  const auto project = [&](const Vec3& x) { return Point2(u.dot(x - ref), v.dot(x - ref)); };
  // The point of a deformable side under q: barycentric on the facing
  // boundary triangle whose projection holds q, else its nearest facing
  // gridpoint.
  const auto support =
      [&](unsigned int blk, double sign, const Point2& q, int* node, double* w, Vec3& point)
  {
    double nearest = 1e300;
    for (unsigned int f = m.face_start[blk]; f < m.face_start[blk + 1]; ++f)
    {
      // A face seen edge-on (a side of the block, its normal turned a
      // hair towards the plane by the motion) projects onto a sliver whose
      // barycentric weights are meaningless: facing means facing.
      if (sign * m.face_normal[f].dot(n) <= 0.1)
        continue;
      const unsigned int k = m.face_loop_start[f];
      const Point2 p0 = project(m.vertex[m.face_vertex[k]]),
                   p1 = project(m.vertex[m.face_vertex[k + 1]]),
                   p2 = project(m.vertex[m.face_vertex[k + 2]]);
      const double total = cross2(p0, p1, p2);
      if (std::abs(total) <= 0.0)
        continue;
      const double l0 = cross2(q, p1, p2) / total, l1 = cross2(p0, q, p2) / total,
                   l2 = 1.0 - l0 - l1;
      const double outside = std::max({-l0, -l1, -l2, 0.0});
      if (outside < nearest)
      {
        nearest = outside;
        const double l[3] = {l0, l1, l2};
        for (int j = 0; j < 3; ++j)
        {
          node[j] = (*vertex_gridpoint_)[m.face_vertex[k + j]];
          w[j] = std::clamp(l[j], 0.0, 1.0);
        }
        const double sum = w[0] + w[1] + w[2];
        point = Vec3::Zero();
        for (int j = 0; j < 3; ++j)
        {
          w[j] /= sum;
          point += w[j] * m.vertex[m.face_vertex[k + j]];
        }
      }
    }
    if (node[0] < 0)
    {
      // No facing triangle (a vertex or edge touching): the nearest vertex.
      double best = 1e300;
      for (unsigned int vtx = m.vertex_start[blk]; vtx < m.vertex_start[blk + 1]; ++vtx)
      {
        const double d =
            (project(m.vertex[vtx]) - q).squaredNorm() + std::pow(n.dot(m.vertex[vtx] - ref), 2);
        if (d < best)
        {
          best = d;
          node[0] = (*vertex_gridpoint_)[vtx];
          w[0] = 1.0;
          point = m.vertex[vtx];
        }
      }
    }
  };
  const bool has_area = region.size() >= 3 && area > 0.0;
  if (has_area && (da || db))
  {
    // Sub-contacts at the gridpoints of deformable sides that lie over the
    // contact region, each with the part over the region of its third of
    // the facing boundary triangles around it (the text after eq. 25); two
    // deformable sides make two sets of springs in parallel, each with half
    // the area. Without that cut, a gridpoint where a face meets two
    // blocks would carry its whole area twice: twice the stiffness the
    // time step of eq. 85 allows for, and a gridpoint that rattles.
    const double share = da && db ? 0.5 : 1.0;
    double region_min[2] = {1e300, 1e300}, region_max[2] = {-1e300, -1e300};
    for (const Point2& p : region)
      for (int d = 0; d < 2; ++d)
      {
        region_min[d] = std::min(region_min[d], p[d]);
        region_max[d] = std::max(region_max[d], p[d]);
      }
    for (const auto& [blk, sign, side] : {std::tuple<unsigned int, double, int>{a, 1.0, 0},
                                          std::tuple<unsigned int, double, int>{b, -1.0, 1}})
    {
      if (!(*is_deformable_)[blk])
        continue;
      std::vector<double> vertex_area(m.vertex_start[blk + 1] - m.vertex_start[blk], 0.0);
      for (unsigned int f = m.face_start[blk]; f < m.face_start[blk + 1]; ++f)
      {
        if (sign * m.face_normal[f].dot(n) < 0.5)
          continue;
        const unsigned int k = m.face_loop_start[f];
        const Vec3& x0 = m.vertex[m.face_vertex[k]];
        const double area =
            0.5 *
            (m.vertex[m.face_vertex[k + 1]] - x0).cross(m.vertex[m.face_vertex[k + 2]] - x0).norm();
        Point2 p[3];
        bool apart = false; // the triangle's box misses the region's
        for (int j = 0; j < 3; ++j)
          p[j] = project(m.vertex[m.face_vertex[k + j]]);
        for (int d = 0; d < 2; ++d)
          apart |= std::max({p[0][d], p[1][d], p[2][d]}) < region_min[d] - eps ||
                   std::min({p[0][d], p[1][d], p[2][d]}) > region_max[d] + eps;
        const double projected = 0.5 * cross2(p[0], p[1], p[2]);
        if (apart || projected == 0.0)
          continue;
        // The part of the triangle over the region, and where its area
        // centre lies in the triangle (barycentric l).
        std::vector<Point2> part = projected > 0.0 ? std::vector<Point2>{p[0], p[1], p[2]}
                                                   : std::vector<Point2>{p[0], p[2], p[1]};
        part = clip_convex(std::move(part), region, eps);
        const double part_area = part.size() >= 3 ? polygon_area(part) : 0.0;
        if (!(part_area > 0.0))
          continue;
        const Point2 c = polygon_centroid(part);
        const double l[3] = {cross2(c, p[1], p[2]) / (2.0 * projected),
                             cross2(p[0], c, p[2]) / (2.0 * projected),
                             cross2(p[0], p[1], c) / (2.0 * projected)};
        // Each corner takes the load a uniform pressure on that part gives
        // it: the integral of its linear shape function over the part,
        // which is the part's area times l at its centre. The zones' own
        // split of a whole triangle (a third each, or for hexahedral zones
        // the mean of both overlays' splits) weights it, so that a whole
        // triangle gives each corner its share, and the parts' areas add up
        // to the region's.
        double s[3], weighted = 0.0;
        for (int q = 0; q < 3; ++q)
        {
          s[q] = m.face_corner_share.empty() ? 1.0 / 3.0 : m.face_corner_share[f][q];
          weighted += s[q] * std::max(l[q], 0.0);
        }
        const double over = std::min(part_area / std::abs(projected), 1.0) * area;
        for (int q = 0; q < 3; ++q)
          vertex_area[m.face_vertex[k + q] - m.vertex_start[blk]] +=
              over * (weighted > 1e-12 ? s[q] * std::max(l[q], 0.0) / weighted
                                       : s[q] / (s[0] + s[1] + s[2]));
      }
      for (unsigned int vtx = m.vertex_start[blk]; vtx < m.vertex_start[blk + 1]; ++vtx)
      {
        const double h = n.dot(m.vertex[vtx] - ref);
        if (vertex_area[vtx - m.vertex_start[blk]] <= 0.0 || sign * h < -band)
          continue;
        // A gridpoint takes part when some of its area lies over the
        // region: the areas then add up to the region's, also where the
        // region's edge passes between gridpoints (a face on two blocks, a
        // block over an edge), at the price of a spring that may stand a
        // fraction of a zone off the edge.
        const Point2 q = project(m.vertex[vtx]);
        Seed seed;
        seed.at = q;
        seed.area = share * vertex_area[vtx - m.vertex_start[blk]];
        seed.node[3 * side] = (*vertex_gridpoint_)[vtx];
        seed.w[3 * side] = 1.0;
        seed.point[side] = m.vertex[vtx];
        const unsigned int other = side == 0 ? b : a;
        if ((*is_deformable_)[other])
          support(other, -sign, q, seed.node + 3 * (1 - side), seed.w + 3 * (1 - side),
                  seed.point[1 - side]);
        seeds.push_back(seed);
      }
    }
  }
  else
  {
    // A point contact (edge on edge, a corner) on a deformable side is
    // carried by a few gridpoints: its area may not exceed half of what
    // they stand for on the faces towards the contact, or its spring would
    // pass the joint stiffness that the time step (eq. 85) allows them.
    // (With no face towards it, a corner touching, all their faces.)
    const auto carried_area = [&](unsigned int blk, double sign, const int* node, const double* w,
                                  bool area_from_all_faces)
    {
      double area = 0.0;
      for (unsigned int f = m.face_start[blk]; f < m.face_start[blk + 1]; ++f)
      {
        if (sign * m.face_normal[f].dot(n) <= (area_from_all_faces ? -2.0 : 0.1))
          continue;
        const unsigned int k = m.face_loop_start[f];
        const Vec3& x0 = m.vertex[m.face_vertex[k]];
        const double third = (m.vertex[m.face_vertex[k + 1]] - x0)
                                 .cross(m.vertex[m.face_vertex[k + 2]] - x0)
                                 .norm() /
                             6.0;
        for (int j = 0; j < 3; ++j)
          for (int c = 0; c < 3; ++c)
            if (node[c] >= 0 && node[c] == (*vertex_gridpoint_)[m.face_vertex[k + j]])
              area += w[c] * third;
      }
      return area;
    };
    const auto carried = [&](unsigned int blk, double sign, const int* node, const double* w)
    {
      const double facing = carried_area(blk, sign, node, w, false);
      return facing > 0.0 ? facing : carried_area(blk, sign, node, w, true);
    };
    for (std::size_t i = 0; i < region.size(); ++i)
    {
      Seed seed;
      seed.at = region[i];
      seed.area = weight[i];
      if (da)
      {
        support(a, 1.0, seed.at, seed.node, seed.w, seed.point[0]);
        seed.area = std::min(seed.area, 0.5 * carried(a, 1.0, seed.node, seed.w));
      }
      if (db)
      {
        support(b, -1.0, seed.at, seed.node + 3, seed.w + 3, seed.point[1]);
        seed.area = std::min(seed.area, 0.5 * carried(b, -1.0, seed.node + 3, seed.w + 3));
      }
      seeds.push_back(seed);
    }
  }

  for (const Seed& seed : seeds)
  {
    if (!(seed.area > 0.0))
      continue;
    const Vec3 on_plane = ref + seed.at.x() * u + seed.at.y() * v;
    // Height of each side's surface above the plane point: the carrying
    // gridpoints' for a deformable side.
    const auto height = [&](const FacingSide& side, const int* node, const Vec3& point)
    { return node[0] < 0 ? surface_height(side, n, on_plane) : n.dot(point - ref); };
    const double ha = height(sa, seed.node, seed.point[0]);
    const double hb = height(sb, seed.node + 3, seed.point[1]);
    const Vec3 at = on_plane + 0.5 * (ha + hb) * n;
    const double un = hb - ha;
    double fn = 0.0;
    Vec3 fs = Vec3::Zero();
    if (settings.initial_stress != nullptr && seed.area > 0.0)
    {
      // The in-situ stress across the plane: A pushes B with -sigma n per
      // unit area; the closure that carries it under the total normal
      // displacement formulation.
      double sg[6];
      settings.initial_stress->at(at.z(), sg);
      const Vec3 t(sg[0] * n.x() + sg[3] * n.y() + sg[5] * n.z(),
                   sg[3] * n.x() + sg[1] * n.y() + sg[4] * n.z(),
                   sg[5] * n.x() + sg[4] * n.y() + sg[2] * n.z());
      fn = std::max(-n.dot(t) * seed.area, 0.0);
      fs = -(t - n.dot(t) * n) * seed.area;
    }
    sc_contact.push_back(c);
    sc_position.push_back(at);
    sc_area.push_back(seed.area);
    sc_un.push_back(un);
    sc_fn.push_back(fn);
    for (int d = 0; d < 3; ++d)
      sc_fs.push_back(fs[d]);
    for (int d = 0; d < 3; ++d)
      sc_us.push_back(0.0);
    // The normal offset holds the closure that carries the initial stress
    // (geometric re-initialisation of un keeps it), later also dilation.
    if (settings.dilation)
    {
      const JointProperties* joint =
          settings.joints != nullptr ? &(*settings.joints)[material[c]] : nullptr;
      if (joint != nullptr && joint->model == JointModel::continuously_yielding)
        sc_dilation.push_back(fn > 0.0 ? NormalStressLaw::of(*joint).closure(fn / seed.area) : 0.0);
      else
        sc_dilation.push_back(fn > 0.0 ? fn / (settings.kn[material[c]] * seed.area) : 0.0);
    }
    if (settings.yielding)
      for (unsigned int k = 0; k < yield_state_size; ++k)
        sc_yield.push_back(0.0);
    sc_state.push_back(0);
    sc_material.push_back(material[c]);
    sc_fresh.push_back(1);
    if (has_deformable())
      for (int k = 0; k < 6; ++k)
      {
        sc_node.push_back(seed.node[k]);
        sc_weight.push_back(seed.w[k]);
      }
  }
}

} // namespace talus
