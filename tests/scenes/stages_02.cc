// Stages with deformable blocks, in every zone formulation: two deformable
// 1 m cubes (E = 1e8 Pa, nu = 0) stacked on a fixed rigid base on joints
// of kn = 1e9 Pa/m (parameters/verification/staged_stack.prm). Stage 1
// settles under gravity; stage 2 excavates the top cube (a region the
// model was cut along) and resets displacements; stage 3 runs 0.002 s of
// dynamics. Removing the top cube's weight W = 2600 x 9.81 = 25506 N lets
// the lower cube rise: its base by W / kn = 2.5506e-5 m at the joint, its
// top face by that plus W h / (E A) = 2.5506e-4 m of elastic rebound
// (uniaxial, nu = 0, h = A = 1): 2.80566e-4 m. Checked at the middle of
// the lower cube's top face (a history point; the contact between two
// meshed cubes spreads the weight a few tenths of a percent unevenly over
// the face, so 1 %), and:
//  - the removed cube's gridpoints are held and, after the reset, at zero;
//  - the energy balance error does not change over the excavation stage
//    (the energy the removed cube held leaves the account with it);
//  - stage 3 (dynamic, from rest) keeps the lower cube where it is;
//  - stage 4 (static, reset) makes the lower cube of twice the density: the
//    added weight is the lower cube's own again, so (all linear) each point
//    moves as the lower cube's weight alone moved it in stage 1: its stage 1
//    displacement (both cubes) plus its stage 2 rise (the top cube's weight
//    taken away), to 1e-3 in every formulation. In the continuum: the base
//    sinks W / kn, the top face W / kn + rho g h^2 / (2 E) more, which the
//    hexahedral zones give to 1e-3 and the coarse tetrahedra at the face's
//    middle to some 7 % (their lumped gravity is uneven over the joint).
// The before figure: with the removed zones keeping their mass (null
// material of density 2600) the rebound is 0 and every check fails.

#include <talus/base/parallel_environment.h>
#include <talus/run/simulation.h>
#include <talus/scene/scene.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "../tests.h"
#include "stage_history.h"

using namespace talus;

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  const double W = 2600 * 9.81, kn = 1e9, E = 1e8;
  const double rebound = W / kn + W / E;
  for (const auto& [element, nodal_mixed, name] :
       {std::tuple{ZoneElement::tet4, false, "tet4"}, std::tuple{ZoneElement::tet4, true, "nmd"},
        std::tuple{ZoneElement::tet10, false, "tet10"},
        std::tuple{ZoneElement::hex_mixed, false, "hex-mixed"}})
  {
    Scene scene = read_scene(
        std::string(SOURCE_DIR) + "/../../parameters/verification/staged_stack.prm", false);
    scene.deformable.material.element = element;
    scene.deformable.material.nodal_mixed = nodal_mixed;
    scene.output.directory = std::string("output_stages_02_") + name;
    scene.output.write_vtu = false;
    const int code = run_quietly(scene);
    std::printf("%s: exit code %d\n", name, code);
    std::vector<std::string> columns;
    const std::vector<std::vector<double>> rows = read_history(
        scene.output.directory + "/" + scene.output.base_name + "_history.csv", columns);
    const std::vector<double>& end2 = last_of_stage(rows, columns, 2);
    const std::vector<double>& end3 = last_of_stage(rows, columns, 3);
    talus_test::check_within(std::string("  ") + name +
                                 ": stage 2, rise of the lower cube's top face (m)",
                             column(end2, columns, "point 0 uz (m)"), rebound, 0.01);
    talus_test::check_within(std::string("  ") + name + ": stage 2, rise of its base (m)",
                             column(end2, columns, "point 1 uz (m)"), W / kn, 0.01);
    std::printf("  %s: the removed cube's gridpoint after the reset: %s\n", name,
                column(end2, columns, "point 2 uz (m)") == 0.0 ? "at zero" : "MOVED (WRONG)");
    // The change over the stage: nodal mixed discretization's account is
    // off by some 2e-3 of the work of gravity from the start (a known
    // error of its own, left for [dynamics]).
    const double change =
        std::abs(column(end2, columns, "energy balance error (J)") -
                 column(last_of_stage(rows, columns, 1), columns, "energy balance error (J)"));
    const double gravity = std::abs(column(end2, columns, "work of gravity (J)"));
    std::printf("  %s: the energy balance error changes by less than 1e-3 of the work of "
                "gravity over the excavation stage: %s\n",
                name, change < 1e-3 * gravity ? "OK" : "WRONG");
    const double u2 = column(end2, columns, "point 0 uz (m)"),
                 u3 = column(end3, columns, "point 0 uz (m)");
    std::printf("  %s: stage 3 (dynamic) keeps it within 1e-3 of where stage 2 left it: %s\n", name,
                talus_test::verdict(std::abs(u3 - u2) <= 1e-3 * std::abs(u2)));
    const std::vector<double>& end4 = last_of_stage(rows, columns, 4);
    const std::vector<double>& end1 = last_of_stage(rows, columns, 1);
    for (const auto& [point, what] : {std::pair{"point 1 uz (m)", "base"},
                                      std::pair{"point 0 uz (m)", "top face"}})
    {
      const double own = column(end1, columns, point) + column(end2, columns, point);
      const double u4 = column(end4, columns, point);
      std::fprintf(stderr, "%s: stage 4 %s %.10g m, own weight %.10g m\n", name, what, u4, own);
      std::printf("  %s: stage 4, twice the density, its %s moves as its own weight moved it, "
                  "to 1e-3: %s\n",
                  name, what, talus_test::verdict(talus_test::relative_error(u4, own) <= 1e-3));
    }
    const double continuum[2] = {-W / kn, -W / kn - W / (2 * E)};
    std::fprintf(stderr, "%s: stage 4 against the continuum: base %.3g, top face %.3g\n", name,
                 talus_test::relative_error(column(end4, columns, "point 1 uz (m)"), continuum[0]),
                 talus_test::relative_error(column(end4, columns, "point 0 uz (m)"), continuum[1]));
    if (element == ZoneElement::hex_mixed)
      talus_test::check_within(std::string("  ") + name + ": stage 4, its top face (m)",
                               column(end4, columns, "point 0 uz (m)"), continuum[1], 1e-3);
  }
}
