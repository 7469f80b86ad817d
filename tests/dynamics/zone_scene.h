#pragma once

// A deformable body built from the text of a parameter file (written to a
// file in the test's folder first): the scene, its blocks, their zones and
// a DeformableSolver of them, as the dynamics column tests need it.

#include <talus/scene/block_system.h>
#include <talus/scene/build_blocks.h>
#include <talus/solver/deformable_solver.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

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

/// A pulse followed through a column: each step() advances the solver one
/// step and records the mean velocity component `d` of the gridpoints
/// `middle` (its time centroid and peak) and the worst energy-account error
/// over the largest term.
struct PulseRecord
{
  std::vector<unsigned int> middle;
  int d = 2;
  double sum_v = 0.0, sum_tv = 0.0, peak = 0.0, worst_error = 0.0;

  void step(talus::DeformableSolver& solver)
  {
    solver.step();
    const std::vector<double> v = solver.velocities();
    double mean = 0.0;
    for (unsigned int g : middle)
      mean += v[3 * g + d] / middle.size();
    const double t = solver.time() - 0.5 * solver.dt(); // v of the last half step
    sum_v += mean;
    sum_tv += t * mean;
    peak = std::max(peak, mean);
    talus::EnergyAccount e;
    solver.add_energy(e);
    worst_error = std::max(worst_error, std::abs(e.error()) / e.scale());
  }
  /// The time centroid of the mean velocity (s).
  double centre() const { return sum_tv / sum_v; }
};
