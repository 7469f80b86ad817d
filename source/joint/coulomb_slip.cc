#include <talus/joint/coulomb_slip.h>

#include <algorithm>
#include <cmath>

namespace talus
{

namespace
{
/// What the loop needs of a joint material, its tangents worked out once.
struct CoulombRow
{
  double kn, ks, tan_phi, tan_psi, cohesion, tensile_strength, dilation_limit;
};

CoulombRow row_of(const JointProperties& joint)
{
  const double deg = M_PI / 180.0;
  return {joint.normal_stiffness,
          joint.shear_stiffness,
          std::tan(joint.friction_angle * deg),
          std::tan(joint.dilation_angle * deg),
          joint.cohesion,
          joint.tensile_strength,
          joint.dilation_limit > 0.0 ? joint.dilation_limit : 1e300};
}
} // namespace

ExactSum coulomb_slip(const JointProperties& joint, SubContactBatch& s)
{
  return coulomb_slip(std::vector<JointProperties>{joint}, s);
}

ExactSum coulomb_slip(const std::vector<JointProperties>& joints, SubContactBatch& s)
{
  CoulombRow rows[256];
  bool other_model[256] = {};
  bool mixed = false; // some materials are of another model: skip their sub-contacts
  for (std::size_t k = 0; k < joints.size() && k < 256; ++k)
  {
    rows[k] = row_of(joints[k]);
    other_model[k] = joints[k].model != JointModel::coulomb_slip;
    mixed |= other_model[k];
  }
  ExactSum dissipated;
  for (unsigned int at = 0; at < s.size; ++at)
  {
    const unsigned int i = s.indices != nullptr ? s.indices[at] : at;
    if (s.computed != nullptr && !s.computed[i])
      continue;
    const unsigned char material = s.material != nullptr ? s.material[i] : 0;
    if (mixed && other_model[material])
      continue;
    const CoulombRow& joint = rows[material];
    const double tan_phi = joint.tan_phi, tan_psi = joint.tan_psi;
    const double kn = joint.kn, ks = joint.ks;
    const double area = s.area[i];
    const double shear_compliance = area > 0.0 ? 1.0 / (ks * area) : 0.0; // for the energy
    double* fs = s.shear_force + 3 * i;
    const double* dus = s.du_shear + 3 * i;
    const bool has_failed = s.state[i] & failed;

    // Water in the joint ('Water') needs nothing here. The theory manual
    // writes the Coulomb limit (eqs. 35-39) on the force the normal spring
    // carries and says nothing of joint water; talus puts the water
    // pressure p on every face below the phreatic surface (water_loads.h),
    // in contact or not, so that across a joint the two faces are pushed
    // apart by p A each. The blocks' equilibrium then leaves the spring only
    // the total normal force less the water's: fn here is the effective
    // normal force N' = N - U, and the limit fn tan(phi) is Terzaghi's; a
    // joint opens (fn < 0) where p exceeds the total normal stress.
    // Normal force from the total normal displacement less the dilation the
    // joint has taken (closure gives compression): equivalent to eqs. 24 and
    // 26 but free of drift.
    s.normal_displacement[i] += s.du_normal[i];
    double fn = -kn * area * (s.normal_displacement[i] - (s.dilation ? s.dilation[i] : 0.0));

    // Tension: an intact joint holds up to T A (eq. 34), a failed one none.
    const double t_max = has_failed ? 0.0 : -joint.tensile_strength * area;
    unsigned char state = s.state[i] & failed;
    if (fn < t_max || (fn < 0.0 && has_failed))
    {
      // Eq. 38: tensile failure or separation: no force at all.
      if (fn < t_max && !has_failed && joint.tensile_strength > 0.0)
        state |= failed;
      // The shear spring's energy is lost with it, and so is the normal
      // spring's when it held tension and broke (in compression it gave its
      // energy back to the blocks as it opened).
      if (area > 0.0)
      {
        const double held = std::min(s.normal_force[i], 0.0);
        if (s.counted == nullptr || s.counted[i])
          dissipated += 0.5 * held * held / (kn * area) +
                        0.5 * (fs[0] * fs[0] + fs[1] * fs[1] + fs[2] * fs[2]) * shear_compliance;
      }
      fn = 0.0;
      fs[0] = fs[1] = fs[2] = 0.0;
      s.normal_force[i] = 0.0;
      s.state[i] = state | open;
      continue;
    }

    // Elastic shear increment (eqs. 25, 27); the total shear displacement
    // before it gives the direction that dilation is measured against.
    double* us = s.shear_displacement + 3 * i;
    const double f_old[3] = {fs[0], fs[1], fs[2]};
    const double us_old[3] = {us[0], us[1], us[2]};
    for (int d = 0; d < 3; ++d)
    {
      fs[d] -= ks * area * dus[d];
      us[d] += dus[d];
    }
    const double fs_mag = std::sqrt(fs[0] * fs[0] + fs[1] * fs[1] + fs[2] * fs[2]);
    // Eq. 35 (intact) or eq. 37 (failed): the shear strength.
    const double cohesion = has_failed ? 0.0 : joint.cohesion;
    const double fs_max = cohesion * area + std::max(fn, 0.0) * tan_phi;
    if (fs_mag > fs_max)
    {
      // Failure removes cohesion and tension for good.
      if (joint.cohesion > 0.0 || joint.tensile_strength > 0.0)
        state |= failed;
      state |= slipping;
      // Dilation while slipping (eqs. 41-43), measured as the change of
      // min(|U^s|, U^s_lim): shear away from the origin opens the joint,
      // shear back towards it closes it again (the direction dependence),
      // and beyond the limiting displacement nothing changes. Eq. 43: the
      // normal force takes the opening at once, and the strength of this
      // step follows it (otherwise the shear force would lag the normal
      // force by one step of dilation: kn A tan(psi) dU^s).
      double strength = fs_max;
      if (tan_psi != 0.0 && s.dilation)
      {
        const double limit = joint.dilation_limit;
        const double before =
            std::sqrt(us_old[0] * us_old[0] + us_old[1] * us_old[1] + us_old[2] * us_old[2]);
        const double after = std::sqrt(us[0] * us[0] + us[1] * us[1] + us[2] * us[2]);
        s.dilation[i] += (std::min(after, limit) - std::min(before, limit)) * tan_psi;
        fn = std::max(-kn * area * (s.normal_displacement[i] - s.dilation[i]), 0.0);
        strength = cohesion * area + fn * tan_phi;
      }
      // Eq. 39: scale back to the strength.
      if (fs_mag > strength)
      {
        const double scale = strength / fs_mag;
        for (int d = 0; d < 3; ++d)
          fs[d] *= scale;
      }
      // Dissipated by the slip: the work done on the joint over the shear
      // increment less what its shear spring stored of it. When the
      // strength drops (the normal force falls) the spring gives up energy
      // with no increment at all: slip too, so no bound by the increment.
      const double work = -0.5 * ((f_old[0] + fs[0]) * dus[0] + (f_old[1] + fs[1]) * dus[1] +
                                  (f_old[2] + fs[2]) * dus[2]);
      const double stored = 0.5 *
                            (fs[0] * fs[0] + fs[1] * fs[1] + fs[2] * fs[2] -
                             (f_old[0] * f_old[0] + f_old[1] * f_old[1] + f_old[2] * f_old[2])) *
                            shear_compliance;
      if (s.counted == nullptr || s.counted[i])
        dissipated += std::max(work - stored, 0.0);
    }
    s.normal_force[i] = fn;
    s.state[i] = state;
  }
  return dissipated;
}

} // namespace talus
