// Input motions in time (issue 23): a rigid 1 m cube resting on a 1 m base
// block across a horizontal Coulomb joint (friction angle 10 degrees, no
// cohesion, no tension) is shaken by the base, whose x velocity is
// prescribed by a 'Load N' with a time function: a half-sine acceleration
// pulse (amplitude 3 m/s^2, 0.3 s; 'Input = acceleration', so the base
// velocity is its integral) and one cycle of a harmonic acceleration (1.5
// Hz, 5 m/s^2), each from 0.5 s on, after a static settling. The cube
// slides on the base while the base's acceleration exceeds g tan(phi)
// (rigid-plastic, Newmark 1965): its largest slip (base displacement less
// the cube's; the harmonic's slips back part of the way, its net slip is
// a difference, not judged) must match an independent fine integration of
// the sliding block's relative motion within 3 %, and the base must have moved by the
// closed-form integral of its velocity within 1e-3. The work of the moving
// base stays in the energy account's 'work of boundaries': the account's
// error over the dynamic part within 1e-4 of its largest term (1e-5). Before
// issue 23 talus refused 'Time function' ('Time function' is not an entry
// of 'Load 1').

#include <talus/solver/energy_account.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include "../stability/scene_text.h"
#include "../tests.h"

namespace
{
constexpr double pi = 3.14159265358979323846, g = 9.81, start = 0.5;

/// The base on a 1 m cube (group base), the cube (group cube) on it.
std::string scene(const std::string& motion)
{
  return "subsection Model\n  set Brick min = 0, 0, 0\n  set Brick max = 1, 1, 2\nend\n"
         "subsection Material\n  set Density = 2650\nend\n"
         "subsection Joint 1\n  set Dip = 0\n  set Origin = 0, 0, 1\nend\n"
         "subsection Group 1\n  set Name = base\n  set Corner min = 0, 0, 0\n"
         "  set Corner max = 1, 1, 1\nend\n"
         "subsection Group 2\n  set Name = cube\n  set Corner min = 0, 0, 1\n"
         "  set Corner max = 1, 1, 2\nend\n"
         "subsection Load 1\n  set Group = cube\n  set Hold rotation = true\nend\n"
         "subsection Load 2\n  set Group = base\n  set Prescribe velocity = true\n"
         "  set Velocity = 1, 0, 0\n  set Hold rotation = true\n"
         "  set Input = acceleration\n" +
         motion +
         "end\n"
         "subsection Joint properties\n  set Normal stiffness = 1e10\n"
         "  set Shear stiffness = 4e9\n  set Friction angle = 10\n  set Cohesion = 0\n"
         "  set Tensile strength = 0\nend\n"
         "subsection Solver\n  set Mode = static\n  set Gravity = 0, 0, -9.81\nend\n";
}

/// The largest rigid-plastic slip of a block on a base of acceleration `a` (m/s^2,
/// zero velocity at `start`) up to `t_end`, by fine steps: the block
/// follows the base while |a| <= mu g, else accelerates at mu g towards
/// the base's velocity until it catches it up.
double newmark_slip(const std::function<double(double)>& a, double mu_g, double t_end)
{
  const double dt = 1e-6;
  double vb = 0.0, vk = 0.0, slip = 0.0, largest = 0.0;
  for (double t = start; t < t_end; t += dt)
  {
    const double ab = a(t + 0.5 * dt);
    const double relative = vb - vk;
    const double ak = relative != 0.0 ? std::copysign(mu_g, relative) : std::clamp(ab, -mu_g, mu_g);
    double vb_next = vb + ab * dt, vk_next = vk + ak * dt;
    if (relative * (vb_next - vk_next) < 0.0)
      vk_next = vb_next; // caught up within the step
    slip += 0.5 * (relative + vb_next - vk_next) * dt;
    vb = vb_next;
    vk = vk_next;
    largest = std::max(largest, slip);
  }
  return largest;
}

void run(const std::string& name, const std::string& motion,
         const std::function<double(double)>& acceleration,
         const std::function<double(double)>& base_displacement, double t_end)
{
  TextScene s("newmark_sliding_block.prm", scene(motion));
  talus::RigidSolver& solver = *s.solver;
  unsigned int cube = 0, base = 0;
  for (unsigned int b = 0; b < s.model.n_blocks(); ++b)
    (s.model.centroid[b].z() > 1.0 ? cube : base) = b;
  // Static settling of the cube onto the joint, then dynamics.
  while (solver.time() < 0.8 * start)
    solver.step();
  solver.set_dynamic(true);
  const double cube_x0 = solver.displacement[cube].x(), base_x0 = solver.displacement[base].x();
  double first_error = 0.0, worst_error = 0.0, slip = 0.0;
  bool first = true;
  while (solver.time() < t_end)
  {
    solver.step();
    const talus::EnergyAccount e = solver.energy_account();
    if (first)
      first_error = e.error();
    first = false;
    worst_error = std::max(worst_error, std::abs(e.error() - first_error) / e.scale());
    slip = std::max(slip, solver.displacement[base].x() - base_x0 -
                              (solver.displacement[cube].x() - cube_x0));
  }
  const double mu_g = g * std::tan(10.0 * pi / 180.0);
  const double base_moved = solver.displacement[base].x() - base_x0;
  const double expected = newmark_slip(acceleration, mu_g, solver.time());
  const double base_expected = base_displacement(solver.time());
  std::fprintf(stderr,
               "%s: %lu steps of %.3g s to %.6g s; slip %.6g m, Newmark %.6g m; base moved %.6g "
               "m, closed form %.6g m; energy error at most %.2e of the largest term\n",
               name.c_str(), solver.steps_done(), solver.dt(), solver.time(), slip, expected,
               base_moved, base_expected, worst_error);
  std::printf(
      "%s: largest slip within 3 %% of Newmark's rigid-plastic block: %s; base displacement "
      "within 1e-3 of the integral of its velocity: %s; energy account error within "
      "1e-4 of its largest term: %s\n",
      name.c_str(), talus_test::verdict(std::abs(slip / expected - 1.0) <= 0.03),
      talus_test::verdict(std::abs(base_moved / base_expected - 1.0) <= 1e-3),
      talus_test::verdict(worst_error <= 1e-4));
}
} // namespace

int main()
{
  {
    // Half sine: v = A T / pi (1 - cos(pi tau / T)), its integral
    // A T / pi (tau - T / pi sin(pi tau / T)), then v = 2 A T / pi.
    const double A = 3.0, T = 0.3;
    run(
        "half-sine pulse",
        "  set Time function = pulse\n  set Amplitude = 3\n  set Pulse duration = 0.3\n"
        "  set Start time = 0.5\n",
        [=](double t)
        { return t > start && t < start + T ? A * std::sin(pi * (t - start) / T) : 0.0; },
        [=](double t)
        {
          const double tau = t - start;
          return tau < T ? A * T / pi * (tau - T / pi * std::sin(pi * tau / T))
                         : A * T / pi * (T + 2.0 * (tau - T));
        },
        1.4);
  }
  {
    // One cycle: v = A / omega (1 - cos(omega tau)), its integral
    // A / omega (tau - sin(omega tau) / omega), then still.
    const double A = 5.0, f = 2.0, omega = 2.0 * pi * f, T = 1.0 / f;
    run(
        "harmonic cycle",
        "  set Time function = harmonic\n  set Amplitude = 5\n  set Frequency = 2\n"
        "  set Start time = 0.5\n  set End time of motion = 1\n",
        [=](double t)
        { return t > start && t < start + T ? A * std::sin(omega * (t - start)) : 0.0; },
        [=](double t)
        {
          const double tau = std::min(t - start, T);
          return A / omega * (tau - std::sin(omega * tau) / omega);
        },
        1.5);
  }
}
