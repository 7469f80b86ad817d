// Extreme scene: parameters/stability/spinning_block.prm (see the comment there).
// Sub-contacts rebuilt every step on a block turning at 100 rad/s carry
// their shear forces over to sub-contacts of other areas, and the
// friction account of those is bounded, not exact: the balance (about
// 5e-2 here) is reported, not asserted; what must hold is no NaN and no
// kinetic energy beyond what the sources gave.

#include "stability.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  StabilityRun r("spinning_block.prm");
  r.run();
  r.report(-2e-2);
}
