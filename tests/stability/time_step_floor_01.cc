// A 1 m cube resting on a fixed n x n x 1 m floor block. Eq. 87 bounds
// the stiffness of a contact by the smaller of its two blocks' faces, and
// a fixed block has no inertia to keep stable: the stable step is the
// cube's, frac 2 sqrt(m / (k A)) with m = 2650 kg, k = 1e10 Pa/m, A = 1 m^2
// (1.0296e-4 s at frac = 0.1), whatever the size of the floor.
// A given 'Time step' of 5e-4 s (half the limit of eq. 87 without its
// fraction) runs: the cube stays at rest on the largest floor. One of
// 1.5e-3 s is refused before the run.

#include <talus/base/exceptions.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "../tests.h"
#include "scene_text.h"

namespace
{
std::string floor_scene(int n, double time_step)
{
  const std::string N = std::to_string(n), N1 = std::to_string(n + 1);
  return "subsection Model\n"
         "  set Brick min = 0, 0, 0\n"
         "  set Brick max = " +
         N + ", " + N +
         ", 2\n"
         "end\n"
         "subsection Material\n"
         "  set Density = 2650\n"
         "end\n"
         "subsection Joint 1\n"
         "  set Dip = 0\n"
         "  set Origin = 0, 0, 1\n"
         "end\n"
         // All of the upper layer but the cube over [0, 1] x [0, 1].
         "subsection Excavation 1\n"
         "  set Corner min = 1, -1, 1\n"
         "  set Corner max = " +
         N1 + ", " + N1 +
         ", 3\n"
         "end\n"
         "subsection Excavation 2\n"
         "  set Corner min = -1, 1, 1\n"
         "  set Corner max = 1, " +
         N1 +
         ", 3\n"
         "end\n"
         "subsection Group 1\n"
         "  set Name = floor\n"
         "  set Corner min = -1, -1, 0\n"
         "  set Corner max = " +
         N1 + ", " + N1 +
         ", 1\n"
         "end\n"
         "subsection Joint properties\n"
         "  set Normal stiffness = 1e10\n"
         "  set Shear stiffness  = 1e10\n"
         "end\n"
         "subsection Solver\n"
         "  set Mode = dynamic\n"
         "  set Fixed groups = floor\n"
         "  set Time step = " +
         std::to_string(time_step) +
         "\n"
         "end\n";
}
} // namespace

int main()
{
  const double exact = 0.1 * 2.0 * std::sqrt(2650.0 / 1e10);
  for (int n : {1, 5, 20})
  {
    TextScene s("time_step_floor.prm", floor_scene(n, 0.0));
    std::fprintf(stderr, "floor %d x %d: %u blocks, step %.6g s\n", n, n, s.model.n_blocks(),
                 s.solver->dt());
    std::printf("floor %d x %d: automatic time step %.5g s (exact %.5g s): %s\n", n, n,
                s.solver->dt(), exact,
                talus_test::verdict(talus_test::relative_error(s.solver->dt(), exact) < 1e-12));
  }
  try
  {
    TextScene s("time_step_floor.prm", floor_scene(20, 5e-4));
    talus::RigidSolver& solver = *s.solver;
    unsigned int cube = 0;
    for (unsigned int b = 0; b < s.model.n_blocks(); ++b)
      if (!solver.fixed[b])
        cube = b;
    for (int k = 0; k < 2000; ++k)
      solver.step();
    const talus::EnergyAccount e = solver.energy_account();
    // Resting under its weight the cube sinks m g / k (2.6e-6 m) and
    // oscillates about that by as much; anything unstable grows past it.
    const double sag = 2650.0 * 9.81 / 1e10;
    std::fprintf(stderr,
                 "given step 5e-4 s on the 20 x 20 floor: displacement %.3g m, "
                 "kinetic energy %.3g J, balance error %.2g J\n",
                 solver.displacement[cube].norm(), e.kinetic, e.error());
    std::printf("floor 20 x 20, given step 5e-4 s: runs 2000 steps, the cube at rest: %s\n",
                talus_test::verdict(solver.displacement[cube].norm() < 3.0 * sag));
  }
  catch (const std::exception& e)
  {
    std::printf("floor 20 x 20, given step 5e-4 s: WRONGLY refused: %s\n", e.what());
  }
  try
  {
    TextScene s("time_step_floor.prm", floor_scene(20, 1.5e-3));
    std::printf("floor 20 x 20, given step 1.5e-3 s: NOT refused\n");
  }
  catch (const talus::InputError& e)
  {
    std::printf("floor 20 x 20, given step 1.5e-3 s: refused: %s\n", e.what());
  }
}
