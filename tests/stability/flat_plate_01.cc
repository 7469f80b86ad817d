// Extreme scene: parameters/stability/flat_plate.prm (see the comment there).

#include "stability.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  StabilityRun r("flat_plate.prm");
  r.run();
  r.report(1e-2);
}
