// Extreme scene: parameters/stability/sliver_beside_large_block.prm (see the comment there).

#include "stability.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  StabilityRun r("sliver_beside_large_block.prm");
  r.run();
  r.report(1e-2);
}
