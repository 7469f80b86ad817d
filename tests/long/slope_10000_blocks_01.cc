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
  // The balance closes to 1.5e-3 (it lost 1.9e-2 before rebuilt
  // sub-contacts carried shear stress and friction counted all the slip).
  r.report(2e-2);
  const double ratio = r.solver().unbalanced_ratio();
  std::printf("equilibrium: unbalanced ratio %.1e (target %.0e) %s\n", ratio,
              r.scene.solver.target_ratio, ratio < r.scene.solver.target_ratio ? "OK" : "WRONG");
}
