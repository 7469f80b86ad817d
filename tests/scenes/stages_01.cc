// Stages with rigid blocks (tests/scenes/staged_cubes.prm): three 1 m
// cubes stacked on a fixed one on joints of kn = 1e9 Pa/m. W = rho g V =
// 2600 x 9.81 = 25506 N per cube.
//  - Stage 1 (static): the joints close under the weight above them: the
//    middle cube sinks 2 W / kn = 5.1012e-5 m, the top one 3 W / kn.
//  - Stage 2 (static): the top cube is excavated (its group chosen by block
//    number) and displacements reset: the middle cube rises W / kn =
//    2.5506e-5 m; the removed cube stays at zero.
//  - Stage 3 (dynamic, 'Time limit' 0.005 s): from rest it stays there,
//    and the stage takes the time limit to within a step.
// Static stages stop at a target ratio of 1e-8: the displacements are
// checked to 1e-6 (the step counts, which follow the CPU's rounding, go to
// standard error).

#include <talus/base/parallel_environment.h>

#include "../tests.h"
#include "stage_history.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  const double W = 2600 * 9.81, kn = 1e9;
  talus::Scene scene = talus::read_scene(std::string(SOURCE_DIR) + "/staged_cubes.prm", false);
  const int code = run_quietly(scene);
  std::printf("exit code %d\n", code);
  std::vector<std::string> columns;
  const std::vector<std::vector<double>> rows =
      read_history(scene.output.directory + "/" + scene.output.base_name + "_history.csv", columns);
  const std::vector<double>&end1 = last_of_stage(rows, columns, 1),
        &end2 = last_of_stage(rows, columns, 2), &end3 = last_of_stage(rows, columns, 3);
  std::fprintf(stderr, "stage ends at steps %g, %g, %g\n", end1[0], end2[0], end3[0]);
  talus_test::check_within("stage 1: the middle cube sinks 2 W / kn (m)",
                           column(end1, columns, "block 1 uz (m)"), -2 * W / kn, 1e-6);
  talus_test::check_within("stage 1: the top cube sinks 3 W / kn (m)",
                           column(end1, columns, "block 2 uz (m)"), -3 * W / kn, 1e-6);
  talus_test::check_within("stage 2: the middle cube rises W / kn (m)",
                           column(end2, columns, "block 1 uz (m)"), W / kn, 1e-6);
  std::printf("stage 2: the removed top cube at zero: %s\n",
              talus_test::verdict(column(end2, columns, "block 2 uz (m)") == 0.0));
  talus_test::check_within("stage 3 (dynamic): the middle cube stays at W / kn (m)",
                           column(end3, columns, "block 1 uz (m)"), W / kn, 1e-6);
  const double span = column(end3, columns, "time (s)") - column(end2, columns, "time (s)");
  const double dt = column(rows[2], columns, "time (s)") - column(rows[1], columns, "time (s)");
  std::printf("stage 3 takes its time limit of 0.005 s to within a step: %s\n",
              talus_test::verdict(span >= 0.005 - 0.5 * dt / 10 && span < 0.005 + dt / 10));
}
