// Extreme scene: parameters/stability/near_incompressible.prm (see the comment there).

#include "stability.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  StabilityRun r("near_incompressible.prm");
  r.run();
  r.report(1e-2);
}
