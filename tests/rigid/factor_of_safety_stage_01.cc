// A factor of safety as a stage ('Mode = factor of safety' in 'Stage N'):
// the slider of tests/rigid/factor_of_safety_01 (1 x 2 x 0.2 m on a 30 deg
// incline, phi = 35 deg, W = 10398.6 N, A = 2 m^2), run in stages:
//  1. static equilibrium, dry;
//  2. water of p = 500 Pa in its joint ('Water' with 'Joint pressures'):
//     still stable, its effective normal force W cos a - p A = 8005.5 N;
//  3. the contacts between the slider and the base take joint material
//     'rough' (phi = 40 deg, 'Group contacts' of the stage), then the factor
//     of safety from that state: F = (W cos a - p A) tan 40 / (W sin a) =
//     1.2920, within 0.5 % (the search's bracket); 1.0781 with phi = 35
//     were the material not changed, 1.4527 were the water not set again;
//  4. static again: the model went on unchanged through stage 3 (the
//     slider where stage 2 left it, to 1e-12 m).
// The mechanism's frames are files of their own
// (talus_stage3_mechanism_blocks_00000.vtu): they once took the name of the
// run's first frame, talus_blocks_00000.vtu, which then showed the
// mechanism in the run's series.
// The before figure: 'factor of safety' is not a stage's 'Mode' (refused).

#include <talus/base/parallel_environment.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "../scenes/stage_history.h"
#include "../tests.h"
#include "slider_scene.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  const double deg = M_PI / 180.0, a = 30 * deg, g = 9.81, A = 2.0, p = 500, W = 2650 * 0.4 * g;
  const std::string file = "factor_of_safety_stage_01_scene.prm";
  write_slider_scene(file, 30, "  set Steps = 5000\n  set History blocks = 1",
                     R"(subsection Joint properties
  set Normal stiffness = 1e11
  set Shear stiffness  = 1e11
  set Friction angle = 35
end
subsection Joint material 1
  set Name = rough
  set Normal stiffness = 1e11
  set Shear stiffness  = 1e11
  set Friction angle = 40
end
subsection Stage 1
  set Name = dry
end
subsection Stage 2
  set Name = water in the joint
  subsection Water
    set Joint pressures = 1, )" +
                         std::to_string(p) +
                         R"(
  end
end
subsection Stage 3
  set Name = factor of safety
  set Mode = factor of safety
  set Group contacts = slider, base = rough
end
subsection Stage 4
  set Name = on, unchanged
end
subsection Output
  set Directory = output_factor_of_safety_stage_01
end
)");
  // Run with the summary kept, for its factor of safety.
  std::fflush(stdout);
  const int saved = dup(1);
  std::freopen("factor_of_safety_stage_01_summary.txt", "w", stdout);
  int code = -1;
  try
  {
    code = Simulation(file, "", false).run();
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "%s\n", e.what());
  }
  std::fflush(stdout);
  dup2(saved, 1);
  close(saved);
  std::printf("exit code %d\n", code);
  double F = NAN;
  std::ifstream summary("factor_of_safety_stage_01_summary.txt");
  for (std::string line; std::getline(summary, line);)
  {
    std::fprintf(stderr, "| %s\n", line.c_str());
    const std::size_t at = line.find("Factor of safety: ");
    if (at != std::string::npos)
      F = std::stod(line.substr(at + 18));
  }
  talus_test::check_within("stage 3: F = (W cos a - p A) tan 40 / (W sin a)", F,
                           (W * std::cos(a) - p * A) * std::tan(40 * deg) / (W * std::sin(a)),
                           0.005);
  std::vector<std::string> columns;
  const auto rows = read_history("output_factor_of_safety_stage_01/talus_history.csv", columns);
  double moved = 0.0;
  for (const char* q : {"block 1 ux (m)", "block 1 uy (m)", "block 1 uz (m)"})
    moved = std::max(moved, std::abs(column(last_of_stage(rows, columns, 4), columns, q) -
                                     column(last_of_stage(rows, columns, 2), columns, q)));
  std::fprintf(stderr, "stage 4 moved the slider %.3g m from where stage 2 left it\n", moved);
  std::printf("stage 4: the slider where stage 2 left it (stage 3 changed nothing): %s\n",
              talus_test::verdict(moved < 1e-12));
  const auto text = [](const std::string& path)
  {
    std::ifstream in(path, std::ios::binary);
    std::stringstream all;
    all << in.rdbuf();
    return all.str();
  };
  const std::string folder = "output_factor_of_safety_stage_01/",
                    own = "talus_stage3_mechanism_blocks_00000.vtu";
  const std::string series = text(folder + "talus_stage3_mechanism_blocks.pvd"),
                    mechanism = text(folder + own), first = text(folder + "talus_blocks_00000.vtu");
  std::printf("mechanism frame in a file of its own, the run's first frame not it: %s\n",
              talus_test::verdict(series.find("file=\"" + own + "\"") != std::string::npos &&
                                  !mechanism.empty() && !first.empty() && mechanism != first));
}
