// Verification 1: a block on an incline (parameters/verification/
// block_on_incline.prm: slope 40 deg, friction 20 deg). It slides with
// a = g (sin a - cos a tan phi); after t the displacement is a t^2 / 2.
// Below the friction angle (slope 15 deg) it stays put: that case is a
// static question, solved with local damping from the block at rest.

#include <cmath>
#include <cstdio>

#include "rigid_scene.h"

void slide(double slope_degrees, double t, bool dynamic)
{
  const double g = 9.81, deg = M_PI / 180.0, phi = 20.0 * deg, a = slope_degrees * deg;
  RigidScene s("verification/block_on_incline.prm", [&](talus::Scene& scene) {
    scene.solver.gravity = talus::Vec3(g * std::sin(a), 0.0, -g * std::cos(a));
    scene.solver.dynamic = dynamic;
    scene.solver.local_damping = dynamic ? 0.0 : 0.8;
  });
  if (dynamic)
    s.run_until(t);
  else
    std::printf("static run: %lu steps to ratio 1e-6\n", s.run_to_ratio(1e-6, 200000));
  const double computed = s.solver->displacement[1][0];
  // Shear spring stretch under the weight's slope component.
  const double elastic = s.solver->mass[1] * g * std::sin(a) /
                         (s.scene.solver.joint.shear_stiffness * 2.0 /* m^2 */);
  const double exact = std::max(0.0, g * (std::sin(a) - std::cos(a) * std::tan(phi))) * t * t / 2;
  std::printf("slope %.0f deg, %s: slide %.6g m, closed form %.6g m", slope_degrees,
              dynamic ? "after 0.5 s" : "at equilibrium", computed, exact);
  if (exact > 0.0)
    std::printf(", relative error %.1e %s\n", std::abs(computed - exact) / exact,
                std::abs(computed - exact) / exact < 1e-4 ? "(< 1e-4)" : "(TOO LARGE)");
  else
    std::printf(" (in equilibrium, moved by %.0f times the shear spring stretch %.1e m "
                "while the contact took up the weight: %s)\n",
                std::abs(computed) / elastic, elastic,
                s.solver->unbalanced_ratio() < 1e-6 && std::abs(computed) < 1e-5 ? "stays put"
                                                                                     : "SLIDES");
}

int main()
{
  slide(40.0, 0.5, true);
  slide(15.0, 0.0, false);
}
