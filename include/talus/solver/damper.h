#pragma once

#include <talus/base/exact_sum.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace talus
{

class CheckpointReader;
class CheckpointWriter;

/// Damping of static runs (dynamic runs take Rayleigh damping and,
/// optionally, local damping; see damper_for).
enum class Damping
{
  local,           ///< eqs. 78-79: opposes the velocity, scales with the unbalanced force
  combined,        ///< eq. 83: half local, half by the sign of the force change (steady motion)
  adaptive_global, ///< eq. 77: viscous, its constant set by a servo
  none
};

/// Static damping of one velocity component at a time, shared by rigid
/// blocks and gridpoints. Local damping (eqs. 78-79) opposes the velocity
/// in proportion to the unbalanced force; combined damping (eq. 83)
/// averages that with the sign of the force change, so that a steady
/// motion is not damped; adaptive global damping (eq. 77) is viscous, c m v,
/// with c set by a servo, taken semi-implicitly (stable for any c h < 2).
/// Dynamic runs add a fixed viscous term, the mass-proportional part of
/// Rayleigh damping, -a m v, taken the same way (eqs. 44, 46, 49 with
/// D1 = 1 - a h / 2, D2 = 1 / (1 + a h / 2)).
class Damper
{
public:
  /// `dt` (s) sets the servo's starting value and bounds; `mass_damping`
  /// is the Rayleigh alpha (1/s) of dynamic runs.
  Damper(Damping mode, double alpha, double ratio, double dt, double mass_damping = 0.0)
      : mode_(mode), alpha_(alpha), ratio_(ratio), dt_(dt), c_(0.01 / dt),
        mass_damping_(mass_damping)
  {
  }

  /// v += (f - f_d) h / m; returns the damping force f_d (N). `f_before`
  /// is the unbalanced force of the last step (combined damping).
  double kick(double& v, double f, double f_before, double m, double h)
  {
    double fd = 0.0;
    switch (mode_)
    {
    case Damping::local:
      fd = alpha_ * std::abs(f) * sign(v);
      break;
    case Damping::combined:
      fd = 0.5 * alpha_ * std::abs(f) * (sign(v) - sign(f - f_before));
      break;
    case Damping::adaptive_global:
    {
      const double v_old = v;
      v = (v * (1.0 - 0.5 * c_ * h) + f * h / m) / (1.0 + 0.5 * c_ * h);
      const double v_mid = 0.5 * (v_old + v);
      fd = c_ * m * v_mid;
      damping_power_.add(fd * v_mid);
      force_power_.add(std::abs(f * v_mid));
      return fd;
    }
    case Damping::none:
      break;
    }
    if (mass_damping_ > 0.0)
    {
      // Eq. 49: v+ = (D1 v- + (F - F_d) h / m) D2, the viscous force
      // a m (v- + v+) / 2 over the step.
      const double v_old = v, a = 0.5 * mass_damping_ * h;
      v = (v * (1.0 - a) + (f - fd) * h / m) / (1.0 + a);
      return fd + mass_damping_ * m * 0.5 * (v_old + v);
    }
    v += (f - fd) * h / m;
    return fd;
  }

  /// Eq. 77: keeps the power absorbed by damping the fraction R of the
  /// power of the unbalanced forces (our measure of the rate of change of
  /// kinetic energy: the sum of |F v| over all components). Call every few
  /// steps; c moves by at most 25 % per call, so it follows the system
  /// without hunting, and c dt stays in [1e-6, 1]. The powers are exact
  /// sums, so that a model split among ranks (issue 24), whose `sums` make
  /// each rank's partial sums the whole model's (a collective call), sets
  /// the servo to the same bits as one run.
  void adjust(const std::function<void(std::vector<ExactSum>&)>& sums = {})
  {
    if (mode_ != Damping::adaptive_global)
      return;
    if (sums)
    {
      std::vector<ExactSum> powers{damping_power_, force_power_};
      sums(powers);
      damping_power_ = powers[0];
      force_power_ = powers[1];
    }
    const double damping_power = damping_power_.value(), force_power = force_power_.value();
    if (force_power > 0.0)
    {
      const double r = damping_power / force_power;
      const double factor = r > 0.0 ? std::clamp(ratio_ / r, 0.8, 1.25) : 1.25;
      c_ = std::clamp(c_ * factor, 1e-6 / dt_, 1.0 / dt_);
    }
    damping_power_.clear();
    force_power_.clear();
  }

  static constexpr unsigned int servo_period = 10; ///< steps between adjust() calls

  /// Checkpoints: the servo's coefficient and the powers summed since its
  /// last adjustment.
  void save_state(CheckpointWriter& out) const;
  void load_state(CheckpointReader& in);

private:
  static double sign(double x) { return (x > 0.0) - (x < 0.0); }
  Damping mode_;
  double alpha_, ratio_, dt_;
  double c_;                             ///< 1/s
  double mass_damping_ = 0.0;            ///< Rayleigh alpha, 1/s (dynamics)
  ExactSum damping_power_, force_power_; ///< W, since the last adjust()
};

/// The factor by which the stiffness-proportional part of Rayleigh damping
/// lowers the stable step 2 / omega of an undamped mode of angular
/// frequency omega (rad/s): with the damping force taken from the velocity
/// of the last half step, the central difference scheme is stable for
/// omega dt <= 2 (sqrt(1 + xi^2) - xi), xi = beta omega / 2 (from the
/// roots of its characteristic polynomial; eqs. 84 and 87 are the case xi
/// = 0).
inline double stiffness_damping_step_factor(double beta, double omega)
{
  const double xi = 0.5 * beta * omega;
  return std::sqrt(1.0 + xi * xi) - xi;
}

} // namespace talus
