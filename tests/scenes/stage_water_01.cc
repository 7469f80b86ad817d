// Stages that change the water ('Water' inside 'Stage N'):
//  - rigid blocks (tests/scenes/staged_water.prm): a 1 m cube on a joint
//    of kn = 1e9 Pa/m; dry it sinks W / kn (W = 25506 N); flooded over its
//    top, (W - U) / kn with the buoyancy U = rho_w g V = 9810 N; with the
//    surface at its middle, (W - U / 2) / (kn + rho_w g A) (its sinking
//    deepens the water on it); drained, W / kn again (1e-6); and the
//    history's pore pressure at its centroid, rho_w g (z_w - z) or 0;
//  - a deformable cube (tests/scenes/staged_water_deformable.prm, every
//    zone formulation) on a joint that holds, so that all is linear: the
//    flooded stage ends where a run flooded from the start ends, and the
//    drained stage where the dry one did (1e-3 of the water's effect at the
//    top face's middle and the base's, or of U / kn where it is smaller).

#include <talus/base/parallel_environment.h>

#include <tuple>

#include "../tests.h"
#include "stage_history.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  {
    const double W = 2600 * 9.81, U = 1000 * 9.81, kn = 1e9;
    Scene scene = read_scene(std::string(SOURCE_DIR) + "/staged_water.prm", false);
    std::printf("rigid: exit code %d\n", run_quietly(scene));
    std::vector<std::string> columns;
    const auto rows = read_history(
        scene.output.directory + "/" + scene.output.base_name + "_history.csv", columns);
    // Half submerged, the cube's sinking u deepens the water on it: the
    // buoyancy is rho_w g (0.5 m + |u|) m^2, and u = -(W - U / 2) / (kn + rho_w g).
    const double expected[4] = {-W / kn, -(W - U) / kn, -(W - U / 2) / (kn + U), -W / kn};
    const char* name[4] = {"dry", "flooded", "half drained", "drained"};
    for (int s = 0; s < 4; ++s)
      talus_test::check_within(std::string("rigid: stage ") + std::to_string(s + 1) + ", " +
                                   name[s] + " (m)",
                               column(last_of_stage(rows, columns, s + 1), columns,
                                      "block 1 uz (m)"),
                               expected[s], 1e-6);
    // The history's pore pressure at the cube's centroid (z = 1.5 m + uz):
    // rho_w g (z_w - z) below the surface, 0 above it or without water.
    const double level[4] = {-1e9, 3.0, 1.5, -1e9};
    for (int s = 0; s < 4; ++s)
    {
      const std::vector<double>& end = last_of_stage(rows, columns, s + 1);
      const double z = 1.5 + column(end, columns, "block 1 uz (m)");
      const double p = column(end, columns, "block 1 pore pressure (Pa)");
      std::printf("rigid: stage %d, the history's pore pressure at the cube's centroid: %s\n",
                  s + 1, talus_test::verdict(std::abs(p - std::max(0.0, U * (level[s] - z))) <=
                                             1e-9 * U));
    }
  }
  for (const auto& [element, nodal_mixed, name] :
       {std::tuple{ZoneElement::tet4, false, "tet4"}, std::tuple{ZoneElement::tet4, true, "nmd"},
        std::tuple{ZoneElement::tet10, false, "tet10"},
        std::tuple{ZoneElement::hex_mixed, false, "hex-mixed"}})
  {
    Scene scene = read_scene(std::string(SOURCE_DIR) + "/staged_water_deformable.prm", false);
    scene.deformable.material.element = element;
    scene.deformable.material.nodal_mixed = nodal_mixed;
    scene.output.directory += std::string("_") + name;
    scene.output.write_vtu = false;
    // The same cube flooded from the start, one stage.
    Scene flooded = scene;
    flooded.solver.water = scene.stages[1].water;
    flooded.stages.clear();
    flooded.output.directory += "_flooded";
    const int code = run_quietly(scene), code_flooded = run_quietly(flooded);
    std::printf("%s: both runs end in equilibrium: %s\n", name,
                talus_test::verdict(code == 0 && code_flooded == 0));
    std::vector<std::string> columns, columns_flooded;
    const auto rows = read_history(
        scene.output.directory + "/" + scene.output.base_name + "_history.csv", columns);
    const auto rows_flooded = read_history(
        flooded.output.directory + "/" + flooded.output.base_name + "_history.csv",
        columns_flooded);
    {
      // The history's pore pressure at the top face's middle, flooded.
      const std::vector<double>& end = last_of_stage(rows, columns, 2);
      const double z = 2 + column(end, columns, "point 0 uz (m)");
      std::printf("  %s: the history's pore pressure at the top face, flooded: %s\n", name,
                  talus_test::verdict(std::abs(column(end, columns, "point 0 pore pressure (Pa)") -
                                               1000 * 9.81 * (3 - z)) <= 1e-9 * 1000 * 9.81));
    }
    for (const auto& [point, where] :
         {std::pair{"point 0 uz (m)", "top face"}, std::pair{"point 1 uz (m)", "base"}})
    {
      const double dry = column(last_of_stage(rows, columns, 1), columns, point),
                   wet = column(last_of_stage(rows, columns, 2), columns, point),
                   drained = column(last_of_stage(rows, columns, 4), columns, point),
                   from_start = column(rows_flooded.back(), columns_flooded, point);
      // The water's effect there, or (where its parts cancel) that of the
      // buoyancy on the joint, U / kn = 9.81e-6 m.
      const double effect = std::max(std::abs(from_start - dry), 1000 * 9.81 / 1e9);
      std::fprintf(stderr, "%s %s: dry %.10g, flooded %.10g (from the start %.10g), drained %.10g\n",
                   name, where, dry, wet, from_start, drained);
      std::printf("  %s: %s, flooded by a stage as flooded from the start: %s\n", name, where,
                  talus_test::verdict(std::abs(wet - from_start) <= 1e-3 * effect));
      std::printf("  %s: %s, drained back where it was dry: %s\n", name, where,
                  talus_test::verdict(std::abs(drained - dry) <= 1e-3 * effect));
    }
  }
}
