// Extreme scene: parameters/stability/soft_beside_stiff.prm (see the comment there).

#include "stability.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  StabilityRun r("soft_beside_stiff.prm");
  r.run();
  r.report(1e-2);
}
