#pragma once

// Runs a shipped scene of parameters/ with deformable blocks, without
// writing output, for the verification tests of deformable blocks.

#include <talus/base/parallel_environment.h>
#include <talus/scene/scene.h>
#include <talus/scene/build_blocks.h>
#include <talus/scene/block_system.h>
#include <talus/solver/deformable_solver.h>

#include <memory>
#include <string>

struct DeformableScene
{
  talus::Scene scene;
  talus::BlockModel model;
  talus::TetMesh mesh;
  talus::MeshReport mesh_report;
  std::unique_ptr<talus::DeformableSolver> solver;

  /// Reads parameters/<name>, applies `edit` to the scene, meshes every
  /// block of the 'Deformable' groups and builds the solver.
  template <typename Edit>
  DeformableScene(const std::string& name, Edit edit)
  {
    scene = talus::read_scene(std::string(SOURCE_DIR) + "/../../parameters/" + name, false);
    edit(scene);
    talus::BuildReport report;
    model = talus::build_blocks(scene, report);
    talus::resolve_group_names(scene, model);
    std::vector<unsigned int> which;
    for (unsigned int b = 0; b < model.n_blocks(); ++b)
      for (const std::string& g : scene.deformable.groups)
        if (model.group_names[model.group[b]] == g)
          which.push_back(b);
    // As talus meshes them and gives them their materials.
    mesh = talus::mesh_deformable_blocks(scene, model, which, mesh_report);
    talus::ZoneMaterials materials = talus::zone_materials(scene, model, mesh);
    solver = std::make_unique<talus::DeformableSolver>(
        mesh, std::move(materials.materials), std::move(materials.of_zone), scene.solver,
        scene.gridpoint_conditions, scene.face_pressures,
        scene.has_initial_stress ? &scene.initial_stress : nullptr);
  }

  /// Mean of displacement component d over the gridpoints whose initial
  /// coordinate c lies within 1e-9 of `value`.
  double mean_displacement(int d, int c, double value) const
  {
    const std::vector<double> u = solver->displacements();
    double sum = 0.0;
    unsigned int n = 0;
    for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
      if (std::abs(mesh.position[3 * g + c] - value) < 1e-9)
      {
        sum += u[3 * g + d];
        ++n;
      }
    return n > 0 ? sum / n : 0.0;
  }
};
