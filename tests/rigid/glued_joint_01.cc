// Verification 5: a joint with cohesion and tensile strength
// (parameters/verification/glued_joint.prm). A plate glued to a fixed base
// is pulled up by a force growing in time, or sheared like in a shear box
// (moved sideways at a constant velocity, not allowed to tilt). The joint
// breaks in tension at T A (net of the weight), in shear at c A + N tan(phi);
// then only the residual strength remains: none in tension, N tan(phi) in
// shear.

#include <talus/joint/coulomb_slip.h>

#include <cmath>
#include <cstdio>

#include "rigid_scene.h"

int main()
{
  for (const bool shear : {false, true})
  {
    RigidScene s("verification/glued_joint.prm",
                 [&](talus::Scene& scene)
                 {
                   if (shear)
                   {
                     talus::BlockLoad& platen = scene.solver.loads[0];
                     platen.force_rate = talus::Vec3::Zero();
                     platen.prescribe_velocity = true;
                     platen.velocity =
                         talus::Vec3(1e-5, 0, 0); // m/s, slow enough to be quasi-static
                     platen.held[0] = true;
                     platen.held[1] = platen.held[2] = false;
                     platen.hold_rotation = true;
                   }
                 });
    const talus::ContactSet& c = s.solver->contacts();
    const double weight = s.solver->mass[1] * 9.81, area = 4.0;
    const talus::JointProperties& j = s.scene.solver.joint;
    const double tan_phi = std::tan(j.friction_angle * M_PI / 180.0);
    const auto broken = [&]()
    {
      for (unsigned int i = 0; i < c.n_subcontacts(); ++i)
        if (c.sc_state[i] & talus::failed)
          return true;
      return false;
    };
    // Tension: the pull of the last step at which the joint held. Shear: the
    // largest shear force the joint carried.
    double peak = 0.0;
    const auto joint_shear = [&]()
    {
      double f = 0.0;
      for (unsigned int i = 0; i < c.n_subcontacts(); ++i)
        f += c.sc_fs[3 * i];
      return std::abs(f);
    };
    while (!broken() && s.solver->steps_done() < 200000)
    {
      peak = shear ? std::max(peak, joint_shear()) : 1e5 * s.solver->time();
      s.solver->step();
    }
    const double load = peak;
    const double exact =
        shear ? j.cohesion * area + weight * tan_phi : j.tensile_strength * area + weight;
    std::printf("%s: breaks at %.6g N, closed form %.6g N, relative error %.1e %s\n",
                shear ? "shear" : "tension", load, exact, std::abs(load - exact) / exact,
                std::abs(load - exact) / exact < 1e-3 ? "(< 1e-3)" : "(TOO LARGE)");
    // Residual: run on a little and sum what the joint still carries.
    for (int k = 0; k < 200; ++k)
      s.solver->step();
    double fn = 0.0, fs = 0.0;
    for (unsigned int i = 0; i < c.n_subcontacts(); ++i)
    {
      fn += c.sc_fn[i];
      fs += std::hypot(c.sc_fs[3 * i], c.sc_fs[3 * i + 1]);
    }
    if (shear)
      std::printf("shear, after failure: shear force %.6g N, residual N tan(phi) = %.6g N "
                  "(N = %.6g N), relative error %.1e\n",
                  fs, fn * tan_phi, fn, std::abs(fs - fn * tan_phi) / (fn * tan_phi));
    else
      std::printf(
          "tension, after failure: normal force %.3g N, shear force %.3g N (residual: none), "
          "plate has risen %.3g m\n",
          fn, fs, s.solver->displacement[1][2]);
  }
}
