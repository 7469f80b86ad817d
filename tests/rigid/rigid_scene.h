#pragma once

// Runs a shipped scene of parameters/ without writing output, for the
// verification tests of the rigid-block engine.

#include <talus/scene/scene.h>
#include <talus/scene/build_blocks.h>
#include <talus/solver/rigid_solver.h>

#include <memory>
#include <string>

struct RigidScene
{
  talus::Scene scene;
  talus::BlockModel model;
  std::unique_ptr<talus::RigidSolver> solver;

  /// Reads parameters/<name>, applying `edit` to the scene before the
  /// solver is built (to vary one value of a shipped scene), and
  /// `edit_model` to the blocks once built (to move one).
  template <typename Edit, typename EditModel>
  RigidScene(const std::string& name, Edit edit, EditModel edit_model)
  {
    scene = talus::read_scene(std::string(SOURCE_DIR) + "/../../parameters/" + name, false);
    edit(scene);
    talus::BuildReport report;
    model = talus::build_blocks(scene, report);
    talus::resolve_group_names(scene, model);
    edit_model(model);
    solver = std::make_unique<talus::RigidSolver>(model, scene.density, scene.solver);
  }
  template <typename Edit>
  RigidScene(const std::string& name, Edit edit) : RigidScene(name, edit, [](talus::BlockModel&) {})
  {
  }
  explicit RigidScene(const std::string& name) : RigidScene(name, [](talus::Scene&) {}) {}

  /// Steps until model time `t` (s).
  void run_until(double t)
  {
    while (solver->time() + 0.5 * solver->dt() < t)
      solver->step();
  }
  /// Steps (statics) until the unbalanced-force ratio is below `ratio`.
  unsigned long run_to_ratio(double ratio, unsigned long max_steps)
  {
    unsigned long n = 0;
    while ((n < 20 || solver->unbalanced_ratio() >= ratio) && n < max_steps)
    {
      solver->step();
      ++n;
    }
    return n;
  }
};
