#pragma once

// A deformable body built from the text of a parameter file (written to a
// file in the test's folder first): the scene, its blocks, their zones and
// a DeformableSolver of them, as the dynamics column tests need it.

#include <talus/scene/block_system.h>
#include <talus/scene/build_blocks.h>
#include <talus/solver/deformable_solver.h>

#include <cstdio>
#include <functional>
#include <memory>
#include <string>

struct ZoneScene
{
  talus::Scene scene;
  talus::BlockModel model;
  talus::TetMesh mesh;
  std::unique_ptr<talus::DeformableSolver> solver;

  /// Writes `text` to `file`, reads it, builds and meshes its blocks (block
  /// 0's zones), lets `adjust` change the scene and the mesh (e.g. turn the
  /// mesh and the boundaries' regions), then builds the solver with the
  /// scene's boundaries.
  ZoneScene(const std::string& file, const std::string& text,
            const std::function<void(talus::Scene&, talus::TetMesh&)>& adjust = {})
  {
    std::FILE* f = std::fopen(file.c_str(), "w");
    std::fputs(text.c_str(), f);
    std::fclose(f);
    scene = talus::read_scene(file, false);
    talus::BuildReport built;
    model = talus::build_blocks(scene, built);
    talus::resolve_group_names(scene, model);
    talus::MeshReport report;
    mesh = talus::mesh_deformable_blocks(scene, model, {0}, report);
    if (adjust)
      adjust(scene, mesh);
    talus::ZoneMaterials materials = talus::zone_materials(scene, model, mesh);
    solver = std::make_unique<talus::DeformableSolver>(
        mesh, std::move(materials.materials), std::move(materials.of_zone), scene.solver,
        scene.gridpoint_conditions, scene.face_pressures);
  }
  // The solver keeps a reference to the mesh: the scene stays where it is.
  ZoneScene(const ZoneScene&) = delete;
  ZoneScene& operator=(const ZoneScene&) = delete;
};
