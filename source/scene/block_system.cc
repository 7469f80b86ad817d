#include <talus/base/exceptions.h>
#include <talus/scene/block_system.h>
#include <talus/zone/tet10_mesh.h>
#include <talus/zone/zone_surface.h>

#include <algorithm>
#include <array>

namespace talus
{

namespace
{
const std::string& group_of(const BlockModel& model, unsigned int block)
{
  return model.group_names[model.group[block]];
}
} // namespace

BlockMeshOrder deformable_zone_order(const Scene& scene, const BlockModel& model)
{
  return [&scene, &model](unsigned int block)
  {
    return scene.deformable.nodal_mixed(group_of(model, block)) ? MeshOrder::columns
                                                                : MeshOrder::slabs;
  };
}

ZoneMaterials zone_materials(const Scene& scene, const BlockModel& model, const TetMesh& mesh)
{
  const DeformableSpec& d = scene.deformable;
  ZoneMaterials m;
  m.of_zone.resize(mesh.n_zones());
  // Material index of each (rock material, nodal mixed) pair, made when
  // first used; rock material 0 is that of 'Deformable'.
  constexpr unsigned int none = ~0u;
  std::vector<std::array<unsigned int, 2>> index(scene.rock_materials.size() + 1, {{none, none}});
  for (unsigned int z = 0; z < mesh.n_zones(); ++z)
  {
    if (z > 0 && mesh.zone_block[z] == mesh.zone_block[z - 1])
    {
      m.of_zone[z] = m.of_zone[z - 1];
      continue;
    }
    const std::string& group = group_of(model, mesh.zone_block[z]);
    const RockMaterialSpec* rock = scene.rock_material_of(group);
    const bool mixed = d.nodal_mixed(group);
    unsigned int& i =
        index[rock == nullptr ? 0 : 1 + (rock - scene.rock_materials.data())][mixed];
    if (i == none)
    {
      ZoneMaterial material = rock == nullptr ? d.material : rock->zone;
      material.element = d.material.element;
      material.nodal_mixed = mixed;
      i = static_cast<unsigned int>(m.materials.size());
      m.materials.push_back(material);
    }
    m.of_zone[z] = i;
  }
  if (m.materials.empty()) // no zones
    m.materials.push_back(d.material);
  return m;
}

TetMesh mesh_deformable_blocks(const Scene& scene, const BlockModel& model,
                               const std::vector<unsigned int>& which, MeshReport& report,
                               MPI_Comm comm)
{
  try
  {
    const ZoneElement element = scene.deformable.material.element;
    // 10-node zones are made from the 4-node mesh (tet10_mesh.h).
    TetMesh mesh = mesh_blocks(model, which, scene.deformable.edge_length, report,
                               element == ZoneElement::tet10 ? ZoneElement::tet4 : element,
                               deformable_zone_order(scene, model), scene.deformable.mesher, comm);
    if (element == ZoneElement::tet10)
    {
      make_quadratic(mesh);
      report = measure_mesh(mesh);
    }
    return mesh;
  }
  catch (const InputError& e)
  {
    throw InputError(scene.parameter_file + ": " + e.what());
  }
}

bool has_joint_pressures(const Scene& scene)
{
  bool any = scene.solver.water.has_fixed_pressures();
  for (const StageSpec& stage : scene.stages)
    any |= stage.changes_water && stage.water.has_fixed_pressures();
  return any;
}

BlockSystem build_block_system(const Scene& scene, BlockModel& model)
{
  BlockSystem s;
  for (unsigned int b = 0; b < model.n_blocks(); ++b)
    for (const std::string& g : scene.deformable.groups)
      if (model.group_names[model.group[b]] == g)
        s.deformable_blocks.push_back(b);
  if (!s.deformable_blocks.empty())
  {
    s.mesh = mesh_deformable_blocks(scene, model, s.deformable_blocks, s.mesh_report);
    std::vector<int> face_origins;
    if (has_joint_pressures(scene))
      face_origins = zone_face_origins(model, s.mesh); // on the blocks' own faces
    s.vertex_gridpoint = use_zone_surfaces(model, s.mesh);
    ZoneMaterials m = zone_materials(scene, model, s.mesh);
    s.zones = std::make_unique<DeformableSolver>(
        s.mesh, std::move(m.materials), std::move(m.of_zone), scene.solver,
        scene.gridpoint_conditions, scene.face_pressures,
        scene.has_initial_stress ? &scene.initial_stress : nullptr);
    if (!face_origins.empty())
      s.zones->set_face_origins(std::move(face_origins));
  }
  SolverSettings settings = scene.solver;
  if (!scene.rock_materials.empty())
    for (unsigned int b = 0; b < model.n_blocks(); ++b)
      settings.block_density.push_back(scene.density_of(group_of(model, b)));
  if (scene.has_initial_stress)
    settings.initial_stress = &scene.initial_stress; // the joints there at the start carry it
  s.solver = std::make_unique<RigidSolver>(model, scene.density, settings, s.zones.get(),
                                           s.vertex_gridpoint);
  s.solver->set_face_loads(scene.face_pressures); // rigid blocks' faces; zones have theirs
  return s;
}

} // namespace talus
