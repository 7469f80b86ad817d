// Verification: cyclic direct shear of a continuously yielding joint
// (parameters/verification/continuously_yielding.prm). The plate is
// sheared forward 1.5 mm, back to its start, and forward 1.5 mm again.
// The plastic shear of the first cycle has lowered phi_m, so the second
// forward peak lies below the first; the whole path (the elastic unloading
// after each reversal, F = 1 again, and the yielding that follows) must
// follow the model's curve (cy_reference.h).

#include <talus/joint/continuously_yielding.h>

#include <cmath>
#include <cstdio>

#include "../tests.h"
#include "cy_reference.h"
#include "rigid_scene.h"

int main()
{
  RigidScene s("verification/continuously_yielding.prm");
  const talus::JointProperties& j = s.scene.solver.joint_materials.at(0);
  const double deg = M_PI / 180.0, area = 4.0, v = 0.001;
  const double sigma = s.solver->mass[1] * 9.81 / area;
  const talus::ContactSet& c = s.solver->contacts();
  const auto shear_stress = [&]()
  {
    double f = 0.0;
    for (unsigned int i = 0; i < c.n_subcontacts(); ++i)
      f -= c.sc_fs[3 * i];
    return f / area;
  };
  s.solver->velocity[1][0] = 0.0; // settle first; held: the solver keeps it
  s.run_until(0.2);
  const double u0 = s.solver->displacement[1][0];

  CyReference ref{sigma, j.shear_stiffness, j.friction_angle * deg, j.initial_friction_angle * deg,
                  j.roughness};
  double curve_error = 0.0;
  // Shears at velocity `velocity` until u passes `target`; returns the
  // largest shear stress along the way (and of the reference).
  const auto shear = [&](double velocity, double target, double& peak_ref)
  {
    s.solver->velocity[1][0] = velocity;
    double peak = -1e300;
    peak_ref = -1e300;
    for (;;)
    {
      s.solver->step();
      const double u = s.solver->displacement[1][0] - u0;
      ref.shear_to(u);
      const double tau = shear_stress();
      curve_error = std::max(curve_error, std::abs(tau - ref.tau));
      peak = std::max(peak, tau);
      peak_ref = std::max(peak_ref, ref.tau);
      if (velocity > 0.0 ? u >= target : u <= target)
        return peak;
    }
  };
  double first_ref = 0.0, back_ref = 0.0, second_ref = 0.0;
  const double first = shear(v, 0.0015, first_ref);
  shear(-v, 0.0, back_ref);
  const double back_stress = shear_stress(), back_stress_ref = ref.tau;
  const double second = shear(v, 0.0015, second_ref);
  std::fprintf(stderr,
               "peaks %.6g Pa then %.6g Pa (reference %.6g, %.6g); back at 0: %.6g Pa (%.6g)\n",
               first, second, first_ref, second_ref, back_stress, back_stress_ref);
  talus_test::check_error("first forward peak (Pa)", first, first_ref, 1e-3);
  talus_test::check_error("second forward peak (Pa)", second, second_ref, 1e-3);
  talus_test::check_error("shear stress back at the start (Pa)", back_stress, back_stress_ref,
                          1e-3);
  std::printf("largest error of tau(u) over the cycles, relative to the first peak: %.1e %s\n",
              curve_error / first_ref, talus_test::verdict(curve_error / first_ref <= 1e-3));
  std::printf("second peak below the first by %.0f%% (reference %.0f%%): %s\n",
              100.0 * (1.0 - second / first), 100.0 * (1.0 - second_ref / first_ref),
              talus_test::verdict(second < 0.97 * first));
}
