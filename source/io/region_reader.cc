#include "region_reader.h"

#include <deal.II/base/utilities.h>

#include <cmath>
#include <stdexcept>

namespace talus
{

namespace
{
namespace P = dealii::Patterns;

const std::string vec3_allowed = "three numbers separated by commas, e.g. 0, 0, 0";
const std::string planes_allowed = "planes separated by ';', each a point and its outward normal: "
                                   "'x, y, z, nx, ny, nz' (m)";
const std::string profile_allowed =
    "at least three corners of a convex polygon separated by ';', each 'u, v' (m)";

/// The numbers of `text` between ';', `count` in each group, finite.
std::vector<std::vector<double>> groups_of_numbers(const std::string& text, unsigned int count,
                                                   bool& good)
{
  std::vector<std::vector<double>> groups;
  good = true;
  for (const std::string& group : dealii::Utilities::split_string_list(text, ';'))
  {
    std::vector<double> numbers;
    for (const std::string& word : dealii::Utilities::split_string_list(group, ','))
    {
      char* end = nullptr;
      const double x = std::strtod(word.c_str(), &end);
      if (word.empty() || *end != '\0' || !std::isfinite(x))
        good = false;
      numbers.push_back(x);
    }
    if (numbers.size() != count)
      good = false;
    groups.push_back(numbers);
  }
  return groups;
}
} // namespace

void declare_region(ParameterFile& prm, const std::string& what)
{
  prm.declare("Shape", "box", P::Selection("box|cylinder|half-space|polyhedron|prism|sphere"),
              "box, cylinder, half-space, polyhedron, prism or sphere",
              "The shape of " + what + ".");
  prm.declare("Corner min", "0, 0, 0", P::List(P::Double(), 3, 3, ","), vec3_allowed,
              "box: lower corner (m).");
  prm.declare("Corner max", "1, 1, 1", P::List(P::Double(), 3, 3, ","), vec3_allowed,
              "box: upper corner (m).");
  prm.declare("Axis start", "0, 0, 0", P::List(P::Double(), 3, 3, ","), vec3_allowed,
              "cylinder and prism: centre of one end (m).");
  prm.declare("Axis end", "0, 1, 0", P::List(P::Double(), 3, 3, ","), vec3_allowed,
              "cylinder and prism: centre of the other end (m).");
  prm.declare("Radius", "1", P::Double(), "a number > 0 (m)",
              "cylinder: radius of the circle the prism is inscribed in; sphere: radius of the "
              "sphere its facets touch (m).");
  prm.declare("Centre", "0, 0, 0", P::List(P::Double(), 3, 3, ","), vec3_allowed,
              "sphere: its centre (m).");
  prm.declare("Facets", "48", P::Integer(8, 1024), "an integer from 8 to 1024",
              "sphere: number of flat faces, each touching the sphere.");
  prm.declare("Sides", "16", P::Integer(3, 1024), "an integer from 3 to 1024",
              "cylinder: number of flat faces around it.");
  prm.declare("Point", "0, 0, 0", P::List(P::Double(), 3, 3, ","), vec3_allowed,
              "half-space: a point on its plane (m).");
  prm.declare("Normal", "0, 0, 1", P::List(P::Double(), 3, 3, ","), vec3_allowed,
              "half-space: the side of the plane it takes.");
  prm.declare("Planes", "", P::Anything(), planes_allowed,
              "polyhedron: the planes whose inner sides it is.");
  prm.declare("Profile", "", P::Anything(), profile_allowed,
              "prism: its section across the axis, u to the right looking along the axis from "
              "'Axis start', v up (m from the axis).");
}

ConvexRegion parse_region(const ParameterFile& prm, const Box& brick, std::string& description)
{
  const std::string shape = prm.get("Shape");
  if (shape == "box")
  {
    const Box b{prm.get_vec3("Corner min"), prm.get_vec3("Corner max")};
    for (unsigned int d = 0; d < 3; ++d)
      if (!(b.hi[d] > b.lo[d]))
        throw prm.error("Corner max", "must exceed 'Corner min' in every coordinate",
                        "a box with hi > lo in x, y and z");
    description = "box";
    return ConvexRegion::box(b);
  }
  if (shape == "cylinder" || shape == "prism")
  {
    const Vec3 a = prm.get_vec3("Axis start"), b = prm.get_vec3("Axis end");
    if (!((b - a).norm() > 0.0))
      throw prm.error("Axis end", "coincides with 'Axis start'", "a point other than Axis start");
    if (shape == "cylinder")
    {
      const double radius = prm.get_double("Radius");
      if (!(radius > 0.0))
        throw prm.error("Radius", "must be positive", "a number > 0 (m)");
      const unsigned int sides = static_cast<unsigned int>(prm.get_integer("Sides"));
      description =
          "cylinder of radius " + prm.get("Radius") + " m, " + std::to_string(sides) + " sides";
      return ConvexRegion::cylinder(a, b, radius, sides);
    }
    bool good = true;
    const auto corners = groups_of_numbers(prm.get("Profile"), 2, good);
    if (!good || corners.size() < 3)
      throw prm.error("Profile", "'" + prm.get("Profile") + "' is not a list of corners",
                      profile_allowed);
    std::vector<std::pair<double, double>> profile;
    for (const std::vector<double>& c : corners)
      profile.emplace_back(c[0], c[1]);
    try
    {
      ConvexRegion r = ConvexRegion::prism(a, b, profile);
      description = "prism of " + std::to_string(profile.size()) + " sides";
      return r;
    }
    catch (const std::invalid_argument& e)
    {
      throw prm.error("Profile", std::string("the polygon ") + e.what(), profile_allowed);
    }
  }
  std::vector<std::pair<Vec3, Vec3>> planes;
  if (shape == "sphere")
  {
    const double radius = prm.get_double("Radius");
    if (!(radius > 0.0))
      throw prm.error("Radius", "must be positive", "a number > 0 (m)");
    const unsigned int facets = static_cast<unsigned int>(prm.get_integer("Facets"));
    description = "sphere of radius " + prm.get("Radius") + " m, " + std::to_string(facets) +
                  " facets";
    return ConvexRegion::sphere(prm.get_vec3("Centre"), radius, facets, brick);
  }
  if (shape == "half-space")
  {
    const Vec3 normal = prm.get_vec3("Normal");
    if (!(normal.norm() > 0.0))
      throw prm.error("Normal", "is zero", "three numbers not all zero");
    // The region's outward normal points away from the side it takes.
    planes.emplace_back(prm.get_vec3("Point"), -normal);
    description = "half-space";
  }
  else
  {
    bool good = true;
    for (const std::vector<double>& p : groups_of_numbers(prm.get("Planes"), 6, good))
      if (good)
        planes.emplace_back(Vec3(p[0], p[1], p[2]), Vec3(p[3], p[4], p[5]));
    if (!good || planes.empty())
      throw prm.error("Planes", "'" + prm.get("Planes") + "' is not a list of planes",
                      planes_allowed);
    for (std::size_t i = 0; i < planes.size(); ++i)
      if (!(planes[i].second.norm() > 0.0))
        throw prm.error("Planes", "plane " + std::to_string(i + 1) + " has a zero normal",
                        planes_allowed);
    description = "polyhedron of " + std::to_string(planes.size()) + " planes";
  }
  ConvexRegion r = ConvexRegion::polyhedron(planes, brick);
  if (!(r.volume > 0.0))
    throw prm.error(shape == "half-space" ? "Point" : "Planes",
                    "the " + shape + " holds no part of the model's brick",
                    "a region that holds part of the brick");
  return r;
}

} // namespace talus
