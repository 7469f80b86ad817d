// A 1 m cube dropped 0.05 m onto a fixed 1 m cube, undamped and without
// friction losses (it lands flat): it must bounce back to the height it
// fell from, again and again. At the top of each rebound the work of
// gravity is back to zero, so a divergence check that compares the
// kinetic energy with the net work of gravity would stop the run there;
// the check compares with the most the sources ever supplied. Twenty
// bounces at time step fractions 0.1 and 0.01 (eq. 87); the restitution
// over them, (h_20 / h_0)^(1/40) from the drop h_0 and the 20th rebound
// height, within 1e-3 of 1. Single bounces scatter more at fraction 0.1
// (a contact closes part way through a step, an error of order
// (omega dt)^2 of the impact's energy either way): standard error shows
// the largest.

#include <talus/solver/energy_account.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "../tests.h"
#include "scene_text.h"

namespace
{
std::string drop_scene(double fraction)
{
  return cube_above_floor(0.05) +
         // A flat landing is unstable to the least tilt: a cube that rocks
         // through the contact leaves it turning (the tilt grows about 200
         // times a bounce), and its rebound heights are no longer those of
         // its centre.
         "subsection Load 1\n"
         "  set Group = cube\n"
         "  set Hold rotation = true\n"
         "end\n"
         "subsection Joint properties\n"
         "  set Normal stiffness = 1e10\n"
         "  set Shear stiffness  = 1e10\n"
         "end\n"
         "subsection Solver\n"
         "  set Mode = dynamic\n"
         "  set Fixed groups = floor\n"
         "  set Time step fraction = " +
         std::to_string(fraction) +
         "\n"
         "end\n";
}
} // namespace

int main()
{
  for (double fraction : {0.1, 0.01})
  {
    TextScene s("bouncing_block.prm", drop_scene(fraction));
    talus::RigidSolver& solver = *s.solver;
    unsigned int cube = 0;
    for (unsigned int b = 0; b < s.model.n_blocks(); ++b)
      if (!solver.fixed[b])
        cube = b;
    const double start = s.model.centroid[cube][2];
    const double drop = start - 1.5; // the gap it falls through (m)
    std::vector<double> tops;        // rebound heights above the floor's contact
    double last_vz = 0.0;
    std::string stopped;
    try
    {
      while (tops.size() < 20 && solver.time() < 10.0)
      {
        solver.step();
        const double vz = solver.velocity[cube][2];
        // The top of a rebound: the vertical velocity turns from up to down.
        if (last_vz > 0.0 && vz <= 0.0)
          tops.push_back(s.model.centroid[cube][2] - 1.5);
        last_vz = vz;
      }
    }
    catch (const talus::DivergenceError& e)
    {
      stopped = e.what();
    }
    std::printf("fraction %g: ", fraction);
    if (!stopped.empty())
    {
      std::printf("WRONGLY stopped after %zu bounces at step %lu\n", tops.size(),
                  solver.steps_done());
      std::fprintf(stderr, "%s\n", stopped.c_str());
      continue;
    }
    // Each bounce's restitution from the heights before and after it.
    double worst = 0.0, before = drop;
    for (double h : tops)
    {
      worst = std::max(worst, std::abs(std::sqrt(h / before) - 1.0));
      before = h;
    }
    const double restitution = std::pow(tops.back() / drop, 0.5 / tops.size());
    std::fprintf(stderr,
                 "fraction %g: %zu bounces in %lu steps (dt %.3g s), heights %.6g .. %.6g m "
                 "of %.6g m, restitution %.6f, of single bounces at most %.2e from 1\n",
                 fraction, tops.size(), solver.steps_done(), solver.dt(), tops.front(), tops.back(),
                 drop, restitution, worst);
    std::printf("%zu bounces, restitution within 1e-3 of 1: %s\n", tops.size(),
                talus_test::verdict(tops.size() == 20 && std::abs(restitution - 1.0) <= 1e-3));
  }
}
