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
/// sets, single joints, excavations, the cuts along the stages'
/// excavations, each with the subsection it comes from. The faces a joint
/// set or joint makes remember it (BlockModel::face_origin).
struct Operation
{
  std::string section;
  CutOperation cut;
};

std::vector<Operation> operations(const Scene& scene)
{
  std::vector<Operation> ops;
  for (std::size_t i = 0; i < scene.joint_sets.size(); ++i)
    ops.push_back({i < scene.joint_set_sections.size() ? scene.joint_set_sections[i] : "Joint set",
                   CutOperation::joint_set(scene.joint_sets[i], BlockModel::joint_set_origin(i))});
  for (std::size_t i = 0; i < scene.joint_planes.size(); ++i)
  {
    const JointPlaneSpec& joint = scene.joint_planes[i];
    ops.push_back(
        {i < scene.joint_plane_sections.size() ? scene.joint_plane_sections[i] : "Joint",
         CutOperation::single_plane(
             Plane::through(joint.origin, normal_from_dip(joint.dip, joint.dip_direction)),
             joint.limited ? &joint.extent : nullptr, BlockModel::joint_origin(i))});
  }
  for (const auto& excavation : scene.excavations)
    ops.push_back({excavation.section, CutOperation::excavation(excavation.region)});
  // Where stages will excavate, the model is cut now: the pieces inside are
  // removed at their stage.
  // A body read from a mesh file is not cut: its zones are removed.
  for (std::size_t k = 0; k < scene.stages.size() && scene.deformable.mesh_file.empty(); ++k)
    for (const auto& excavation : scene.stages[k].excavations)
      ops.push_back({excavation.section, CutOperation::along(excavation.region)});
  return ops;
}

/// The report of the operations from what each did.
void report_operations(const std::vector<Operation>& ops, const std::vector<OperationTally>& tally,
                       BuildReport& report)
{
  for (std::size_t k = 0; k < ops.size(); ++k)
  {
    const auto cuts = std::make_pair(tally[k].cutting.cuts, tally[k].cutting.skipped_slivers);
    switch (ops[k].cut.kind)
    {
    case CutOperation::Kind::joint_set:
      report.joint_set_cuts.push_back(cuts);
      break;
    case CutOperation::Kind::plane:
      report.joint_cuts.push_back(cuts);
      break;
    case CutOperation::Kind::excavate:
      report.excavated_volume.push_back(tally[k].volume);
      break;
    case CutOperation::Kind::cut_along:
      report.stage_excavated_volume.push_back(tally[k].volume);
      break;
    }
  }
  report.cutting = total_report(tally);
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
  for (const Operation& op : operations(scene))
  {
    generator.apply(op.cut);
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

namespace
{

/// Adds a block of the scene, checked, to `model` in its group: by the
/// group boxes its centroid lies in, or the groups that list `number` (its
/// number in the whole model).
void add_scene_block(const Scene& scene, const ConvexPolyhedron& block, unsigned int number,
                     BlockModel& model)
{
  try
  {
    block.validate("block " + std::to_string(number), 1e-6);
  }
  catch (const GeometryError& e)
  {
    explain_invalid_block(scene, e);
  }
  const unsigned int b = model.add_block(block, model.group_index(scene.default_group));
  // A centroid on a group box's face counts as inside, within a tolerance
  // far above round-off: whether it lies a hair inside or outside would
  // otherwise follow how the CPU rounds (a block centred on x = 0 and a
  // box from x = 0 joined the group or not with and without fused
  // multiply-adds).
  const double on_face = 1e-9 * scene.brick.diagonal();
  for (const GroupSpec& g : scene.groups)
    if (g.blocks.empty() ? g.region.contains(model.centroid[b], on_face)
                         : std::find(g.blocks.begin(), g.blocks.end(), number) != g.blocks.end())
    {
      model.group[b] = model.group_index(g.name);
      break;
    }
}

/// A model whose groups are numbered as build_blocks() numbers them: the
/// default group, then the scene's groups in order.
BlockModel with_scene_groups(const Scene& scene)
{
  BlockModel model;
  model.group_index(scene.default_group);
  for (const GroupSpec& g : scene.groups)
    model.group_index(g.name);
  return model;
}

} // namespace

BlockModel scene_groups(const Scene& scene)
{
  return with_scene_groups(scene);
}

BlockModel scene_block(const Scene& scene, const ConvexPolyhedron& block, unsigned int number)
{
  BlockModel model = with_scene_groups(scene);
  add_scene_block(scene, block, number, model);
  return model;
}

BlockModel build_blocks(const Scene& scene, BuildReport& report)
{
  BlockGenerator generator(ConvexPolyhedron::box(scene.brick.lo, scene.brick.hi), scene.cutting);
  const std::vector<Operation> ops = operations(scene);
  std::vector<OperationTally> tally(ops.size());
  for (std::size_t k = 0; k < ops.size(); ++k)
  {
    const CuttingReport before = generator.report();
    tally[k].volume = generator.apply(ops[k].cut);
    tally[k].cutting.cuts = generator.report().cuts - before.cuts;
    tally[k].cutting.skipped_slivers = generator.report().skipped_slivers - before.skipped_slivers;
  }
  report_operations(ops, tally, report);
  report.cutting = generator.report();

  BlockModel model = with_scene_groups(scene);
  const std::vector<ConvexPolyhedron>& blocks = generator.blocks();
  for (std::size_t i = 0; i < blocks.size(); ++i)
    add_scene_block(scene, blocks[i], static_cast<unsigned int>(i), model);
  return model;
}

BlockModel build_blocks_where(const Scene& scene, BuildReport& report, const KeepBlock& keep,
                              std::vector<unsigned int>& global, unsigned int& n_blocks)
{
  const BlockGenerator generator(ConvexPolyhedron::box(scene.brick.lo, scene.brick.hi),
                                 scene.cutting);
  const std::vector<Operation> ops = operations(scene);
  std::vector<CutOperation> cuts;
  for (const Operation& op : ops)
    cuts.push_back(op.cut);
  BlockModel model = with_scene_groups(scene);
  global.clear();
  std::vector<OperationTally> tally;
  unsigned long count = 0;
  generator.cut_depth_first(
      cuts,
      [&](unsigned long number, ConvexPolyhedron& block)
      {
        count = number + 1;
        const auto b = static_cast<unsigned int>(number);
        if (!keep(b, block))
          return;
        add_scene_block(scene, block, b, model);
        global.push_back(b);
      },
      tally);
  report_operations(ops, tally, report);
  n_blocks = static_cast<unsigned int>(count);
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
