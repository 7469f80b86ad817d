// Extreme scene: parameters/stability/near_incompressible.prm (see the comment there).
// Zones on the updated geometry with the Jaumann stress rate are not
// exactly hyperelastic, and the friction account of sub-contacts whose
// forces are carried over at updates is bounded, not exact: the balance
// (about 2e-2 here) is reported, not asserted; what must hold is no NaN
// and no kinetic energy beyond what the sources gave.

#include "stability.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  StabilityRun r("near_incompressible.prm");
  r.run();
  r.report(-2e-2);
}
