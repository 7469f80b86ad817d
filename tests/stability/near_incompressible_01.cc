// Extreme scene: parameters/stability/near_incompressible.prm (see the comment there).
// Measured 2.7e-5; it was 1.7e-2 while friction missed the energy a shear
// spring gives up when its normal force falls (not the zones' large
// strains, as first thought).

#include "stability.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  StabilityRun r("near_incompressible.prm");
  r.run();
  r.report(1e-3);
}
