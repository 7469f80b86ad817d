#include <talus/model/build_blocks.h>

namespace talus
{

BlockModel build_blocks(const Scene& scene, BuildReport& report)
{
  BlockGenerator generator(ConvexPolyhedron::box(scene.brick.lo, scene.brick.hi), scene.cutting);
  // Cuts made and refused by one operation.
  const auto counted = [&generator](auto cut)
  {
    const CuttingReport before = generator.report();
    cut();
    return std::make_pair(generator.report().cuts - before.cuts,
                          generator.report().skipped_slivers - before.skipped_slivers);
  };
  // Faces remember their joint set (+1, +2, ...) or joint (-1, -2, ...).
  for (std::size_t i = 0; i < scene.joint_sets.size(); ++i)
    report.joint_set_cuts.push_back(counted(
        [&] { generator.cut_joint_set(scene.joint_sets[i], BlockModel::joint_set_origin(i)); }));
  for (std::size_t j = 0; j < scene.joint_planes.size(); ++j)
    report.joint_cuts.push_back(counted(
        [&]
        {
          const JointPlaneSpec& joint = scene.joint_planes[j];
          generator.cut_plane(
              Plane::through(joint.origin, normal_from_dip(joint.dip, joint.dip_direction)),
              joint.limited ? &joint.extent : nullptr, BlockModel::joint_origin(j));
        }));
  for (const ExcavationSpec& excavation : scene.excavations)
    report.excavated_volume.push_back(generator.excavate(excavation.region));
  report.cutting = generator.report();

  BlockModel model;
  const unsigned int default_group = model.group_index(scene.default_group);
  std::vector<unsigned int> group_of_region;
  for (const GroupSpec& g : scene.groups)
    group_of_region.push_back(model.group_index(g.name));

  const std::vector<ConvexPolyhedron>& blocks = generator.blocks();
  for (std::size_t i = 0; i < blocks.size(); ++i)
  {
    blocks[i].validate("block " + std::to_string(i), 1e-6);
    const unsigned int b = model.add_block(blocks[i], default_group);
    for (std::size_t r = 0; r < scene.groups.size(); ++r)
      if (scene.groups[r].region.contains(model.centroid[b]))
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
}

} // namespace talus
