// Rayleigh damping of a rigid block (issue 23): a 1 m cube on a fixed
// 1 m cube, joined by a bonded joint (cohesion and tensile strength far
// above its load, so it neither opens nor slips) with kn = 1e10 Pa/m and
// ks = 4e9 Pa/m, no gravity, rotation held. An initial velocity of the cube
// across the joint (normal) or along it (shear) starts a free vibration
// of one degree of freedom at omega = sqrt(k A / m). Rayleigh damping
// with xi_min = 0.05 at the normal mode's frequency (alpha = xi_min
// omega_n, beta = xi_min / omega_n); the logarithmic decrement over ten
// half periods gives the damping ratio, which must be xi(omega) =
// (alpha / omega + beta omega) / 2 at the measured frequency within 2 %:
// mass-proportional only (2 alpha), stiffness-proportional only (2 beta),
// both; and both again in a run built static and switched to dynamics by
// set_dynamic, as a stage does. The decrement is taken on the swings from
// one extreme to the next, which do not depend on where the vibration is
// centred. The energy account closes: its error
// over its largest term at most 1e-6 (1e-9 across the joint; along it the
// undamped vibration alone leaves 7e-7, from the sub-contacts' points
// moving with the blocks). Before issue 23 talus had no damping in
// dynamics and refused the entries ('Rayleigh alpha' is not an entry of
// 'Solver').

#include <talus/solver/energy_account.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "../tests.h"
#include "block_on_joint.h"
#include "decay.h"

namespace
{
void run(const std::string& name, const char* mode, int component, double alpha, double beta)
{
  const char* velocity = component == 2 ? "0, 0, 1e-3" : "1e-3, 0, 0";
  TextScene s("rayleigh_block.prm", block_on_joint(mode, velocity, alpha, beta));
  talus::RigidSolver& solver = *s.solver;
  if (std::string(mode) == "static")
    solver.set_dynamic(true);
  unsigned int cube = 0;
  for (unsigned int b = 0; b < s.model.n_blocks(); ++b)
    if (!solver.fixed[b])
      cube = b;
  ExtremeTracker tracker;
  double worst_error = 0.0;
  while (tracker.value.size() < 13 && solver.steps_done() < 100000)
  {
    solver.step();
    tracker.add(solver.time(), solver.displacement[cube][component]);
    const talus::EnergyAccount e = solver.energy_account();
    worst_error = std::max(worst_error, std::abs(e.error()) / e.scale());
  }
  const Decay d = tracker.decay(1, 11);

  const double expected = 0.5 * (alpha / d.omega + beta * d.omega);
  const double k = component == 2 ? kn : ks;
  std::fprintf(stderr,
               "%s: %lu steps of %.4g s, omega %.6g rad/s (sqrt(k A / m) %.6g), xi %.6f, "
               "expected %.6f; energy error at most %.2e of the largest term\n",
               name.c_str(), solver.steps_done(), solver.dt(), d.omega, std::sqrt(k / rho), d.xi,
               expected, worst_error);
  std::printf("%s: damping ratio within 2 %% of (alpha / omega + beta omega) / 2: %s; energy "
              "account error within 1e-6 of its largest term: %s\n",
              name.c_str(), talus_test::verdict(std::abs(d.xi / expected - 1.0) <= 0.02),
              talus_test::verdict(worst_error <= 1e-6));
}
} // namespace

int main()
{
  const double xi_min = 0.05, omega_n = std::sqrt(kn / rho);
  const double alpha = xi_min * omega_n, beta = xi_min / omega_n;
  for (int component : {2, 0})
  {
    const std::string across = component == 2 ? "normal" : "shear";
    run(across + ", mass-proportional", "dynamic", component, 2.0 * alpha, 0.0);
    run(across + ", stiffness-proportional", "dynamic", component, 0.0, 2.0 * beta);
    run(across + ", both", "dynamic", component, alpha, beta);
    run(across + ", both, static switched to dynamic", "static", component, alpha, beta);
  }
}
