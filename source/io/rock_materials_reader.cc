#include "rock_materials_reader.h"

#include "joint_materials_reader.h" // check_group_name

#include <deal.II/base/utilities.h>

#include <algorithm>

namespace talus
{

namespace
{
namespace P = dealii::Patterns;
/// kg/m^3: no material is denser than this (osmium: 22,590).
constexpr double max_density = 1e5;
} // namespace

void declare_zone_constants(ParameterFile& prm)
{
  prm.declare("Zone model", "elastic", P::Selection("elastic|mohr-coulomb"),
              "elastic or mohr-coulomb", "Constitutive model of the zones.");
  prm.declare("Young's modulus", "5e10", P::Double(), "a number > 0 (Pa)", "E (Pa).");
  prm.declare("Poisson's ratio", "0.25", P::Double(), "a number > -1 and < 0.5", "nu.");
  prm.declare("Friction angle", "30", P::Double(), "a number from 0 to below 90 (degrees)",
              "phi of the Mohr-Coulomb zones (degrees).");
  prm.declare("Dilation angle", "0", P::Double(), "a number from 0 to the friction angle (degrees)",
              "psi of the Mohr-Coulomb zones (degrees).");
  prm.declare("Cohesion", "0", P::Double(), "a number >= 0 (Pa)",
              "c of the Mohr-Coulomb zones (Pa).");
  prm.declare("Tensile strength", "0", P::Double(), "a number >= 0 (Pa)",
              "Tension cut-off of the Mohr-Coulomb zones (Pa).");
}

void parse_zone_constants(ParameterFile& prm, const std::string& section, ZoneMaterial& m,
                          bool inherit)
{
  const std::map<std::string, unsigned int> lines = prm.lines();
  const auto set = [&](const char* entry)
  { return !inherit || lines.count(section + " / " + entry) > 0; };
  const double E = set("Young's modulus") ? prm.get_double("Young's modulus") : m.young();
  const double nu = set("Poisson's ratio") ? prm.get_double("Poisson's ratio") : m.poisson();
  if (!(E > 0.0))
    throw prm.error("Young's modulus", "must be positive", "a number > 0 (Pa)");
  if (!(nu > -1.0 && nu < 0.5))
    throw prm.error("Poisson's ratio", "must lie between -1 and 0.5 (0.5 would be incompressible)",
                    "a number > -1 and < 0.5");
  if (set("Young's modulus") || set("Poisson's ratio"))
    m.set_young_poisson(E, nu);
  if (set("Zone model"))
    m.model = prm.get("Zone model") == "elastic" ? ZoneModel::elastic : ZoneModel::mohr_coulomb;
  if (set("Friction angle"))
    m.friction_angle = prm.get_double("Friction angle");
  if (!(m.friction_angle >= 0.0 && m.friction_angle < 90.0))
    throw prm.error("Friction angle", "must be at least 0 and below 90 degrees",
                    "a number from 0 to below 90");
  if (set("Dilation angle"))
    m.dilation_angle = prm.get_double("Dilation angle");
  if (!(m.dilation_angle >= 0.0 && m.dilation_angle <= m.friction_angle))
    throw prm.error("Dilation angle", "must lie between 0 and the friction angle",
                    "a number from 0 to the friction angle (degrees)");
  if (set("Cohesion"))
    m.cohesion = prm.get_double("Cohesion");
  if (!(m.cohesion >= 0.0))
    throw prm.error("Cohesion", "must not be negative", "a number >= 0 (Pa)");
  if (set("Tensile strength"))
    m.tensile_strength = prm.get_double("Tensile strength");
  if (!(m.tensile_strength >= 0.0))
    throw prm.error("Tensile strength", "must not be negative", "a number >= 0 (Pa)");
}

void declare_rock_material(ParameterFile& prm, const std::string& section)
{
  prm.enter(section);
  prm.declare("Name", "", P::Anything(), "a name", "The material's name, for the summary.");
  prm.declare("Groups", "", P::List(P::Anything()), "group names separated by commas",
              "Blocks of these groups are made of this material (none: a material that stages "
              "give with 'Rock materials').");
  prm.declare("Density", "0", P::Double(), "a number > 0 and at most 1e5 (kg/m^3)",
              "kg/m^3 (not set: that of 'Material').");
  declare_zone_constants(prm);
  prm.leave();
}

void parse_rock_material(ParameterFile& prm, const std::string& section, Scene& scene)
{
  prm.enter(section);
  RockMaterialSpec r;
  r.section = section;
  r.name = prm.get("Name");
  if (r.name.empty())
    throw prm.error("Name", "is missing", "a name");
  for (const RockMaterialSpec& other : scene.rock_materials)
    if (other.name == r.name)
      throw prm.error("Name", "'" + r.name + "' is taken by '" + other.section + "'",
                      "a name that no other rock material has");
  for (const std::string& g : dealii::Utilities::split_string_list(prm.get("Groups")))
  {
    check_group_name(prm, "Groups", scene, g);
    if (const RockMaterialSpec* other = scene.rock_material_of(g))
      throw prm.error("Groups", "names '" + g + "', which '" + other->section + "' has already",
                      "groups of no other rock material");
    r.groups.push_back(g);
  }
  r.density = prm.lines().count(section + " / Density") ? prm.get_double("Density") : scene.density;
  if (!(r.density > 0.0 && r.density <= max_density))
    throw prm.error("Density", "must be positive and at most 1e5",
                    "a number > 0 and at most 1e5 (kg/m^3)");
  r.zone = scene.deformable.material;
  parse_zone_constants(prm, section, r.zone, true);
  r.zone.density = r.density;
  scene.rock_materials.push_back(r);
  prm.leave();
}

} // namespace talus
