// Extreme scene: parameters/stability/tunnel_roof_collapse.prm (see the
// comment there). Hundreds of blocks fall at once and hit each other: each
// contact that closes part way through a step adds or loses up to about
// (omega dt)^2 of its impact's energy, hence the 2 % tolerance.

#include "stability.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  StabilityRun r("tunnel_roof_collapse.prm");
  r.run();
  r.report(2e-2);
  double largest = 0.0;
  for (const talus::Vec3& u : r.solver().displacement)
    largest = std::max(largest, u.norm());
  std::fprintf(stderr, "blocks fell: largest displacement %.2f m\n", largest);
  std::printf("blocks fell: largest displacement above 0.2 m: %s\n",
              largest > 0.2 ? "yes (collapsing)" : "NO (not collapsing)");
}
