#include <talus/base/exceptions.h>
#include <talus/solver/block_system.h>
#include <talus/zone/tet10_mesh.h>
#include <talus/zone/zone_surface.h>

namespace talus
{

TetMesh mesh_deformable_blocks(const Scene& scene, const BlockModel& model,
                               const std::vector<unsigned int>& which, MeshReport& report)
{
  try
  {
    const ZoneElement element = scene.deformable.material.element;
    // 10-node zones are made from the 4-node mesh (tet10_mesh.h).
    // Nodal mixed discretization runs fastest on zones in columns.
    TetMesh mesh =
        mesh_blocks(model, which, scene.deformable.edge_length, report,
                    element == ZoneElement::tet10 ? ZoneElement::tet4 : element,
                    scene.deformable.material.nodal_mixed ? MeshOrder::columns : MeshOrder::slabs);
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
    s.vertex_gridpoint = use_zone_surfaces(model, s.mesh);
    // A second material for the 'Stiffness ratio groups' (E scaled).
    std::vector<ZoneMaterial> materials{scene.deformable.material};
    std::vector<unsigned int> material_of_zone(s.mesh.n_zones(), 0);
    if (!scene.deformable.scaled_groups.empty())
    {
      ZoneMaterial scaled = scene.deformable.material;
      scaled.bulk_modulus *= scene.deformable.stiffness_ratio;
      scaled.shear_modulus *= scene.deformable.stiffness_ratio;
      materials.push_back(scaled);
      for (unsigned int z = 0; z < s.mesh.n_zones(); ++z)
        for (const std::string& g : scene.deformable.scaled_groups)
          if (model.group_names[model.group[s.mesh.zone_block[z]]] == g)
            material_of_zone[z] = 1;
    }
    s.zones = std::make_unique<DeformableSolver>(
        s.mesh, materials, material_of_zone, scene.solver, scene.gridpoint_conditions,
        scene.face_pressures, scene.has_initial_stress ? &scene.initial_stress : nullptr);
  }
  SolverSettings settings = scene.solver;
  if (scene.has_initial_stress)
    settings.initial_stress = &scene.initial_stress; // the joints there at the start carry it
  s.solver = std::make_unique<RigidSolver>(model, scene.density, settings, s.zones.get(),
                                           s.vertex_gridpoint);
  return s;
}

} // namespace talus
