// Extreme scene: parameters/stability/soft_beside_stiff.prm (see the comment there).
// Zones on the updated geometry with the Jaumann stress rate are not
// exactly hyperelastic: the balance closes to about the largest strain.

#include "stability.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  StabilityRun r("soft_beside_stiff.prm");
  r.run();
  r.report(2e-2);
}
