#include <talus/contact/contact_origin.h>

#include <cmath>

namespace talus
{

namespace
{
/// Whether block b has a face whose outward normal lies within 10 degrees
/// of `direction`; then `origin` is that of the closest such face.
bool facing_origin(const BlockModel& m, unsigned int b, const Vec3& direction, int& origin)
{
  const double cos_limit = std::cos(10.0 * M_PI / 180.0);
  double best = cos_limit;
  bool found = false;
  for (unsigned int f = m.face_start[b]; f < m.face_start[b + 1]; ++f)
    if (const double c = m.face_normal[f].dot(direction); c > best)
    {
      best = c;
      origin = m.face_origin.empty() ? 0 : m.face_origin[f];
      found = true;
    }
  return found;
}
} // namespace

int contact_joint_origin(const BlockModel& m, const ContactSet& cs, unsigned int c)
{
  const Vec3& n = cs.plane[c].normal; // from A towards B
  int a = 0, b = 0;
  facing_origin(m, cs.block_a[c], n, a);
  facing_origin(m, cs.block_b[c], -n, b);
  // A side without a facing face (a vertex or an edge) or with a face of no
  // joint leaves the other side's answer; two different joints, none.
  if (a == 0 || a == b)
    return b;
  return b == 0 ? a : 0;
}

} // namespace talus
