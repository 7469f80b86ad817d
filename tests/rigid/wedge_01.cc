// Verification 3: a symmetric wedge on two joints dipping 45 deg, the line of
// intersection plunging 30 deg (parameters/verification/wedge.prm). Limit
// equilibrium gives FS = tan(phi) / (tan(30) sin(45)) = 1 at
// phi = 22.208 deg: 0.2 deg below it the wedge slides, 0.2 deg above it holds.

#include <cmath>
#include <cstdio>

#include "rigid_scene.h"

int main()
{
  const double deg = M_PI / 180.0;
  const double critical = std::atan(std::tan(30 * deg) * std::sin(45 * deg)) / deg;
  std::printf("limit-equilibrium friction angle: %.4f deg\n", critical);
  for (double offset : {-0.2, 0.2})
  {
    const double phi = critical + offset;
    RigidScene s("verification/wedge.prm",
                 [&](talus::Scene& scene) { scene.solver.joint.friction_angle = phi; });
    unsigned int wedge = 0;
    for (unsigned int b = 0; b < s.model.n_blocks(); ++b)
      if (s.model.group_names[s.model.group[b]] == "wedge")
        wedge = b;
    s.run_until(1.0);
    const double moved = s.solver->displacement[wedge].norm();
    // Closed-form acceleration along the line of intersection.
    const double a = 9.81 * (std::sin(30 * deg) - std::cos(30 * deg) * std::tan(phi * deg) /
                                                       std::sin(45 * deg));
    std::printf("phi = critical %+.1f deg: moved %.3g m in 1 s (closed form %.3g m): %s\n", offset,
                moved, std::max(a, 0.0) / 2, moved > 1e-3 ? "slides" : "holds");
  }
}
