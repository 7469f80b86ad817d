#pragma once

#include <talus/geometry/plane.h>

#include <limits>
#include <string>
#include <vector>

namespace talus
{

/// The phreatic surface z_w(x, y) of a scene's water ('Water'): none, a
/// plane (a horizontal level, or inclined through a point with a normal) or
/// heights on a rectilinear grid interpolated bilinearly and held at the
/// edge values outside the grid.
class WaterTable
{
public:
  enum class Kind
  {
    none,
    plane,
    table
  };

  WaterTable() = default;
  /// z_w = level everywhere.
  static WaterTable level(double z);
  /// The plane through `point` with normal `normal` (which must not be
  /// horizontal: normal.z() != 0).
  static WaterTable plane(const Vec3& point, const Vec3& normal);
  /// Heights z_w at the grid points (x[i], y[j]), row-major: heights[j * nx + i];
  /// x and y strictly ascending (one value of either: constant along it).
  static WaterTable grid(std::vector<double> x, std::vector<double> y, std::vector<double> heights);

  Kind kind() const { return kind_; }
  bool empty() const { return kind_ == Kind::none; }
  /// Whether z_w is linear in x and y (then a pressure is linear over a
  /// plane face and integrates in closed form).
  bool linear() const { return kind_ == Kind::plane; }

  /// z_w(x, y), m.
  double height(double x, double y) const
  {
    if (kind_ == Kind::plane)
      return a_ + bx_ * x + by_ * y;
    return table_height(x, y);
  }
  /// The highest z_w anywhere (m): faces wholly above it carry no water.
  double highest() const { return highest_; }
  /// The smallest spacing of the table's grid (m; 0 for a plane).
  double spacing() const { return spacing_; }

  /// For the summary: "level 12 m", "plane through (..) with normal (..)",
  /// "table of 3 x 2 heights from 0 to 12 m".
  std::string description() const;

private:
  double table_height(double x, double y) const;
  Kind kind_ = Kind::none;
  double a_ = 0.0, bx_ = 0.0, by_ = 0.0; ///< plane: z_w = a + bx x + by y
  std::vector<double> x_, y_, h_;        ///< table
  double highest_ = -1e300, spacing_ = 0.0;
  std::string description_;
};

/// A scene's water: the phreatic surface and the water's unit weight.
/// Every block face (and every boundary face of a deformable block's
/// zones) below the surface carries p = rho_w g (z_w(x, y) - z).
struct WaterSpec
{
  WaterTable table;
  double density = 1000.0; ///< kg/m^3
  /// Pa, a fixed water pressure on the faces made by the scene's i-th
  /// joint set (and j-th single joint) in place of the surface's; NaN (or
  /// missing) for none.
  std::vector<double> joint_set_pressure, joint_pressure;
  /// The fixed pressure of faces of BlockModel::face_origin `origin`, or NaN.
  double fixed_pressure(int origin) const
  {
    const std::vector<double>& p = origin > 0 ? joint_set_pressure : joint_pressure;
    const std::size_t i = static_cast<std::size_t>(origin > 0 ? origin - 1 : -origin - 1);
    return origin != 0 && i < p.size() ? p[i] : std::numeric_limits<double>::quiet_NaN();
  }
  bool has_fixed_pressures() const
  {
    for (const std::vector<double>* v : {&joint_set_pressure, &joint_pressure})
      for (double p : *v)
        if (p == p)
          return true;
    return false;
  }
  bool active() const { return !table.empty() || has_fixed_pressures(); }
};

} // namespace talus
