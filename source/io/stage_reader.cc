#include "stage_reader.h"

#include "joint_materials_reader.h"
#include "region_reader.h"

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace talus
{

namespace P = dealii::Patterns;

namespace
{

/// A number >= 0 from `entry`, or `fallback` when it says "solver" (its
/// default: the value of 'Solver').
double number_or_solver(const ParameterFile& prm, const std::string& entry, double fallback,
                        const std::string& allowed)
{
  const std::string text = prm.get(entry);
  if (text == "solver")
    return fallback;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || !(value >= 0.0) || !std::isfinite(value))
    throw prm.error(entry, "'" + text + "' is not a number >= 0", allowed);
  return value;
}

/// The group names of list entry `entry`, each checked.
std::vector<std::string> group_list(const ParameterFile& prm, const std::string& entry,
                                    const Scene& scene)
{
  std::vector<std::string> names = dealii::Utilities::split_string_list(prm.get(entry));
  for (const std::string& g : names)
    check_group_name(prm, entry, scene, g);
  return names;
}

} // namespace

void declare_stage(ParameterFile& prm, const std::string& section,
                   const std::vector<std::string>& excavations)
{
  prm.enter(section);
  prm.declare("Name", "", P::Anything(), "any name (empty: the subsection's)",
              "What the stage does, for the summary and the history.");
  prm.declare("Mode", "solver", P::Selection("solver|static|dynamic|factor of safety"),
              "solver, static, dynamic or factor of safety",
              "static: damped to equilibrium; dynamic: motion in time; factor of safety: the "
              "strength reduction search from the state the stage starts in (the model goes on "
              "unchanged to the next stage); solver: as 'Solver / Mode'.");
  prm.declare("Steps", "solver", P::Anything(), "an integer >= 0, or solver",
              "Step limit of this stage (counted from its start); solver: 'Solver / Steps'.");
  prm.declare("Target ratio", "solver", P::Anything(), "a number >= 0, or solver",
              "Static stages stop when the unbalanced-force ratio falls below this (0: never); "
              "solver: 'Solver / Target ratio'.");
  prm.declare("Time limit", "0", P::Double(0.0), "a number >= 0 (s; 0: none)",
              "The stage stops after this much model time (s).");
  prm.declare("Excavate groups", "", P::List(P::Anything()), "group names separated by commas",
              "The blocks of these groups are removed at the stage's start.");
  prm.declare("Fix groups", "", P::List(P::Anything()), "group names separated by commas",
              "The blocks of these groups are held still from the stage's start.");
  prm.declare("Free groups", "", P::List(P::Anything()), "group names separated by commas",
              "The blocks of these groups move freely from the stage's start.");
  prm.declare("Reset displacements", "false", P::Bool(), "true or false",
              "Displacements (and rotations) start again from zero, stresses and forces stay: "
              "the stage reports the movement it causes.");
  prm.declare("Joint materials", "", P::Anything(),
              "'Joint set N = material' or 'Joint N = material' separated by ';'",
              "Joint sets and joints whose contacts take another joint material from the "
              "stage's start.");
  prm.declare("Group contacts", "", P::Anything(),
              "'group, group = material' separated by ';'",
              "Contacts between blocks of the two groups that lie on no joint with a material "
              "take this joint material from the stage's start (as 'Group contact N').");
  prm.declare("Rock materials", "", P::Anything(),
              "'group = material' separated by ';' (material: a 'Rock material N' name, or "
              "default)",
              "Groups whose blocks take another rock material from the stage's start: density "
              "(rigid and deformable blocks) and zone constants (deformable ones); stresses "
              "stay.");
  prm.declare("Release", "", P::List(P::Anything()),
              "names of 'Boundary N' and 'Load N' separated by commas",
              "Boundaries and loads that stop acting at the stage's start (a 'Boundary M' or "
              "'Load M' subsection of the stage adds one, or replaces the one of that name).");
  for (const std::string& e : excavations)
  {
    prm.enter(e);
    declare_region(prm, "the region to remove at the stage's start");
    prm.leave();
  }
  prm.leave();
}

void parse_stage(ParameterFile& prm, const std::string& section,
                 const std::vector<std::string>& excavations, Scene& scene)
{
  prm.enter(section);
  StageSpec stage;
  stage.section = section;
  stage.name = prm.get("Name").empty() ? section : prm.get("Name");
  const std::string mode = prm.get("Mode");
  stage.dynamic = mode == "solver" ? scene.solver.dynamic : mode == "dynamic";
  stage.factor_of_safety = mode == "factor of safety";
  const double steps = number_or_solver(prm, "Steps", double(scene.solver.steps),
                                        "an integer >= 0, or solver (the Solver's 'Steps')");
  if (steps != std::floor(steps) || steps > 1e15)
    throw prm.error("Steps", "'" + prm.get("Steps") + "' is not an integer from 0 to 1e15",
                    "an integer >= 0, or solver (the Solver's 'Steps')");
  stage.steps = static_cast<unsigned long>(steps);
  stage.target_ratio = number_or_solver(prm, "Target ratio", scene.solver.target_ratio,
                                        "a number >= 0, or solver (the Solver's 'Target ratio')");
  stage.time_limit = prm.get_double("Time limit");
  stage.excavate_groups = group_list(prm, "Excavate groups", scene);
  stage.fix_groups = group_list(prm, "Fix groups", scene);
  stage.free_groups = group_list(prm, "Free groups", scene);
  for (const std::string& g : stage.fix_groups)
    if (std::find(stage.free_groups.begin(), stage.free_groups.end(), g) != stage.free_groups.end())
      throw prm.error("Free groups", "names group '" + g + "', which 'Fix groups' names too",
                      "each group in one of the two lists");
  stage.reset_displacements = prm.get_bool("Reset displacements");
  const std::string allowed = "'Joint set N = material' or 'Joint N = material' separated by "
                              "';', with N a subsection of the file and a material of "
                              "'Joint properties' (default) or a 'Joint material N'";
  for (const std::string& item :
       dealii::Utilities::split_string_list(prm.get("Joint materials"), ';'))
  {
    const auto parts = dealii::Utilities::split_string_list(item, '=');
    if (parts.size() != 2)
      throw prm.error("Joint materials", "'" + item + "' is not 'joint = material'", allowed);
    JointMaterialChange change;
    const auto set =
        std::find(scene.joint_set_sections.begin(), scene.joint_set_sections.end(), parts[0]);
    const auto joint =
        std::find(scene.joint_plane_sections.begin(), scene.joint_plane_sections.end(), parts[0]);
    if (set != scene.joint_set_sections.end())
      change.origin = BlockModel::joint_set_origin(set - scene.joint_set_sections.begin());
    else if (joint != scene.joint_plane_sections.end())
      change.origin = BlockModel::joint_origin(joint - scene.joint_plane_sections.begin());
    else
      throw prm.error("Joint materials",
                      "names '" + parts[0] +
                          "', which is no subsection of the "
                          "file",
                      allowed);
    const auto m =
        std::find(scene.joint_material_names.begin(), scene.joint_material_names.end(), parts[1]);
    if (m == scene.joint_material_names.end())
      throw prm.error("Joint materials", "names the unknown joint material '" + parts[1] + "'",
                      allowed);
    change.material = static_cast<unsigned char>(m - scene.joint_material_names.begin());
    stage.joint_materials.push_back(change);
  }
  const std::string pair_allowed =
      "'group, group = material' separated by ';', with groups of the scene and a material of "
      "'Joint properties' (default) or a 'Joint material N'";
  for (const std::string& item :
       dealii::Utilities::split_string_list(prm.get("Group contacts"), ';'))
  {
    const auto parts = dealii::Utilities::split_string_list(item, '=');
    const auto groups =
        parts.size() == 2 ? dealii::Utilities::split_string_list(parts[0], ',')
                          : std::vector<std::string>{};
    if (groups.size() != 2)
      throw prm.error("Group contacts", "'" + item + "' is not 'group, group = material'",
                      pair_allowed);
    GroupContactChange change;
    change.a = groups[0];
    change.b = groups[1];
    check_group_name(prm, "Group contacts", scene, change.a);
    check_group_name(prm, "Group contacts", scene, change.b);
    const auto m =
        std::find(scene.joint_material_names.begin(), scene.joint_material_names.end(), parts[1]);
    if (m == scene.joint_material_names.end())
      throw prm.error("Group contacts", "names the unknown joint material '" + parts[1] + "'",
                      pair_allowed);
    change.material = static_cast<unsigned char>(m - scene.joint_material_names.begin());
    stage.group_contacts.push_back(change);
  }
  for (const std::string& e : excavations)
  {
    prm.enter(e);
    ExcavationSpec spec;
    std::string description;
    spec.region = parse_region(prm, scene.brick, description);
    spec.section = section + " / " + e;
    spec.description = spec.section + ": " + description;
    stage.excavations.push_back(spec);
    prm.leave();
  }
  prm.leave();
  scene.stages.push_back(std::move(stage));
}

void parse_stage_rock_materials(ParameterFile& prm, const std::string& section, Scene& scene,
                                StageSpec& stage)
{
  prm.enter(section);
  const std::string allowed = "'group = material' separated by ';', with a group of the scene and "
                              "the 'Name' of a 'Rock material N', or default (the constants of "
                              "'Material' and 'Deformable')";
  for (const std::string& item :
       dealii::Utilities::split_string_list(prm.get("Rock materials"), ';'))
  {
    const auto parts = dealii::Utilities::split_string_list(item, '=');
    if (parts.size() != 2)
      throw prm.error("Rock materials", "'" + item + "' is not 'group = material'", allowed);
    check_group_name(prm, "Rock materials", scene, parts[0]);
    RockMaterialChange change;
    change.group = parts[0];
    if (parts[1] != "default")
    {
      const auto& rocks = scene.rock_materials;
      const auto m = std::find_if(rocks.begin(), rocks.end(),
                                  [&](const RockMaterialSpec& r) { return r.name == parts[1]; });
      if (m == rocks.end())
        throw prm.error("Rock materials", "names the unknown rock material '" + parts[1] + "'",
                        allowed);
      change.material = static_cast<int>(m - rocks.begin());
    }
    stage.rock_materials.push_back(change);
  }
  prm.leave();
}

} // namespace talus
