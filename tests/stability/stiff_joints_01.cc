// Extreme scene: parameters/stability/stiff_joints.prm (see the comment there).
// No contact closes part way through a step, so the energy balance closes
// to the accuracy of the central difference scheme: tolerance 1e-4.

#include "stability.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  StabilityRun r("stiff_joints.prm");
  r.run();
  r.report(1e-4);
}
