// Verification: direct shear of a continuously yielding joint at constant
// normal stress (parameters/verification/continuously_yielding.prm). The
// plate settles under its weight, then is sheared 3 mm at 1 mm/s. The shear
// stress against the shear displacement must follow the model's curve
// (cy_reference.h, stepped a thousand times finer): it rises with a
// tangent stiffness F ks that falls as tau nears tau_m, peaks, and softens
// to the residual strength sigma_n tan(phi) as phi_m decays with the
// plastic shear (Cundall and Lemos 1990).

#include <cmath>
#include <cstdio>

#include <talus/joint/continuously_yielding.h>

#include "../tests.h"
#include "cy_reference.h"
#include "rigid_scene.h"

int main()
{
  RigidScene s("verification/continuously_yielding.prm");
  const talus::JointProperties& j = s.scene.solver.joint_materials.at(0);
  const double deg = M_PI / 180.0, area = 4.0;
  const double sigma = s.solver->mass[1] * 9.81 / area;
  const talus::ContactSet& c = s.solver->contacts();
  const auto shear_stress = [&]()
  {
    double f = 0.0;
    for (unsigned int i = 0; i < c.n_subcontacts(); ++i)
      f -= c.sc_fs[3 * i];
    return f / area;
  };
  // Settle first (no shear), so that the normal stress is the weight's.
  s.solver->velocity[1][0] = 0.0; // held: the solver keeps it
  s.run_until(0.2);
  const double u0 = s.solver->displacement[1][0];
  s.solver->velocity[1][0] = 0.001;

  CyReference ref{sigma, j.shear_stiffness, j.friction_angle * deg, j.initial_friction_angle * deg,
                  j.roughness};
  double curve_error = 0.0, peak = 0.0, peak_ref = 0.0, peak_at = 0.0, peak_ref_at = 0.0;
  double u = 0.0;
  while (u < 0.003)
  {
    s.solver->step();
    u = s.solver->displacement[1][0] - u0;
    ref.shear_to(u);
    const double tau = shear_stress();
    curve_error = std::max(curve_error, std::abs(tau - ref.tau));
    if (tau > peak)
      peak = tau, peak_at = u;
    if (ref.tau > peak_ref)
      peak_ref = ref.tau, peak_ref_at = u;
  }
  std::fprintf(stderr, "sigma_n %.6g Pa, peak %.6g Pa at %.4g mm (reference %.6g Pa at %.4g mm)\n",
               sigma, peak, 1e3 * peak_at, peak_ref, 1e3 * peak_ref_at);
  talus_test::check_error("peak shear stress (Pa)", peak, peak_ref, 1e-3);
  std::printf("shear displacement at the peak within 2%% of the reference's: %s\n",
              talus_test::verdict(talus_test::relative_error(peak_at, peak_ref_at) <= 2e-2));
  std::printf("largest error of tau(u) over 3 mm, relative to the peak: %.1e %s\n",
              curve_error / peak_ref, talus_test::verdict(curve_error / peak_ref <= 1e-3));
  // The peak lies well above the residual strength and below phi_i's.
  std::printf("peak between sigma_n tan(phi) and sigma_n tan(phi_i): %s\n",
              talus_test::verdict(peak > 1.1 * sigma * std::tan(j.friction_angle * deg) &&
                                  peak < sigma * std::tan(j.initial_friction_angle * deg)));
  // Residual: after 3 mm (6 R of plastic shear) the stress sits on the
  // bound sigma_n tan(phi_m(u_p)), within exp(-6) of sigma_n tan(phi).
  double u_p = 0.0;
  for (unsigned int i = 0; i < c.n_subcontacts(); ++i)
    u_p += c.sc_yield[talus::yield_state_size * i + talus::plastic_shear_displacement];
  u_p /= c.n_subcontacts();
  const double phi_m = j.friction_angle * deg + (j.initial_friction_angle - j.friction_angle) *
                                                    deg * std::exp(-u_p / j.roughness);
  talus_test::check_error("plastic shear displacement after 3 mm (m)", u_p, ref.u_p, 1e-3);
  std::printf("residual shear stress on the bound sigma_n tan(phi_m(u_p)) within 1e-9: %s\n",
              talus_test::verdict(
                  talus_test::relative_error(shear_stress(), sigma * std::tan(phi_m)) <= 1e-9));
  talus_test::check_error("residual shear stress against sigma_n tan(phi) (Pa)", shear_stress(),
                          sigma * std::tan(j.friction_angle * deg), 1e-2);
}
