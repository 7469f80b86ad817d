#pragma once

// Builds a solver from the text of a parameter file (written to a file in
// the test's folder first), for small scenes made up by a test.

#include <talus/io/scene.h>
#include <talus/model/build_blocks.h>
#include <talus/solver/rigid_solver.h>

#include <cstdio>
#include <memory>
#include <string>

struct TextScene
{
  talus::Scene scene;
  talus::BlockModel model;
  std::unique_ptr<talus::RigidSolver> solver;

  /// Writes `text` to `file` and builds the blocks and the solver from it.
  TextScene(const std::string& file, const std::string& text)
  {
    std::FILE* f = std::fopen(file.c_str(), "w");
    std::fputs(text.c_str(), f);
    std::fclose(f);
    scene = talus::read_scene(file, false);
    talus::BuildReport report;
    model = talus::build_blocks(scene, report);
    talus::resolve_group_names(scene, model);
    solver = std::make_unique<talus::RigidSolver>(model, scene.density, scene.solver);
  }
};
