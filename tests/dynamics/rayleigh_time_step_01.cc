// The time step with Rayleigh's stiffness-proportional term (issue 23).
// With the damping force taken from the velocity of the last half step,
// the central difference scheme on one degree of freedom of angular
// frequency omega is stable for omega dt <= 2 (sqrt(1 + xi^2) - xi), xi =
// beta omega / 2. The block of rayleigh_block_01 (omega = sqrt(kn A / m),
// A its largest face) with beta = 1 / omega (xi = 0.5 at omega): the
// automatic step is eq. 87's times that factor (0.618); and with the step
// given (the check against eq. 87 switched off, 'Time step fraction' 0)
// the vibration across the joint decays at 0.98 times the limit and grows
// without bound at 1.02 times it. Before issue 23 talus refused 'Rayleigh
// beta'.

#include <talus/solver/energy_account.h>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include "../tests.h"
#include "block_on_joint.h"

namespace
{
/// The largest swing of the block across the joint in the last tenth of
/// `steps` steps over that in the first tenth, or infinity if it diverged.
double growth(double beta, double dt, unsigned long steps)
{
  std::ostringstream given;
  given.precision(17);
  given << "  set Time step = " << dt << "\n";
  const std::string file = "rayleigh_time_step.prm";
  std::FILE* f = std::fopen(file.c_str(), "w");
  std::fputs(block_on_joint("dynamic", "0, 0, 1e-3", 0.0, beta, given.str()).c_str(), f);
  std::fclose(f);
  talus::Scene scene = talus::read_scene(file, false);
  talus::BuildReport report;
  talus::BlockModel model = talus::build_blocks(scene, report);
  talus::resolve_group_names(scene, model);
  scene.solver.time_step_fraction = 0.0; // no check against eq. 87
  talus::RigidSolver solver(model, scene.density, scene.solver);
  double first = 0.0, last = 0.0;
  try
  {
    for (unsigned long n = 0; n < steps; ++n)
    {
      solver.step();
      const double u = std::abs(solver.displacement[1][2]);
      if (n < steps / 10)
        first = std::max(first, u);
      if (n >= steps - steps / 10)
        last = std::max(last, u);
    }
  }
  catch (const talus::DivergenceError&)
  {
    return INFINITY;
  }
  return last / first;
}
} // namespace

int main()
{
  const double omega = std::sqrt(kn / rho), beta = 1.0 / omega, xi = 0.5 * beta * omega;
  const double factor = std::sqrt(1.0 + xi * xi) - xi;
  {
    TextScene s("rayleigh_time_step.prm", block_on_joint("dynamic", "0, 0, 1e-3", 0.0, beta));
    const double dt = s.solver->dt(), without = s.solver->time_step_without_stiffness_damping();
    std::fprintf(stderr, "time step %.6g s, %.6g s without the stiffness term: %.9f of it\n", dt,
                 without, dt / without);
    talus_test::check_within("time step over the step without the stiffness term", dt / without,
                             factor, 1e-12);
    talus_test::check_within("that step over eq. 87", without, 0.1 * 2.0 / omega, 1e-12);
  }
  const double limit = 2.0 / omega * factor;
  const double below = growth(beta, 0.98 * limit, 4000), above = growth(beta, 1.02 * limit, 4000);
  std::fprintf(stderr, "swing growth over 4000 steps: %.3g at 0.98 of the limit, %.3g at 1.02\n",
               below, above);
  std::printf("at 0.98 of the limit the vibration decays: %s\n", talus_test::verdict(below < 1e-3));
  std::printf("at 1.02 of the limit it grows: %s\n", talus_test::verdict(above > 1e3));
}
