#include "water_reader.h"

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace talus
{

namespace
{
namespace P = dealii::Patterns;
const char* const vec3_allowed = "three numbers separated by commas, e.g. 0, 0, 1";
const char* const list_allowed = "numbers separated by commas (m), strictly ascending";

/// The grid values of 'X values' or 'Y values': at least one, ascending.
std::vector<double> grid_axis(const ParameterFile& prm, const char* name)
{
  const std::vector<double> v = prm.get_doubles(name);
  if (v.empty())
    throw prm.error(name, "is missing for 'Phreatic surface = table'", list_allowed);
  for (std::size_t i = 1; i < v.size(); ++i)
    if (!(v[i] > v[i - 1]))
      throw prm.error(
          name, "is not strictly ascending (" + number(v[i - 1]) + " then " + number(v[i]) + ")",
          list_allowed);
  return v;
}
/// 'Joint set pressures' or 'Joint pressures': "N, p; N, p" for the
/// subsections "<kind> N" of the scene (`sections`), into `pressure`
/// (indexed like `sections`, NaN where none is given).
std::vector<double> joint_pressures(const ParameterFile& prm, const char* name,
                                    const std::string& kind,
                                    const std::vector<std::string>& sections)
{
  std::vector<double> pressure(sections.size(), std::numeric_limits<double>::quiet_NaN());
  const std::string text = prm.get(name);
  const std::string allowed = "pairs 'N, p' separated by ';': the number N of a '" + kind +
                              " N' of the file and a water pressure p >= 0 (Pa)";
  for (const std::string& pair : dealii::Utilities::split_string_list(text, ';'))
  {
    const std::vector<std::string> parts = dealii::Utilities::split_string_list(pair, ',');
    char* end = nullptr;
    const double p = parts.size() == 2 ? std::strtod(parts[1].c_str(), &end) : 0.0;
    if (parts.size() != 2 || end == nullptr || *end != '\0' || !std::isfinite(p) ||
        parts[0].empty() || parts[0].find_first_not_of("0123456789") != std::string::npos)
      throw prm.error(name, "'" + pair + "' is not a joint number and a pressure", allowed);
    if (!(p >= 0.0))
      throw prm.error(name, "gives a negative pressure, " + number(p) + " Pa", allowed);
    const std::string section = kind + " " + parts[0];
    const auto it = std::find(sections.begin(), sections.end(), section);
    if (it == sections.end())
      throw prm.error(name, "names '" + section + "', which the file does not have", allowed);
    pressure[static_cast<std::size_t>(it - sections.begin())] = p;
  }
  return pressure;
}
} // namespace

void declare_water(ParameterFile& prm)
{
  prm.enter("Water");
  prm.declare("Density", "1000", P::Double(), "a number > 0 and at most 1e5 (kg/m^3)",
              "Density of the water (kg/m^3).");
  prm.declare("Phreatic surface", "none", P::Selection("none|plane|table"), "none, plane or table",
              "none: no water; plane: a horizontal 'Level' or a plane through 'Point' with "
              "'Normal'; table: heights on a grid ('X values', 'Y values', 'Heights').");
  prm.declare("Level", "0", P::Double(), "a number (m)", "Height z_w of a horizontal surface (m).");
  prm.declare("Point", "0, 0, 0", P::List(P::Double(), 3, 3, ","), vec3_allowed,
              "A point of an inclined surface (m).");
  prm.declare("Normal", "0, 0, 1", P::List(P::Double(), 3, 3, ","), vec3_allowed,
              "Normal of an inclined surface (not horizontal).");
  prm.declare("X values", "", P::List(P::Double(), 0, P::List::max_int_value, ","), list_allowed,
              "x of the table's grid lines (m), ascending.");
  prm.declare("Y values", "", P::List(P::Double(), 0, P::List::max_int_value, ","), list_allowed,
              "y of the table's grid lines (m), ascending.");
  prm.declare("Heights", "", P::List(P::Double(), 0, P::List::max_int_value, ","),
              "one height z_w (m) per grid point, row by row: ny rows of nx numbers",
              "z_w at the grid points, rows of constant y in ascending y, each in ascending x.");
  prm.declare("Joint set pressures", "", P::Anything(),
              "pairs 'N, p' separated by ';': the number N of a 'Joint set N' of the file and a "
              "water pressure p >= 0 (Pa)",
              "A water pressure of its own (Pa) on the faces that joint set N made, in place of "
              "the phreatic surface's: 'N, p; N, p'. Rigid blocks only.");
  prm.declare("Joint pressures", "", P::Anything(),
              "pairs 'N, p' separated by ';': the number N of a 'Joint N' of the file and a "
              "water pressure p >= 0 (Pa)",
              "The same for single joints ('Joint N').");
  prm.leave();
}

void parse_water(ParameterFile& prm, Scene& scene)
{
  parse_water(prm, scene, scene.solver.water);
}

void parse_water(ParameterFile& prm, const Scene& scene, WaterSpec& w)
{
  prm.enter("Water");
  w = WaterSpec();
  w.density = prm.get_double("Density");
  if (!(w.density > 0.0 && w.density <= 1e5))
    throw prm.error("Density", "must be positive and at most 1e5",
                    "a number > 0 and at most 1e5 (kg/m^3)");
  const std::string surface = prm.get("Phreatic surface");
  const auto set = [&](const char* entry) { return prm.is_set(entry); };
  if (surface != "none" && !(scene.solver.gravity.norm() > 0.0))
    throw prm.error("Phreatic surface", "gives water without weight: 'Gravity' of 'Solver' is zero",
                    "none, or a gravity that is not zero");
  if (surface == "plane")
  {
    if (set("Level") && (set("Point") || set("Normal")))
      throw prm.error("Level", "is given with 'Point' or 'Normal'",
                      "either 'Level' (a horizontal surface) or 'Point' and 'Normal'");
    if (set("Level"))
      w.table = WaterTable::level(prm.get_double("Level"));
    else if (set("Point") || set("Normal"))
    {
      const Vec3 normal = prm.get_vec3("Normal");
      // A plane within 0.01 degree of vertical gives no height.
      if (!(normal.norm() > 0.0) || !(std::abs(normal.z()) > 1.7e-4 * normal.norm()))
        throw prm.error("Normal", "is horizontal or zero: a vertical plane has no height z_w(x, y)",
                        "a normal with a vertical component, e.g. 0, 0, 1");
      w.table = WaterTable::plane(prm.get_vec3("Point"), normal);
    }
    else
      throw prm.error("Phreatic surface", "is plane but neither 'Level' nor 'Point' is set",
                      "'Level' (m), or 'Point' and 'Normal'");
  }
  else if (surface == "table")
  {
    std::vector<double> x = grid_axis(prm, "X values"), y = grid_axis(prm, "Y values");
    std::vector<double> h = prm.get_doubles("Heights");
    if (h.size() != x.size() * y.size())
      throw prm.error("Heights",
                      "has " + std::to_string(h.size()) + " values for a grid of " +
                          std::to_string(x.size()) + " x values and " + std::to_string(y.size()) +
                          " y values",
                      std::to_string(y.size()) + " rows of " + std::to_string(x.size()) + " = " +
                          std::to_string(x.size() * y.size()) + " heights (m)");
    w.table = WaterTable::grid(std::move(x), std::move(y), std::move(h));
  }
  w.joint_set_pressure =
      joint_pressures(prm, "Joint set pressures", "Joint set", scene.joint_set_sections);
  w.joint_pressure = joint_pressures(prm, "Joint pressures", "Joint", scene.joint_plane_sections);
  prm.leave();
}

} // namespace talus
