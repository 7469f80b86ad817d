#include "joint_materials_reader.h"

#include <deal.II/base/utilities.h>

#include <algorithm>

namespace talus
{

namespace
{
namespace P = dealii::Patterns;

const std::string stiffness_allowed = "a number > 0 and at most 1e16 (Pa/m)";

std::string material_names(const Scene& scene)
{
  std::string names;
  for (const std::string& n : scene.joint_material_names)
    names += (names.empty() ? "'" : ", '") + n + "'";
  return names;
}
} // namespace

void declare_joint_properties(ParameterFile& prm)
{
  prm.declare("Normal stiffness", "1e10", P::Double(), stiffness_allowed, "kn (Pa/m).");
  prm.declare("Shear stiffness", "1e10", P::Double(), stiffness_allowed, "ks (Pa/m).");
  prm.declare("Friction angle", "30", P::Double(0.0, 89.999),
              "a number from 0 to less than 90 (degrees)", "phi (degrees).");
  prm.declare("Cohesion", "0", P::Double(0.0), "a number >= 0 (Pa)", "c (Pa), lost at failure.");
  prm.declare("Tensile strength", "0", P::Double(0.0), "a number >= 0 (Pa)",
              "T (Pa), lost at failure.");
  prm.declare("Dilation angle", "0", P::Double(0.0, 89.999),
              "a number from 0 to less than 90 (degrees)", "psi (degrees), active while slipping.");
  prm.declare("Dilation limit", "0", P::Double(0.0), "a number >= 0 (m; 0: no limit)",
              "Shear displacement beyond which dilation stops (m).");
}

JointProperties parse_joint_properties(ParameterFile& prm, const std::string& section,
                                       const JointProperties* inherit)
{
  const std::map<std::string, unsigned int> lines = prm.lines();
  const auto value = [&](const char* entry, double inherited)
  {
    return inherit != nullptr && lines.count(section + " / " + entry) == 0 ? inherited
                                                                           : prm.get_double(entry);
  };
  JointProperties j = inherit != nullptr ? *inherit : JointProperties{};
  // Rock joints are 1e8-1e13 Pa/m; far stiffer ones only shrink the time
  // step (eq. 87) towards nothing, and at 1e300 their forces overflow.
  j.normal_stiffness = value("Normal stiffness", j.normal_stiffness);
  j.shear_stiffness = value("Shear stiffness", j.shear_stiffness);
  for (const auto& [entry, k] : {std::pair{"Normal stiffness", j.normal_stiffness},
                                 std::pair{"Shear stiffness", j.shear_stiffness}})
  {
    if (!(k > 0.0))
      throw prm.error(entry, "must be positive", stiffness_allowed);
    if (!(k <= 1e16))
      throw prm.error(entry, "is stiffer than any rock joint by orders of magnitude",
                      stiffness_allowed);
  }
  j.friction_angle = value("Friction angle", j.friction_angle);
  j.cohesion = value("Cohesion", j.cohesion);
  j.tensile_strength = value("Tensile strength", j.tensile_strength);
  j.dilation_angle = value("Dilation angle", j.dilation_angle);
  j.dilation_limit = value("Dilation limit", j.dilation_limit);
  return j;
}

void declare_joint_material(ParameterFile& prm, const std::string& section)
{
  prm.enter(section);
  prm.declare("Name", "", P::Anything(), "a name of letters, digits, '_' and '-'",
              "What 'Material' entries call this joint material.");
  declare_joint_properties(prm);
  prm.leave();
}

void parse_joint_material(ParameterFile& prm, const std::string& section, Scene& scene)
{
  prm.enter(section);
  const std::string name = prm.get("Name");
  const std::string allowed = "a name of letters, digits, '_' and '-' that no other joint "
                              "material has ('default' is 'Joint properties')";
  if (name.empty())
    throw prm.error("Name", "is missing", allowed);
  if (!std::all_of(name.begin(), name.end(),
                   [](char c)
                   { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'; }))
    throw prm.error("Name", "'" + name + "' has other characters", allowed);
  if (std::find(scene.joint_material_names.begin(), scene.joint_material_names.end(), name) !=
      scene.joint_material_names.end())
    throw prm.error("Name", "'" + name + "' is taken", allowed);
  if (scene.joint_material_names.size() >= 255)
    throw prm.error("Name", "is one joint material too many", "at most 254 'Joint material N'");
  scene.solver.joint_materials.push_back(parse_joint_properties(prm, section, &scene.solver.joint));
  scene.joint_material_names.push_back(name);
  prm.leave();
}

void declare_joint_material_entry(ParameterFile& prm)
{
  prm.declare("Material", "", P::Anything(), "the name of a 'Joint material N', or 'default'",
              "Joint material of the contacts on these joints (none: the group contact rules, "
              "else 'Joint properties').");
}

unsigned char parse_joint_material_entry(ParameterFile& prm, const Scene& scene)
{
  const std::string name = prm.get("Material");
  if (name.empty())
    return JointMaterialRule::none;
  const auto it =
      std::find(scene.joint_material_names.begin(), scene.joint_material_names.end(), name);
  if (it == scene.joint_material_names.end())
    throw prm.error("Material", "names the unknown joint material '" + name + "'",
                    "one of " + material_names(scene));
  return static_cast<unsigned char>(it - scene.joint_material_names.begin());
}

void declare_group_contact(ParameterFile& prm, const std::string& section)
{
  prm.enter(section);
  prm.declare("Groups", "", P::Anything(), "two group names separated by a comma",
              "Contacts between blocks of these two groups (the same name twice: within one "
              "group) that lie on no joint with a 'Material'.");
  declare_joint_material_entry(prm);
  prm.leave();
}

void parse_group_contact(ParameterFile& prm, const std::string& section, Scene& scene)
{
  prm.enter(section);
  const std::vector<std::string> groups = dealii::Utilities::split_string_list(prm.get("Groups"));
  if (groups.size() != 2)
    throw prm.error("Groups", "names " + std::to_string(groups.size()) + " groups",
                    "two group names separated by a comma");
  for (const std::string& g : groups)
    check_group_name(prm, "Groups", scene, g);
  GroupContactSpec spec{groups[0], groups[1], parse_joint_material_entry(prm, scene), section};
  if (spec.material == JointMaterialRule::none)
  {
    // Not set, so no line of its own: the subsection's.
    const auto lines = prm.lines();
    const auto at = lines.find(section);
    throw InputError::at(prm.filename(), at == lines.end() ? 0u : at->second, section, "Material",
                         "is missing: a group contact rule gives a joint material",
                         "one of " + material_names(scene));
  }
  scene.group_contacts.push_back(spec);
  prm.leave();
}

} // namespace talus
