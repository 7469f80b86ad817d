#include "joint_materials_reader.h"

#include <deal.II/base/utilities.h>

#include <algorithm>

namespace talus
{

namespace
{
namespace P = dealii::Patterns;

const std::string stiffness_allowed = "a number > 0 and at most 1e16 (Pa/m)";
const std::string normal_factor_allowed = "a number >= 0 (Pa^(1-e_n)/m; 0: kn constant)";
const std::string normal_exponent_allowed = "a number from 0 to less than 1";
const std::string shear_factor_allowed = "a number >= 0 (Pa^(1-e_s)/m; 0: ks constant)";
const std::string shear_exponent_allowed = "a number from 0 to 1";
const std::string maximum_stiffness_allowed =
    "with a stiffness factor, a number from the larger of 'Normal stiffness' and 'Shear "
    "stiffness' to 1e16 (Pa/m)";
const std::string initial_friction_allowed =
    "a number from the 'Friction angle' to less than 90 (degrees)";
const std::string roughness_allowed = "a number > 0 (m) for a continuously yielding joint";

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
  prm.declare("Model", "coulomb slip", P::Selection("coulomb slip|continuously yielding"),
              "coulomb slip or continuously yielding",
              "Joint constitutive model: Coulomb slip (eqs. 24-43) or the continuously yielding "
              "model of Cundall and Lemos (1990).");
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
  // Continuously yielding only.
  prm.declare("Normal stiffness factor", "0", P::Double(0.0), normal_factor_allowed,
              "Continuously yielding: a_n of kn = a_n sigma_n^e_n (Pa^(1-e_n)/m; 0: kn is "
              "the 'Normal stiffness'), never below the 'Normal stiffness'.");
  prm.declare("Normal stiffness exponent", "0", P::Double(0.0, 0.999), normal_exponent_allowed,
              "Continuously yielding: e_n of kn = a_n sigma_n^e_n.");
  prm.declare("Shear stiffness factor", "0", P::Double(0.0), shear_factor_allowed,
              "Continuously yielding: a_s of ks = a_s sigma_n^e_s (Pa^(1-e_s)/m; 0: ks is the "
              "'Shear stiffness'), never below the 'Shear stiffness'.");
  prm.declare("Shear stiffness exponent", "0", P::Double(0.0, 1.0), shear_exponent_allowed,
              "Continuously yielding: e_s of ks = a_s sigma_n^e_s.");
  prm.declare("Maximum stiffness", "0", P::Double(0.0), maximum_stiffness_allowed,
              "Continuously yielding with a stiffness factor: the largest kn and ks (Pa/m), "
              "which the time step takes.");
  prm.declare("Initial friction angle", "30", P::Double(0.0, 89.999), initial_friction_allowed,
              "Continuously yielding: phi_i (degrees), the friction angle of the bounding "
              "strength before any plastic shear; it decays to the 'Friction angle'.");
  prm.declare("Roughness", "0", P::Double(0.0), roughness_allowed,
              "Continuously yielding: R (m), the plastic shear displacement over which "
              "(phi_m - phi) falls by the factor e.");
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

  const bool model_set = inherit == nullptr || lines.count(section + " / Model") != 0;
  if (model_set)
    j.model = prm.get("Model") == "continuously yielding" ? JointModel::continuously_yielding
                                                          : JointModel::coulomb_slip;
  j.normal_stiffness_factor = value("Normal stiffness factor", j.normal_stiffness_factor);
  j.normal_stiffness_exponent = value("Normal stiffness exponent", j.normal_stiffness_exponent);
  j.shear_stiffness_factor = value("Shear stiffness factor", j.shear_stiffness_factor);
  j.shear_stiffness_exponent = value("Shear stiffness exponent", j.shear_stiffness_exponent);
  j.maximum_stiffness = value("Maximum stiffness", j.maximum_stiffness);
  j.initial_friction_angle = value("Initial friction angle", j.initial_friction_angle);
  j.roughness = value("Roughness", j.roughness);
  if (j.model == JointModel::coulomb_slip)
    // A continuously yielding entry in a Coulomb-slip section: most likely
    // a forgotten 'Model' line, which would leave the joint Coulomb.
    for (const char* entry :
         {"Normal stiffness factor", "Normal stiffness exponent", "Shear stiffness factor",
          "Shear stiffness exponent", "Maximum stiffness", "Initial friction angle", "Roughness"})
      if (lines.count(section + " / " + entry) != 0)
        throw prm.error(entry, "applies only to a continuously yielding joint, and this one is "
                               "Coulomb slip",
                        "'Model = continuously yielding' (here or, for a 'Joint material N', in "
                        "'Joint properties'), or no such entry");
  if (j.model == JointModel::continuously_yielding)
  {
    // What the model has no place for, set in this section: refused
    // rather than ignored.
    for (const char* entry : {"Cohesion", "Tensile strength", "Dilation angle", "Dilation limit"})
      if (lines.count(section + " / " + entry) != 0 && prm.get_double(entry) != 0.0)
        throw prm.error(entry, "does not apply to a continuously yielding joint",
                        "0, or 'Model = coulomb slip'");
    j.cohesion = j.tensile_strength = j.dilation_angle = j.dilation_limit = 0.0;
    if (!(j.roughness > 0.0))
      throw prm.error("Roughness",
                      "is 0: a continuously yielding joint needs the plastic shear "
                      "displacement over which its friction decays",
                      roughness_allowed);
    if (!(j.initial_friction_angle >= j.friction_angle))
      throw prm.error("Initial friction angle",
                      "is below the 'Friction angle' (" +
                          dealii::Utilities::to_string(j.friction_angle) +
                          "), which the bounding strength decays to",
                      initial_friction_allowed);
    if (j.normal_stiffness_factor > 0.0 || j.shear_stiffness_factor > 0.0)
    {
      const double k_min = std::max(j.normal_stiffness, j.shear_stiffness);
      if (!(j.maximum_stiffness >= k_min && j.maximum_stiffness <= 1e16))
        throw prm.error("Maximum stiffness",
                        j.maximum_stiffness == 0.0
                            ? "is missing: a stiffness factor makes kn or ks grow with the "
                              "normal stress, and the time step needs their bound"
                            : "is outside its range",
                        maximum_stiffness_allowed);
    }
  }
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
