// Extreme scene: parameters/stability/degenerate_contacts.prm (see the comment there).

#include "stability.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  StabilityRun r("degenerate_contacts.prm");
  r.run();
  r.report(1e-2);
}
