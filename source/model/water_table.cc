#include <talus/model/water_table.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace talus
{

WaterTable WaterTable::level(double z)
{
  WaterTable t;
  t.kind_ = Kind::plane;
  t.a_ = z;
  t.highest_ = z;
  std::ostringstream text;
  text << "level " << z << " m";
  t.description_ = text.str();
  return t;
}

WaterTable WaterTable::plane(const Vec3& point, const Vec3& normal)
{
  // n . (x - p) = 0 solved for z.
  WaterTable t;
  t.kind_ = Kind::plane;
  t.bx_ = -normal.x() / normal.z();
  t.by_ = -normal.y() / normal.z();
  t.a_ = point.z() - t.bx_ * point.x() - t.by_ * point.y();
  // A tilted plane rises without end; the faces' own heights bound it.
  t.highest_ = (t.bx_ == 0.0 && t.by_ == 0.0) ? t.a_ : 1e300;
  std::ostringstream text;
  text << "plane through (" << point.x() << ", " << point.y() << ", " << point.z()
       << ") m with normal (" << normal.x() << ", " << normal.y() << ", " << normal.z() << ")";
  t.description_ = text.str();
  return t;
}

WaterTable WaterTable::grid(std::vector<double> x, std::vector<double> y,
                            std::vector<double> heights)
{
  WaterTable t;
  t.kind_ = Kind::table;
  t.x_ = std::move(x);
  t.y_ = std::move(y);
  t.h_ = std::move(heights);
  t.highest_ = *std::max_element(t.h_.begin(), t.h_.end());
  t.spacing_ = 1e300;
  for (const std::vector<double>* axis : {&t.x_, &t.y_})
    for (std::size_t i = 1; i < axis->size(); ++i)
      t.spacing_ = std::min(t.spacing_, (*axis)[i] - (*axis)[i - 1]);
  if (t.spacing_ == 1e300)
    t.spacing_ = 0.0; // a single point: a level
  std::ostringstream text;
  text << "table of " << t.x_.size() << " x " << t.y_.size() << " heights from "
       << *std::min_element(t.h_.begin(), t.h_.end()) << " to " << t.highest_ << " m";
  t.description_ = text.str();
  return t;
}

std::string WaterTable::description() const
{
  return kind_ == Kind::none ? "none" : description_;
}

namespace
{
/// The cell [v[i], v[i+1]] holding `s` (clamped to the ends) and the
/// fraction of the way across it.
void locate(const std::vector<double>& v, double s, std::size_t& i, double& t)
{
  if (v.size() == 1 || s <= v.front())
  {
    i = 0;
    t = 0.0;
    return;
  }
  if (s >= v.back())
  {
    i = v.size() - 2;
    t = 1.0;
    return;
  }
  i = static_cast<std::size_t>(std::upper_bound(v.begin(), v.end(), s) - v.begin()) - 1;
  t = (s - v[i]) / (v[i + 1] - v[i]);
}
} // namespace

double WaterTable::table_height(double x, double y) const
{
  if (kind_ == Kind::none)
    return -1e300;
  std::size_t i, j;
  double s, t;
  locate(x_, x, i, s);
  locate(y_, y, j, t);
  const std::size_t nx = x_.size();
  const std::size_t i1 = std::min(i + 1, nx - 1), j1 = std::min(j + 1, y_.size() - 1);
  const double h00 = h_[j * nx + i], h10 = h_[j * nx + i1];
  const double h01 = h_[j1 * nx + i], h11 = h_[j1 * nx + i1];
  return (1 - t) * ((1 - s) * h00 + s * h10) + t * ((1 - s) * h01 + s * h11);
}

} // namespace talus
