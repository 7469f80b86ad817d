#include <talus/joint/continuously_yielding.h>

#include <algorithm>
#include <cmath>

namespace talus
{

NormalStressLaw NormalStressLaw::of(const JointProperties& joint)
{
  NormalStressLaw law;
  law.k_min = joint.normal_stiffness;
  law.k_max = std::max(joint.maximum_stiffness, joint.normal_stiffness);
  law.a = joint.normal_stiffness_factor;
  law.e = joint.normal_stiffness_exponent;
  if (!(law.a > 0.0))
  {
    // kn constant: all of it the last, linear part.
    law.k_max = law.k_min;
    return law;
  }
  if (law.e == 0.0)
  {
    // kn = a_n, kept between the bounds: linear again.
    law.k_min = law.k_max = std::min(std::max(law.a, law.k_min), law.k_max);
    return law;
  }
  // Where a_n sigma^e_n meets kn_min and kn_max.
  law.sigma_t = std::pow(law.k_min / law.a, 1.0 / law.e);
  law.sigma_u = std::pow(law.k_max / law.a, 1.0 / law.e);
  law.c_t = law.sigma_t / law.k_min;
  const double g = 1.0 - law.e;
  law.c_u = law.c_t + (std::pow(law.sigma_u, g) - std::pow(law.sigma_t, g)) / (g * law.a);
  return law;
}

double NormalStressLaw::stress(double c) const
{
  if (c <= c_t)
    return k_min * c;
  if (c >= c_u)
    return sigma_u + k_max * (c - c_u);
  const double g = 1.0 - e;
  return std::pow(std::pow(sigma_t, g) + g * a * (c - c_t), 1.0 / g);
}

double NormalStressLaw::closure(double sigma) const
{
  if (sigma <= sigma_t)
    return sigma / k_min;
  if (sigma >= sigma_u)
    return c_u + (sigma - sigma_u) / k_max;
  const double g = 1.0 - e;
  return c_t + (std::pow(sigma, g) - std::pow(sigma_t, g)) / (g * a);
}

double NormalStressLaw::stiffness(double sigma) const
{
  if (sigma <= sigma_t)
    return k_min;
  if (sigma >= sigma_u)
    return k_max;
  return a * std::pow(sigma, e);
}

double NormalStressLaw::energy(double sigma) const
{
  const double first = std::min(sigma, sigma_t);
  double w = 0.5 * first * first / k_min;
  if (sigma > sigma_t)
  {
    const double top = std::min(sigma, sigma_u), h = 2.0 - e;
    w += (std::pow(top, h) - std::pow(sigma_t, h)) / (h * a);
  }
  if (sigma > sigma_u)
    w += 0.5 * (sigma * sigma - sigma_u * sigma_u) / k_max;
  return w;
}

double cy_shear_stiffness(const JointProperties& joint, double sigma_n)
{
  if (!(joint.shear_stiffness_factor > 0.0))
    return joint.shear_stiffness;
  const double k = joint.shear_stiffness_factor *
                   std::pow(std::max(sigma_n, 0.0), joint.shear_stiffness_exponent);
  return std::min(std::max(k, joint.shear_stiffness),
                  std::max(joint.maximum_stiffness, joint.shear_stiffness));
}

double cy_stored_energy(const JointProperties& joint, double fn, double fs2, double area)
{
  if (!(area > 0.0))
    return 0.0;
  const double sigma = std::max(fn, 0.0) / area;
  return NormalStressLaw::of(joint).energy(sigma) * area +
         0.5 * fs2 / (cy_shear_stiffness(joint, sigma) * area);
}

namespace
{
/// What the loop needs of a material, worked out once per batch.
struct YieldingRow
{
  bool active = false; ///< a continuously yielding material
  NormalStressLaw normal;
  double phi = 0.0, phi_i = 0.0, roughness = 1.0; ///< radians, radians, m
};
} // namespace

ExactSum continuously_yielding(const std::vector<JointProperties>& joints, SubContactBatch& s)
{
  YieldingRow rows[256];
  const double deg = M_PI / 180.0;
  for (std::size_t k = 0; k < joints.size() && k < 256; ++k)
    if (joints[k].model == JointModel::continuously_yielding)
    {
      rows[k].active = true;
      rows[k].normal = NormalStressLaw::of(joints[k]);
      rows[k].phi = joints[k].friction_angle * deg;
      rows[k].phi_i = joints[k].initial_friction_angle * deg;
      rows[k].roughness = joints[k].roughness;
    }
  ExactSum dissipated;
  for (unsigned int at = 0; at < s.size; ++at)
  {
    const unsigned int i = s.indices != nullptr ? s.indices[at] : at;
    if (s.computed != nullptr && !s.computed[i])
      continue;
    const unsigned char material = s.material != nullptr ? s.material[i] : 0;
    const YieldingRow& row = rows[material];
    if (!row.active)
      continue;
    const JointProperties& joint = joints[material];
    const double area = s.area[i];
    double* fs = s.shear_force + 3 * i;
    const double* dus = s.du_shear + 3 * i;
    double* us = s.shear_displacement + 3 * i;
    double* y = s.yield + yield_state_size * i;

    // Normal stress from the total closure less the normal offset (the
    // closure that carries an initial stress): a function of it, so free
    // of drift as Coulomb slip's (eqs. 24, 26).
    s.normal_displacement[i] += s.du_normal[i];
    const double closure =
        -(s.normal_displacement[i] - (s.dilation != nullptr ? s.dilation[i] : 0.0));
    for (int d = 0; d < 3; ++d)
      us[d] += dus[d];
    if (!(closure > 0.0) || !(area > 0.0))
    {
      // Open (no tension): no forces; the shear spring's energy goes, and
      // the next shear starts a new loading (r = 0).
      const double ks = cy_shear_stiffness(joint, 0.0);
      if (area > 0.0 && (s.counted == nullptr || s.counted[i]))
        dissipated += 0.5 * (fs[0] * fs[0] + fs[1] * fs[1] + fs[2] * fs[2]) / (ks * area);
      fs[0] = fs[1] = fs[2] = 0.0;
      s.normal_force[i] = 0.0;
      y[reversal_ratio] = 0.0;
      y[loading_direction] = y[loading_direction + 1] = y[loading_direction + 2] = 0.0;
      s.state[i] = open;
      continue;
    }
    const double sigma = row.normal.stress(closure);
    const double fn = sigma * area;
    const double ks = cy_shear_stiffness(joint, sigma);
    const auto bounding_force = [&](double u_p)
    {
      const double phi_m = row.phi + (row.phi_i - row.phi) * std::exp(-u_p / row.roughness);
      return fn * std::tan(phi_m);
    };
    const double f_old[3] = {fs[0], fs[1], fs[2]};
    const double step = std::sqrt(dus[0] * dus[0] + dus[1] * dus[1] + dus[2] * dus[2]);
    unsigned char state = 0;
    if (step > 0.0)
    {
      // The shear force on B grows against the relative displacement
      // (eq. 27): its loading direction is -du_s.
      const double dir[3] = {-dus[0] / step, -dus[1] / step, -dus[2] / step};
      double* last = y + loading_direction;
      const double turn = last[0] * dir[0] + last[1] * dir[1] + last[2] * dir[2];
      const double f_m = bounding_force(y[plastic_shear_displacement]);
      const double along = fs[0] * dir[0] + fs[1] * dir[1] + fs[2] * dir[2];
      // tau / tau_m with the sign of the increment.
      const double ratio = f_m > 0.0 ? along / f_m : 1.0;
      if (turn < 0.0)
        y[reversal_ratio] = std::min(ratio, 0.75); // reversal: F starts at 1 again
      const double fraction = std::clamp((1.0 - ratio) / (1.0 - y[reversal_ratio]), 0.0, 1.0);
      for (int d = 0; d < 3; ++d)
      {
        fs[d] += fraction * ks * area * step * dir[d];
        last[d] = dir[d];
      }
      y[plastic_shear_displacement] += (1.0 - fraction) * step;
    }
    // |tau| <= tau_m with the plastic shear of this step (and a normal
    // stress that may have fallen).
    const double f_m = bounding_force(y[plastic_shear_displacement]);
    const double fs_mag = std::sqrt(fs[0] * fs[0] + fs[1] * fs[1] + fs[2] * fs[2]);
    if (fs_mag > f_m)
    {
      const double scale = f_m / fs_mag;
      for (int d = 0; d < 3; ++d)
        fs[d] *= scale;
      state |= slipping;
    }
    // Dissipated: the work done on the joint over the increment less what
    // its shear spring stored of it.
    const double work = -0.5 * ((f_old[0] + fs[0]) * dus[0] + (f_old[1] + fs[1]) * dus[1] +
                                (f_old[2] + fs[2]) * dus[2]);
    const double stored = 0.5 *
                          (fs[0] * fs[0] + fs[1] * fs[1] + fs[2] * fs[2] -
                           (f_old[0] * f_old[0] + f_old[1] * f_old[1] + f_old[2] * f_old[2])) /
                          (ks * area);
    if (s.counted == nullptr || s.counted[i])
      dissipated += std::max(work - stored, 0.0);
    s.normal_force[i] = fn;
    s.state[i] = state;
  }
  return dissipated;
}

} // namespace talus
