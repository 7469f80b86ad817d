// A block that moves more than the contact tolerance in one step can pass
// through another between two contact detections (eq. 1). A 1 m cube at
// 1e5 m/s moves 10 m per step of 1e-4 s: falling onto a fixed 1 m floor
// 1.5 m below it, the run must stop at once, naming the block, its speed
// and the step that would catch it (tolerance / speed). Flying away from
// the floor at the same speed, nothing is within its reach: the run goes
// on. Thrown down at 200 m/s (2 cm per step, more than the tolerance but
// less than half the cube) it is warned of (standard error) and lands,
// its contacts starting up to 2 cm deep. Dropped at 5 m/s (0.5 mm per
// step) it lands.

#include <talus/solver/energy_account.h>

#include <cstdio>
#include <string>

#include "../tests.h"
#include "scene_text.h"

namespace
{
std::string thrown(const std::string& velocity)
{
  return cube_above_floor(1.5) +
         "subsection Load 1\n"
         "  set Group = cube\n"
         "  set Initial velocity = " +
         velocity +
         "\n"
         "end\n"
         "subsection Contacts\n"
         "  set Tolerance = 0.01\n"
         "end\n"
         "subsection Solver\n"
         "  set Mode = dynamic\n"
         "  set Fixed groups = floor\n"
         "  set Time step = 1e-4\n"
         "end\n";
}

void run(const std::string& what, const std::string& velocity, unsigned long steps)
{
  TextScene s("fast_block.prm", thrown(velocity));
  talus::RigidSolver& solver = *s.solver;
  unsigned int cube = 0;
  for (unsigned int b = 0; b < s.model.n_blocks(); ++b)
    if (!solver.fixed[b])
      cube = b;
  try
  {
    while (solver.steps_done() < steps)
      solver.step();
    std::fprintf(stderr, "%s: %lu steps, the cube's centroid at z = %.4g m\n", what.c_str(),
                 solver.steps_done(), s.model.centroid[cube][2]);
    std::printf("%s: ran %lu steps, the cube above the floor: %s\n", what.c_str(),
                solver.steps_done(), s.model.centroid[cube][2] > 1.0 ? "yes" : "NO");
  }
  catch (const talus::DivergenceError& e)
  {
    std::printf("%s: stopped at step %lu: %s\n", what.c_str(), solver.steps_done(), e.what());
  }
}
} // namespace

int main()
{
  run("falling at 1e5 m/s", "0, 0, -1e5", 10);
  run("flying away at 1e5 m/s", "0, 0, 1e5", 10);
  run("thrown down at 200 m/s", "0, 0, -200", 300);
  run("dropped at 5 m/s", "0, 0, -5", 4000);
}
