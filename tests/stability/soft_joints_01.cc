// Extreme scene: parameters/stability/soft_joints.prm (see the comment there).

#include "stability.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  StabilityRun r("soft_joints.prm");
  r.run();
  r.report(1e-2);
}
