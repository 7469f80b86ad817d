// Extreme scene: parameters/stability/degenerate_contacts.prm (see the comment there).
// The falling blocks hit the floor and the pillars: each contact that
// closes part way through a step changes the energy by up to about
// (omega dt)^2 = 4e-2 of its impact's; tolerance 2e-2.

#include "stability.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  StabilityRun r("degenerate_contacts.prm");
  r.run();
  r.report(2e-2);
}
