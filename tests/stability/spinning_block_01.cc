// Extreme scene: parameters/stability/spinning_block.prm (see the comment there).
// A block turning at 100 rad/s meets others edge first at every angle;
// sub-contacts rebuilt every step take over the shear forces of the
// nearest old ones, and what friction dissipates across those rebuilds is
// bounded, not exact: about 5 % of the energy goes unaccounted, all of it
// lost. What is asserted: no energy created beyond the tolerance, no NaN,
// no kinetic energy beyond what the sources gave.

#include "stability.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  StabilityRun r("spinning_block.prm");
  r.run();
  r.report(2e-2, true);
}
