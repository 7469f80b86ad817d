// Extreme scene: parameters/stability/spinning_block.prm (see the comment there).
// A block turning at 100 rad/s meets others edge first at every angle,
// its sub-contacts rebuilt every step (5.1e-3 measured; 5.4e-2 before
// sub-contacts carried shear stress and friction counted all of the slip).

#include "stability.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  StabilityRun r("spinning_block.prm");
  r.run();
  r.report(2e-2);
}
