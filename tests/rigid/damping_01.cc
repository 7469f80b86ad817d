// The three forms of static damping reach the same equilibrium: a column of
// five free cubes on a fixed one (parameters/verification/stack_of_blocks.prm)
// settled with local (eqs. 78-79), combined (eq. 83) and adaptive global
// damping (eq. 77). Each must converge to the unbalanced-force ratio 1e-7
// with the floor reaction equal to the weight and the bottom joint closed
// by sigma / kn. Steps taken go to standard error (they are not a result).

#include <cmath>
#include <cstdio>
#include <iostream>

#include "../tests.h"
#include "rigid_scene.h"

int main()
{
  for (const talus::Damping mode :
       {talus::Damping::local, talus::Damping::combined, talus::Damping::adaptive_global})
  {
    const char* name = mode == talus::Damping::local      ? "local"
                       : mode == talus::Damping::combined ? "combined"
                                                          : "adaptive global";
    RigidScene s("verification/stack_of_blocks.prm",
                 [&](talus::Scene& scene) { scene.solver.damping = mode; });
    const unsigned long steps = s.run_to_ratio(1e-7, 100000);
    std::cerr << name << ": " << steps << " steps to ratio 1e-7\n";
    std::printf("%s damping: %s\n", name,
                s.solver->unbalanced_ratio() < 1e-7 ? "reached ratio 1e-7" : "NOT converged");
    const talus::ContactSet& c = s.solver->contacts();
    const double weight = 5 * s.scene.density * 9.81; // N, five 1 m^3 cubes
    double fn = 0.0, closure = 0.0, area = 0.0;
    for (unsigned int i = 0; i < c.n_subcontacts(); ++i)
      if (std::abs(c.sc_position[i].z() - 1.0) < 0.5)
      {
        fn += c.sc_fn[i];
        closure -= c.sc_un[i] * c.sc_area[i];
        area += c.sc_area[i];
      }
    std::printf("  ");
    talus_test::check_within("floor reaction (N)", fn, weight, 1e-6);
    std::printf("  ");
    talus_test::check_within("bottom joint closure (m)", closure / area,
                             weight / area / s.scene.solver.joint.normal_stiffness, 1e-6);
  }
}
