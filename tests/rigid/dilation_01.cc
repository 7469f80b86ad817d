// Verification: a dilatant Coulomb joint sheared forward past its limiting
// displacement and back again (parameters/verification/dilation.prm).
// Under a constant normal load the plate rises by tan(psi) times the shear
// displacement beyond the elastic part u_e = N tan(phi) / (ks A) (eq. 42),
// up to the limit U_lim; shearing back lowers it again, since dilation
// depends on the direction of shearing. The shear force stays N tan(phi).

#include <cmath>
#include <cstdio>

#include "../tests.h"
#include "rigid_scene.h"

int main()
{
  RigidScene s("verification/dilation.prm");
  const talus::JointProperties& j = s.scene.solver.joint;
  const double deg = M_PI / 180.0, area = 4.0;
  const double n_force = s.solver->mass[1] * 9.81;
  const double tan_psi = std::tan(j.dilation_angle * deg),
               tan_phi = std::tan(j.friction_angle * deg);
  const double u_e = n_force * tan_phi / (j.shear_stiffness * area);
  const double lim = j.dilation_limit;
  const talus::ContactSet& c = s.solver->contacts();
  const auto shear_force = [&]()
  {
    double f = 0.0;
    for (unsigned int i = 0; i < c.n_subcontacts(); ++i)
      f += c.sc_fs[3 * i];
    return std::abs(f);
  };
  // The plate first settles by the elastic closure N / (kn A); dilation is
  // measured from there.
  const double closure = n_force / (j.normal_stiffness * area);
  const auto report = [&](const char* what, double exact)
  {
    const double u = s.solver->displacement[1][0];
    const double rise = s.solver->displacement[1][2] + closure;
    std::printf("%s: shear displacement %.4g m, ", what, u);
    talus_test::check("uplift (m)", rise, exact, 1e-4);
  };
  s.run_until(1.0); // 1 mm forward
  report("forward 1 mm", tan_psi * (s.solver->displacement[1][0] - u_e));
  const auto forces = [&](const char* what)
  {
    double fn = 0.0;
    for (unsigned int i = 0; i < c.n_subcontacts(); ++i)
      fn += c.sc_fn[i];
    std::printf("%s: ", what);
    talus_test::check("normal force (N)", fn, n_force, 1e-6);
    std::printf("%s: ", what);
    talus_test::check("shear force (N)", shear_force(), n_force * tan_phi, 1e-6);
  };
  forces("dilating forward");
  s.run_until(3.0); // 3 mm forward, beyond the limit
  report("forward 3 mm (limit 2 mm)", tan_psi * (lim - u_e));
  // Back to 0.5 mm: the first 2 u_e unload elastically, then the joint
  // closes as it slips back.
  s.solver->velocity[1][0] = -0.001; // held: the solver keeps it
  s.run_until(5.5);
  report("back to 0.5 mm", tan_psi * (s.solver->displacement[1][0] - u_e));
  forces("closing backward");
}
