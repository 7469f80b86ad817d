// Extreme scene: parameters/stability/flat_plate.prm (see the comment there).
// One impact at 2 m/s: the contact that closes part way through a step
// changes the energy by at most about (omega dt)^2 of the impact's: 1e-2.

#include "stability.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  StabilityRun r("flat_plate.prm");
  r.run();
  r.report(1e-2);
}
