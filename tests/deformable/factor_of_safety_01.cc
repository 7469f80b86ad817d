// Factor of safety by strength reduction with a deformable block: the
// block of parameters/verification/deformable_on_incline.prm (1 x 2 x 1 m,
// elastic zones, E = 50 GPa, on a fixed rigid base; friction 20 deg) on a
// 30 deg incline (gravity tilted). Its joint with the base is at its limit
// at F = tan 20 / tan 30 = 0.63041 (the zones are elastic, so 'Reduce zone
// strength' changes nothing); within 0.5 %. The mechanism, the last
// unstable trial's gridpoints, slides down the slope (+x).

#include <talus/base/parallel_environment.h>
#include <talus/scene/build_blocks.h>
#include <talus/scene/factor_of_safety.h>

#include <cmath>
#include <cstdio>

#include "../tests.h"

using namespace talus;

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  Scene scene = read_scene(
      std::string(SOURCE_DIR) + "/../../parameters/verification/deformable_on_incline.prm", false);
  const double deg = M_PI / 180.0, a = 30 * deg;
  // Static trials, as 'Mode = factor of safety' sets them.
  scene.solver.dynamic = false;
  scene.solver.local_damping = 0.8;
  scene.solver.gravity = Vec3(9.81 * std::sin(a), 0.0, -9.81 * std::cos(a));
  scene.solver.steps = 5000;
  scene.strength_reduction.enabled = true;
  scene.strength_reduction.reduce_zone_strength = true;
  BuildReport built;
  BlockModel model = build_blocks(scene, built);
  resolve_group_names(scene, model);
  double slide_x = 0.0, slide = 0.0;
  unsigned int zones = 0;
  TrialHooks hooks;
  hooks.finished = [&](const TrialView& view, const StrengthReductionTrial& t)
  {
    if (t.stable || !view.system.zones)
      return;
    zones = view.system.mesh.n_zones();
    const std::vector<double> u = view.system.zones->displacements();
    const unsigned int n = view.system.mesh.n_gridpoints();
    slide_x = slide = 0.0;
    for (unsigned int g = 0; g < n; ++g)
    {
      const double dx = u[3 * g] - view.start_gridpoint_displacement[3 * g];
      const double dz = u[3 * g + 2] - view.start_gridpoint_displacement[3 * g + 2];
      slide_x += dx / n;
      slide += std::sqrt(dx * dx + dz * dz) / n;
    }
  };
  const StrengthReductionResult r =
      factor_of_safety(scene, model, hooks,
                       [](const StrengthReductionTrial& t)
                       { std::fprintf(stderr, "  %s\n", trial_line(t).c_str()); });
  std::printf("found: %s; mechanism in %s zones\n", r.found ? "yes" : "no",
              zones > 0 ? "the" : "NO");
  talus_test::check_within("F of the deformable block", r.factor(),
                           std::tan(20 * deg) / std::tan(30 * deg), 0.005);
  std::fprintf(stderr, "mechanism: mean slide %.3g m, along the slope %.3g m\n", slide, slide_x);
  std::printf("mechanism slides down the slope: %s\n",
              talus_test::verdict(slide_x > 0.0 && slide_x > 0.9 * slide));
}
