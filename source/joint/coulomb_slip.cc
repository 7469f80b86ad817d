#include <talus/joint/coulomb_slip.h>

#include <cmath>

namespace talus
{

double coulomb_slip(const JointProperties& joint, SubContactBatch& s)
{
  const double deg = M_PI / 180.0;
  const double tan_phi = std::tan(joint.friction_angle * deg);
  const double tan_psi = std::tan(joint.dilation_angle * deg);
  const double kn = joint.normal_stiffness, ks = joint.shear_stiffness;
  double dissipated = 0.0;
  for (unsigned int i = 0; i < s.size; ++i)
  {
    const double area = s.area[i];
    double* fs = s.shear_force + 3 * i;
    const double* dus = s.du_shear + 3 * i;
    const bool has_failed = s.state[i] & failed;

    // Normal force from the total normal displacement (closure positive
    // force): equivalent to eqs. 24 and 26 but free of drift.
    s.normal_displacement[i] += s.du_normal[i];
    double fn = -kn * area * s.normal_displacement[i];

    // Tension: an intact joint holds up to T A (eq. 34), a failed one none.
    const double t_max = has_failed ? 0.0 : -joint.tensile_strength * area;
    unsigned char state = s.state[i] & failed;
    if (fn < t_max || (fn < 0.0 && has_failed))
    {
      // Eq. 38: tensile failure or separation: no force at all.
      if (fn < t_max && !has_failed && joint.tensile_strength > 0.0)
        state |= failed;
      fn = 0.0;
      fs[0] = fs[1] = fs[2] = 0.0;
      s.normal_force[i] = 0.0;
      s.state[i] = state | open;
      continue;
    }

    // Elastic shear increment (eqs. 25, 27).
    const double f_old[3] = {fs[0], fs[1], fs[2]};
    for (int d = 0; d < 3; ++d)
      fs[d] -= ks * area * dus[d];
    const double fs_mag = std::sqrt(fs[0] * fs[0] + fs[1] * fs[1] + fs[2] * fs[2]);
    // Eq. 35 (intact) or eq. 37 (failed): the shear strength.
    const double cohesion = has_failed ? 0.0 : joint.cohesion;
    const double fs_max = cohesion * area + std::max(fn, 0.0) * tan_phi;
    if (fs_mag > fs_max)
    {
      // Eq. 39: scale back to the strength; failure removes cohesion and
      // tension for good.
      const double scale = fs_max / fs_mag;
      for (int d = 0; d < 3; ++d)
        fs[d] *= scale;
      if (joint.cohesion > 0.0 || joint.tensile_strength > 0.0)
        state |= failed;
      state |= slipping;
      // Dilation while slipping (eqs. 41-43), until the limiting shear
      // displacement; opening the joint raises the normal force.
      const double dus_mag = std::sqrt(dus[0] * dus[0] + dus[1] * dus[1] + dus[2] * dus[2]);
      s.shear_displacement[i] += dus_mag;
      if (tan_psi != 0.0 && (joint.dilation_limit <= 0.0 ||
                             s.shear_displacement[i] < joint.dilation_limit))
        s.normal_displacement[i] -= dus_mag * tan_psi;
      // Work of the friction force against the slip (always dissipated).
      dissipated += 0.5 * std::abs((f_old[0] + fs[0]) * dus[0] + (f_old[1] + fs[1]) * dus[1] +
                                   (f_old[2] + fs[2]) * dus[2]);
    }
    s.normal_force[i] = fn;
    s.state[i] = state;
  }
  return dissipated;
}

} // namespace talus
