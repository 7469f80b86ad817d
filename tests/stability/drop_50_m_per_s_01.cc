// Extreme scene: a cube thrown at 50 m/s onto a fixed floor
// (parameters/stability/drop_50_m_per_s.prm). Besides the stability checks,
// the bounce must give the kinetic energy back: undamped, with no slip,
// the block leaves the floor at the speed it hit it (less what gravity
// took on the way, v^2 = v0^2 - 2 g h both ways), so its rebound speed is
// compared with the impact speed. The contact closes part way through a
// step (the block moves 5 mm a step), which changes the energy by up to
// (omega dt)^2 = 4e-2 of it; tolerance 2e-2.

#include <cmath>

#include "../tests.h"
#include "stability.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  StabilityRun r("drop_50_m_per_s.prm");
  r.run();
  r.report(2e-2);
  const unsigned int block = r.block_of("block");
  std::printf("block %u rises again: %s\n", block,
              r.solver().velocity[block].z() > 0 ? "yes" : "NO");
  // Free flight after the bounce: v_z^2 + 2 g z is the same as before it.
  const double g = 9.81, v0 = 50.0;
  const double z = r.solver().displacement[block].z();
  const double vz = r.solver().velocity[block].z();
  talus_test::check("rebound energy per unit mass, (v^2 + 2 g z) / 2 (J/kg)", 0.5 * vz * vz + g * z,
                    0.5 * v0 * v0, 2e-2);
}
