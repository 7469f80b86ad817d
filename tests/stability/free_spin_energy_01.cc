// A free 1 x 2 x 3 m block (no gravity, no contacts) spinning with the
// principal inertia (Rotation = principal, eqs. 45 and 49). The principal
// moments are m (b^2 + c^2) / 12: 17225, 13250 and 6625 kg m^2 for m =
// 15900 kg.
// 1. Spinning at (10, 0.5, 0.5) rad/s about its axes, it starts with
//    1/2 w . I w = 863,734.4 J, which row 0 of the energy account holds.
// 2. Kinetic energy and angular momentum of a free body are invariants of
//    Euler's equations; at omega dt = 1e-2 the rotation scheme keeps both
//    to round-off (drift below 1e-8 per 1000 steps).
// 3. Spinning about the intermediate axis (y) with a small disturbance, it
//    tumbles: the body's y angular momentum reverses, the energy and the
//    angular momentum kept all along.

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "../tests.h"
#include "scene_text.h"

namespace
{
std::string free_block(const std::string& spin)
{
  return "subsection Model\n"
         "  set Brick min = 0, 0, 0\n"
         "  set Brick max = 1, 2, 3\n"
         "  set Default group = block\n"
         "end\n"
         "subsection Material\n"
         "  set Density = 2650\n"
         "end\n"
         "subsection Joint properties\n"
         "  set Normal stiffness = 1e8\n"
         "  set Shear stiffness  = 1e8\n"
         "end\n"
         "subsection Load 1\n"
         "  set Group = block\n"
         "  set Initial spin = " +
         spin +
         "\n"
         "end\n"
         "subsection Solver\n"
         "  set Mode = dynamic\n"
         "  set Rotation = principal\n"
         "  set Time step = 1e-3\n" // omega dt = 1e-2
         "  set Gravity = 0, 0, 0\n"
         "end\n";
}

/// Runs `steps` steps; returns the largest relative change of the kinetic
/// energy and of the angular momentum from their values at the start, and
/// whether the body y component of the angular momentum reversed.
struct Drift
{
  double energy = 0.0, momentum = 0.0;
  bool reversed = false;
};
Drift run(TextScene& s, unsigned long steps)
{
  talus::RigidSolver& solver = *s.solver;
  const double e0 = solver.kinetic_energy();
  const talus::Vec3 l0 = solver.angular_momentum(0);
  const double sign0 = (solver.axes[0].transpose() * l0)[1];
  Drift d;
  for (unsigned long n = 0; n < steps; ++n)
  {
    solver.step();
    d.energy = std::max(d.energy, std::abs(solver.kinetic_energy() - e0) / e0);
    const talus::Vec3 l = solver.angular_momentum(0);
    d.momentum = std::max(d.momentum, (l - l0).norm() / l0.norm());
    d.reversed = d.reversed || (solver.axes[0].transpose() * l)[1] * sign0 < 0.0;
  }
  return d;
}
} // namespace

int main()
{
  const double m = 2650.0 * 6.0;
  const Eigen::Vector3d I(m * 13.0 / 12.0, m * 10.0 / 12.0, m * 5.0 / 12.0);
  {
    TextScene s("free_spin.prm", free_block("10, 0.5, 0.5"));
    const double exact = 0.5 * (I[0] * 100.0 + I[1] * 0.25 + I[2] * 0.25);
    const talus::EnergyAccount e = s.solver->energy_account();
    std::printf("energy at the start: %.7g J (exact %.7g J): %s\n", e.initial_stored, exact,
                talus_test::verdict(talus_test::relative_error(e.initial_stored, exact) < 1e-12));
    std::printf("kinetic term at the start: %.7g J: %s\n", e.kinetic,
                talus_test::verdict(talus_test::relative_error(e.kinetic, exact) < 1e-12));
    std::printf("balance error at the start: %s\n",
                talus_test::verdict(std::abs(e.error()) <= 1e-12 * exact));
    const unsigned long steps = 20000;
    const Drift d = run(s, steps);
    const talus::EnergyAccount end = s.solver->energy_account();
    std::fprintf(stderr,
                 "spin about the major axis, %lu steps: kinetic energy drift %.2e, angular "
                 "momentum drift %.2e (%.2e and %.2e per 1000 steps), balance error %.2e J\n",
                 steps, d.energy, d.momentum, d.energy * 1000 / steps, d.momentum * 1000 / steps,
                 end.error());
    std::printf("major axis: kinetic energy drift below 1e-8 per 1000 steps: %s\n",
                talus_test::verdict(d.energy * 1000 / steps < 1e-8));
    std::printf("major axis: angular momentum drift below 1e-8 per 1000 steps: %s\n",
                talus_test::verdict(d.momentum * 1000 / steps < 1e-8));
    std::printf("major axis: energy balance error below 1e-8 of the energy: %s\n",
                talus_test::verdict(std::abs(end.error()) < 1e-8 * exact));
  }
  {
    TextScene s("free_spin.prm", free_block("0.01, 10, 0.01"));
    const unsigned long steps = 20000;
    const Drift d = run(s, steps);
    std::fprintf(stderr,
                 "spin about the intermediate axis, %lu steps: reversed %d, kinetic energy drift "
                 "%.2e, angular momentum drift %.2e\n",
                 steps, d.reversed, d.energy, d.momentum);
    std::printf("intermediate axis: tumbles (body y momentum reverses): %s\n",
                talus_test::verdict(d.reversed));
    std::printf("intermediate axis: kinetic energy drift below 1e-8 per 1000 steps: %s\n",
                talus_test::verdict(d.energy * 1000 / steps < 1e-8));
    std::printf("intermediate axis: angular momentum drift below 1e-8 per 1000 steps: %s\n",
                talus_test::verdict(d.momentum * 1000 / steps < 1e-8));
  }
}
