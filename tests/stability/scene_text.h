#pragma once

// Builds a solver from the text of a parameter file (written to a file in
// the test's folder first), for small scenes made up by a test.

#include <talus/scene/scene.h>
#include <talus/scene/build_blocks.h>
#include <talus/solver/rigid_solver.h>

#include <cstdio>
#include <memory>
#include <sstream>
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

/// The first subsections of a scene of a 1 m cube (group `cube`) held
/// `gap` m above a fixed 1 m cube (group `floor`): a brick
/// cut by a horizontal joint at z = 1 with the layer [1, 1 + gap]
/// excavated; density 2650 kg/m^3. A test appends its loads and solver.
inline std::string cube_above_floor(double gap)
{
  std::ostringstream top, cube_bottom;
  top << 2.0 + gap;
  cube_bottom << 1.0 + gap;
  return "subsection Model\n"
         "  set Brick min = 0, 0, 0\n"
         "  set Brick max = 1, 1, " +
         top.str() +
         "\n"
         "end\n"
         "subsection Material\n"
         "  set Density = 2650\n"
         "end\n"
         "subsection Joint 1\n"
         "  set Dip = 0\n"
         "  set Origin = 0, 0, 1\n"
         "end\n"
         "subsection Excavation 1\n"
         "  set Corner min = -1, -1, 1\n"
         "  set Corner max = 2, 2, " +
         cube_bottom.str() +
         "\n"
         "end\n"
         "subsection Group 1\n"
         "  set Name = floor\n"
         "  set Corner min = 0, 0, 0\n"
         "  set Corner max = 1, 1, 1\n"
         "end\n"
         "subsection Group 2\n"
         "  set Name = cube\n"
         "  set Corner min = 0, 0, " +
         cube_bottom.str() +
         "\n"
         "  set Corner max = 1, 1, " +
         top.str() +
         "\n"
         "end\n";
}
