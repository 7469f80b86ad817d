// Extreme scene: parameters/stability/slope_10000_blocks.prm, a benched
// slope of about 11,000 blocks run by the static solver to equilibrium
// (unbalanced ratio 1e-4). Checks as for the other extreme scenes (no NaN
// or infinity, kinetic energy within its sources, energy balance) and that
// the run reached the target ratio before its step limit.

#include "../stability/stability.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  StabilityRun r("slope_10000_blocks.prm");
  r.run(r.scene.solver.steps, 100);
  // Sub-contacts rebuilt at the common-plane updates of a static run
  // lose a little stored joint energy (about 2 % of the largest term over
  // the run): no energy may be created beyond the tolerance.
  r.report(2e-2, true);
  const double ratio = r.solver().unbalanced_ratio();
  std::printf("equilibrium: unbalanced ratio %.1e (target %.0e) %s\n", ratio,
              r.scene.solver.target_ratio, ratio < r.scene.solver.target_ratio ? "OK" : "WRONG");
}
