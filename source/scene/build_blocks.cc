#include <talus/scene/build_blocks.h>

#include <talus/base/exceptions.h>

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

namespace talus
{

namespace
{

/// The cutting operations of a scene in the order they are made: joint
/// sets, single joints, excavations, each with the subsection it comes from.
/// The faces a joint set or joint makes remember it (BlockModel::face_origin).
struct Operation
{
  std::string section;
  std::function<void(BlockGenerator&)> apply;
};

std::vector<Operation> operations(const Scene& scene, BuildReport* report)
{
  std::vector<Operation> ops;
  for (std::size_t i = 0; i < scene.joint_sets.size(); ++i)
    ops.push_back({i < scene.joint_set_sections.size() ? scene.joint_set_sections[i] : "Joint set",
                   [&scene, i](BlockGenerator& g)
                   { g.cut_joint_set(scene.joint_sets[i], BlockModel::joint_set_origin(i)); }});
  for (std::size_t i = 0; i < scene.joint_planes.size(); ++i)
    ops.push_back({i < scene.joint_plane_sections.size() ? scene.joint_plane_sections[i] : "Joint",
                   [&scene, i](BlockGenerator& g)
                   {
                     const JointPlaneSpec& joint = scene.joint_planes[i];
                     g.cut_plane(Plane::through(joint.origin,
                                                normal_from_dip(joint.dip, joint.dip_direction)),
                                 joint.limited ? &joint.extent : nullptr,
                                 BlockModel::joint_origin(i));
                   }});
  for (std::size_t e = 0; e < scene.excavations.size(); ++e)
    ops.push_back({scene.excavations[e].section, [&scene, e, report](BlockGenerator& g)
                   {
                     const double removed = g.excavate(scene.excavations[e].region);
                     if (report)
                       report->excavated_volume.push_back(removed);
                   }});
  // Where stages will excavate, the model is cut now: the pieces inside are
  // removed at their stage.
  // A body read from a mesh file is not cut: its zones are removed.
  for (std::size_t k = 0; k < scene.stages.size() && scene.deformable.mesh_file.empty(); ++k)
    for (std::size_t e = 0; e < scene.stages[k].excavations.size(); ++e)
      ops.push_back({scene.stages[k].excavations[e].section,
                     [&scene, k, e, report](BlockGenerator& g)
                     {
                       const double inside = g.cut_along(scene.stages[k].excavations[e].region);
                       if (report)
                         report->stage_excavated_volume.push_back(inside);
                     }});
  return ops;
}

/// A block came out invalid: cuts the brick again, checking every block
/// after each operation, and throws a GeometryError that names the first
/// operation that made an invalid block and what would help.
[[noreturn]] void explain_invalid_block(const Scene& scene, const GeometryError& found)
{
  BlockGenerator generator(ConvexPolyhedron::box(scene.brick.lo, scene.brick.hi), scene.cutting);
  const auto invalid = [&generator]() -> std::string
  {
    const std::vector<ConvexPolyhedron>& blocks = generator.blocks();
    for (std::size_t i = 0; i < blocks.size(); ++i)
      try
      {
        blocks[i].validate("block " + std::to_string(i), 1e-6);
      }
      catch (const GeometryError& e)
      {
        return e.what();
      }
    return "";
  };
  const std::string help =
      "what would help: a larger 'Minimum block volume' in subsection 'Model' (a cut that would "
      "leave a smaller piece is then not made), a larger 'Cutting tolerance' there, or moving "
      "the plane away from the faces and corners it nearly touches";
  if (const std::string problem = invalid(); !problem.empty())
    throw GeometryError("subsection 'Model': the brick is not a valid block (" + problem +
                        "); allowed: a brick of a size double precision can hold (each side "
                        "from 1e-6 to 1e8 m)");
  for (const Operation& op : operations(scene, nullptr))
  {
    op.apply(generator);
    // Which face or edge came out wrong follows the rounding; the
    // subsection and the remedy do not.
    if (!invalid().empty())
      throw GeometryError("subsection '" + op.section +
                          "' cuts a piece too thin or too small beside the rest of the model "
                          "for the cutting tolerance (" +
                          number(scene.cutting.relative_tolerance) +
                          " of the block size): the piece is not a closed convex polyhedron; " +
                          help);
  }
  throw found; // not reproduced: the first message is all there is
}

} // namespace

BlockModel build_blocks(const Scene& scene, BuildReport& report)
{
  BlockGenerator generator(ConvexPolyhedron::box(scene.brick.lo, scene.brick.hi), scene.cutting);
  // Cuts made and refused by one operation.
  const std::size_t n_sets = scene.joint_sets.size(), n_joints = scene.joint_planes.size();
  const std::vector<Operation> ops = operations(scene, &report);
  for (std::size_t k = 0; k < ops.size(); ++k)
  {
    const CuttingReport before = generator.report();
    ops[k].apply(generator);
    const auto cuts = std::make_pair(generator.report().cuts - before.cuts,
                                     generator.report().skipped_slivers - before.skipped_slivers);
    if (k < n_sets)
      report.joint_set_cuts.push_back(cuts);
    else if (k < n_sets + n_joints)
      report.joint_cuts.push_back(cuts);
  }
  report.cutting = generator.report();

  BlockModel model;
  const unsigned int default_group = model.group_index(scene.default_group);
  std::vector<unsigned int> group_of_region;
  for (const GroupSpec& g : scene.groups)
    group_of_region.push_back(model.group_index(g.name));

  const std::vector<ConvexPolyhedron>& blocks = generator.blocks();
  for (std::size_t i = 0; i < blocks.size(); ++i)
  {
    try
    {
      blocks[i].validate("block " + std::to_string(i), 1e-6);
    }
    catch (const GeometryError& e)
    {
      explain_invalid_block(scene, e);
    }
    const unsigned int b = model.add_block(blocks[i], default_group);
    // A centroid on a group box's face counts as inside, within a tolerance
    // far above round-off: whether it lies a hair inside or outside would
    // otherwise follow how the CPU rounds (a block centred on x = 0 and a
    // box from x = 0 joined the group or not with and without fused
    // multiply-adds).
    const double on_face = 1e-9 * scene.brick.diagonal();
    for (std::size_t r = 0; r < scene.groups.size(); ++r)
      if (scene.groups[r].blocks.empty()
              ? scene.groups[r].region.contains(model.centroid[b], on_face)
              : std::find(scene.groups[r].blocks.begin(), scene.groups[r].blocks.end(), b) !=
                    scene.groups[r].blocks.end())
      {
        model.group[b] = group_of_region[r];
        break;
      }
  }
  return model;
}

void resolve_group_names(Scene& scene, BlockModel& model)
{
  scene.solver.fixed_groups.clear();
  for (const std::string& name : scene.fixed_groups)
    scene.solver.fixed_groups.push_back(model.group_index(name));
  for (std::size_t l = 0; l < scene.solver.loads.size(); ++l)
    scene.solver.loads[l].group = model.group_index(scene.load_groups[l]);
  for (StageSpec& stage : scene.stages)
    for (std::size_t l = 0; l < stage.boundaries.loads.size(); ++l)
      stage.boundaries.loads[l].group = model.group_index(stage.boundaries.load_groups[l]);
  // Group contact rules on group indices (the first rule for a pair wins).
  JointMaterialRule& rule = scene.solver.joint_rule;
  std::vector<std::pair<unsigned int, unsigned int>> pairs;
  for (const GroupContactSpec& g : scene.group_contacts)
    pairs.emplace_back(model.group_index(g.a), model.group_index(g.b));
  rule.n_groups = static_cast<unsigned int>(model.group_names.size());
  rule.of_group_pair.assign(std::size_t(rule.n_groups) * rule.n_groups, JointMaterialRule::none);
  for (std::size_t i = pairs.size(); i-- > 0;)
  {
    const auto [a, b] = pairs[i];
    rule.of_group_pair[a * rule.n_groups + b] = rule.of_group_pair[b * rule.n_groups + a] =
        scene.group_contacts[i].material;
  }
}

} // namespace talus
