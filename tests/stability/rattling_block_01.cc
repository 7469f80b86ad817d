// Extreme scene: parameters/stability/rattling_block.prm (see the comment there).

#include "stability.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  StabilityRun r("rattling_block.prm");
  r.run();
  r.report(1e-2);
}
