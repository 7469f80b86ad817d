// A block that starts with a velocity along a joint (issue 23): the
// 1 m cube of block_on_joint.h (2650 kg, rotation held, no gravity) on a
// fixed cube, 'Initial velocity' v0 = 1e-3 m/s along x, 'Mode = dynamic',
// no damping. The joint springs must follow the relative displacement the
// blocks have made, nothing else:
// - bonded joint (ks A = 4e9 N/m, strength far above the load): a free
//   shear vibration. The shear force on the cube at each step must be
//   -ks A x with x the cube's displacement when the force is taken (zero
//   at the first step, when nothing has moved), within 1e-4 of the
//   amplitude ks A v0 / omega; and kinetic plus joint elastic energy must
//   stay 1/2 m v0^2 (nothing else works on it), within 1e-5, over two
//   periods;
// - frictionless joint (no cohesion, no tension, phi = 0): the cube slides
//   at v0 for 100 steps, then at -v0 (its velocity set between two steps,
//   as a stage or a test may set it), and the sub-contacts' shear
//   displacement must be its displacement x within 1e-6 of v0 dt.
// Before: the first step took v0 dt as a shear increment although nothing
// had moved: a shear force ks A v0 dt at the first step, every later force
// off by that (1.3e-1 of the amplitude, omega dt), an energy error
// 1/2 ks A (v0 dt)^2 (1.6e-2 of 1/2 m v0^2), and a shear displacement one
// step ahead of the block (off by v0 dt); and the step after the reversal
// took -v0 dt for the +v0 dt the cube had last moved (2 v0 dt off, once
// the first step was mended).

#include <talus/solver/energy_account.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "../tests.h"
#include "block_on_joint.h"

namespace
{
constexpr double mass = rho * 1.0; // the 1 m cube, kg

/// The scene with the joint's strength entries replaced by `strength`.
std::string scene(const std::string& strength)
{
  std::string text = block_on_joint("dynamic", "1e-3, 0, 0", 0.0, 0.0);
  const std::string bonded =
      "  set Cohesion = 1e9\n  set Tensile strength = 1e9\n  set Friction angle = 30\n";
  text.replace(text.find(bonded), bonded.size(), strength);
  return text;
}

/// The cube's block index, and the x components (on the cube) of the
/// shear force and mean shear displacement of its sub-contacts.
struct CubeContact
{
  double force = 0.0, displacement = 0.0;
};

CubeContact cube_contact(const talus::RigidSolver& solver, unsigned int cube)
{
  const talus::ContactSet& cs = solver.contacts();
  CubeContact r;
  unsigned int n = 0;
  for (unsigned int i = 0; i < cs.n_subcontacts(); ++i)
  {
    const unsigned int c = cs.sc_contact[i];
    // The force and displacement are those of B relative to A.
    const double sign = cs.block_b[c] == cube ? 1.0 : -1.0;
    r.force += sign * cs.sc_fs[3 * i];
    r.displacement += sign * cs.sc_us[3 * i];
    ++n;
  }
  if (n > 0)
    r.displacement /= n;
  return r;
}

unsigned int free_block(const TextScene& s)
{
  for (unsigned int b = 0; b < s.model.n_blocks(); ++b)
    if (!s.solver->fixed[b])
      return b;
  return 0;
}

void bonded()
{
  TextScene s("initial_velocity_shear.prm",
              scene("  set Cohesion = 1e9\n  set Tensile strength = 1e9\n  set Friction angle = "
                    "30\n"));
  talus::RigidSolver& solver = *s.solver;
  const unsigned int cube = free_block(s);
  const double K = ks * 1.0, omega = std::sqrt(K / mass), amplitude = K * v0 / omega;
  const double energy = 0.5 * mass * v0 * v0;
  double first = 0.0, worst_force = 0.0, worst_energy = 0.0;
  while (solver.time() < 2.0 * 2.0 * M_PI / omega)
  {
    const double x = solver.displacement[cube].x();
    solver.step();
    const double f = cube_contact(solver, cube).force;
    if (solver.steps_done() == 1)
      first = f;
    worst_force = std::max(worst_force, std::abs(f + K * x) / amplitude);
    const talus::EnergyAccount e = solver.energy_account();
    worst_energy = std::max(worst_energy, std::abs(e.stored() / energy - 1.0));
  }
  std::fprintf(stderr,
               "bonded: %lu steps of %.4g s (omega dt %.4f); shear force at the first step %.4g "
               "N (ks A v0 dt %.4g N); force against -ks A x off by at most %.2e of ks A v0 / "
               "omega; kinetic and joint energy off 1/2 m v0^2 by at most %.2e\n",
               solver.steps_done(), solver.dt(), omega * solver.dt(), first, K * v0 * solver.dt(),
               worst_force, worst_energy);
  std::printf("bonded joint: shear force zero at the first step: %s; shear force -ks A x within "
              "1e-4 of its amplitude: %s; kinetic and joint elastic energy 1/2 m v0^2 within "
              "1e-5: %s\n",
              talus_test::verdict(std::abs(first) <= 1e-9 * K * v0 * solver.dt()),
              talus_test::verdict(worst_force <= 1e-4), talus_test::verdict(worst_energy <= 1e-5));
}

void frictionless()
{
  TextScene s("initial_velocity_shear.prm",
              scene("  set Cohesion = 0\n  set Tensile strength = 0\n  set Friction angle = 0\n"));
  talus::RigidSolver& solver = *s.solver;
  const unsigned int cube = free_block(s);
  double worst = 0.0, worst_velocity = 0.0;
  while (solver.steps_done() < 200)
  {
    if (solver.steps_done() == 100)
      solver.velocity[cube].x() = -v0;
    const double x = solver.displacement[cube].x();
    solver.step();
    worst =
        std::max(worst, std::abs(cube_contact(solver, cube).displacement - x) / (v0 * solver.dt()));
    worst_velocity =
        std::max(worst_velocity, std::abs(std::abs(solver.velocity[cube].x()) / v0 - 1.0));
  }
  std::fprintf(stderr,
               "frictionless: %lu steps of %.4g s, %u sub-contacts; shear displacement off the "
               "cube's by at most %.2e of v0 dt; velocity off v0 by at most %.2e\n",
               solver.steps_done(), solver.dt(), solver.contacts().n_subcontacts(), worst,
               worst_velocity);
  std::printf("frictionless joint, v0 then -v0: shear displacement that of the cube within 1e-6 "
              "of v0 dt: %s; speed v0 within 1e-12: %s\n",
              talus_test::verdict(worst <= 1e-6), talus_test::verdict(worst_velocity <= 1e-12));
}
} // namespace

int main()
{
  bonded();
  frictionless();
}
