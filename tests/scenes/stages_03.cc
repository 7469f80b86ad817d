// Loads and face pressures that stages add, replace and release
// (tests/scenes/staged_loads.prm): a 1 m cube on a fixed one, on a joint of
// kn = 1e9 Pa/m over 1 m^2; W = rho g V = 2600 x 9.81 = 25506 N.
//  - Stage 1: the cube sinks W / kn.
//  - Stage 2 (displacements reset): 'Load 1' adds 2 W downwards: it sinks
//    2 W / kn = 5.1012e-5 m.
//  - Stage 3: 'Load 1' replaced by W, and 'Boundary 1' adds p = 50 kPa on
//    the top face: (W + p A) / kn = 7.5506e-5 m from stage 2's start.
//  - Stage 4: both released, and the cube made of 'heavy' rock of twice
//    the density: W / kn below where stage 2 began.
//  - Stage 5 (dynamic): 'Load 2' drives the cube at vx = 0.01 m/s: it moves
//    vx times the stage's time, and its held x velocity is exactly vx.
// Static stages stop at a target ratio of 1e-8; displacements are checked
// to 1e-6 of W / kn's size (step counts go to standard error).

#include <talus/base/parallel_environment.h>

#include "../tests.h"
#include "stage_history.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  const double W = 2600 * 9.81, kn = 1e9, p = 5e4, vx = 0.01;
  talus::Scene scene = talus::read_scene(std::string(SOURCE_DIR) + "/staged_loads.prm", false);
  const int code = run_quietly(scene);
  std::printf("exit code %d\n", code);
  std::vector<std::string> columns;
  const std::vector<std::vector<double>> rows =
      read_history(scene.output.directory + "/" + scene.output.base_name + "_history.csv", columns);
  std::vector<const std::vector<double>*> end;
  for (int s = 1; s <= 5; ++s)
    end.push_back(&last_of_stage(rows, columns, s));
  for (const auto* e : end)
    std::fprintf(stderr, "stage ends at step %g\n", (*e)[0]);
  const auto uz = [&](int s) { return column(*end[s - 1], columns, "block 1 uz (m)"); };
  // Relative to the answer.
  const double tolerance = 1e-6;
  talus_test::check_within("stage 1: the cube sinks W / kn (m)", uz(1), -W / kn, tolerance);
  talus_test::check_within("stage 2: 'Load 1' of 2 W sinks it 2 W / kn more (m)", uz(2),
                           -2 * W / kn, tolerance);
  talus_test::check_within("stage 3: 'Load 1' replaced by W, 'Boundary 1' pressure p: (W + p A) "
                           "/ kn (m)",
                           uz(3), -(W + p) / kn, tolerance);
  talus_test::check_within("stage 4: both released, of twice the density: W / kn (m)", uz(4),
                           -W / kn, tolerance);
  const double span = column(*end[4], columns, "time (s)") - column(*end[3], columns, "time (s)");
  const double ux =
      column(*end[4], columns, "block 1 ux (m)") - column(*end[3], columns, "block 1 ux (m)");
  std::fprintf(stderr, "stage 5: ux %.10g m over %.10g s\n", ux, span);
  std::printf("stage 5: 'Load 2' drives the cube vx times the stage's time, to 1e-9: %s\n",
              talus_test::verdict(std::abs(ux - vx * span) <= 1e-9 * vx * span));
  std::printf("stage 5: its x velocity is vx: %s\n",
              talus_test::verdict(column(*end[4], columns, "block 1 vx (m/s)") == vx));
  // It rings on the joint at the sudden drive, by some 1e-9 m.
  talus_test::check_within("stage 5: its vertical position stays (m)", uz(5), -W / kn, 1e-3);
}
