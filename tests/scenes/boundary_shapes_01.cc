// Boundaries given as regions of other shapes than boxes ('Shape' of
// 'Boundary N', as for excavations and groups):
//  - rigid blocks (tests/scenes/shaped_boundaries_rigid.prm): a half-space
//    presses the top face of a 1 m cube with p = 50 kPa, and only that face
//    (the side faces leave the half-space): the cube sinks (W + p A) / kn
//    on its joint, W = 25506 N, kn = 1e9 Pa/m, A = 1 m^2 (to 1e-6);
//  - a deformable column (tests/scenes/shaped_boundaries_column.prm) held
//    on rollers by a half-space (base) and by slabs of two planes (sides),
//    its top pressed with p = 1e5 Pa through a cylinder: the top sinks
//    rho g H^2 / (2 M) + p H / M: to 1e-3 for the pressure's part (uniform
//    stress, exact), 1e-2 for gravity's (the zones' lumped gravity on this
//    coarse mesh moves the middle of the top face some 3e-3 off it).
// The before figure: 'Shape' is not an entry of 'Boundary N' (refused).

#include <talus/base/parallel_environment.h>

#include "../tests.h"
#include "stage_history.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  {
    const double W = 2600 * 9.81, kn = 1e9, p = 5e4;
    talus::Scene scene =
        talus::read_scene(std::string(SOURCE_DIR) + "/shaped_boundaries_rigid.prm", false);
    std::printf("rigid: exit code %d\n", run_quietly(scene));
    std::vector<std::string> columns;
    const auto rows = read_history(
        scene.output.directory + "/" + scene.output.base_name + "_history.csv", columns);
    talus_test::check_within("rigid: the cube sinks (W + p A) / kn (m)",
                             column(rows.back(), columns, "block 1 uz (m)"), -(W + p) / kn, 1e-6);
  }
  {
    const double rho_g = 2600 * 9.81, H = 4, M = 1.2e9, p = 1e5;
    talus::Scene scene =
        talus::read_scene(std::string(SOURCE_DIR) + "/shaped_boundaries_column.prm", false);
    scene.output.write_vtu = false;
    std::printf("column: exit code %d\n", run_quietly(scene));
    std::vector<std::string> columns;
    const auto rows = read_history(
        scene.output.directory + "/" + scene.output.base_name + "_history.csv", columns);
    // The same column under gravity alone, for the pressure's part.
    talus::Scene alone = scene;
    alone.face_pressures.clear();
    alone.face_pressure_sections.clear();
    alone.output.directory += "_gravity";
    run_quietly(alone);
    std::vector<std::string> columns_alone;
    const auto rows_alone = read_history(
        alone.output.directory + "/" + alone.output.base_name + "_history.csv", columns_alone);
    const double u = column(rows.back(), columns, "point 0 uz (m)"),
                 u_gravity = column(rows_alone.back(), columns_alone, "point 0 uz (m)");
    talus_test::check_within("column: under gravity alone, the top sinks rho g H^2 / (2 M) (m)",
                             u_gravity, -rho_g * H * H / (2 * M), 1e-2);
    talus_test::check_within("column: the cylinder's pressure sinks it p H / M more (m)",
                             u - u_gravity, -p * H / M, 1e-3);
  }
}
