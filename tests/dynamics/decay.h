#pragma once

// The decay of a free vibration, from a signal sampled every step: its
// extremes (each refined by the parabola through the samples around it),
// the logarithmic decrement over them and the ratio of critical damping
// it means, and the angular frequency from their spacing.

#include <cmath>
#include <vector>

struct Decay
{
  double xi = 0.0;    ///< fraction of critical damping
  double omega = 0.0; ///< undamped angular frequency, rad/s (from the damped one)
  unsigned int extremes = 0;
};

/// Tracks the extremes of q(t) as samples come.
struct ExtremeTracker
{
  std::vector<double> time, value; ///< of each extreme: s, q
  double q0 = 0.0, q1 = 0.0, t1 = 0.0;
  unsigned int samples = 0;

  void add(double t, double q)
  {
    if (samples >= 2 && (q1 - q0) * (q - q1) < 0.0)
    {
      // Parabola through (t1 - dt, q0), (t1, q1), (t1 + dt, q).
      const double curvature = q - 2.0 * q1 + q0, slope = 0.5 * (q - q0);
      const double shift = curvature != 0.0 ? -slope / curvature : 0.0; // in steps
      const double dt = t - t1;
      time.push_back(t1 + shift * dt);
      value.push_back(q1 + 0.5 * slope * shift);
    }
    q0 = q1;
    q1 = q;
    t1 = t;
    ++samples;
  }

  /// The decay from extreme `first` to extreme `last` (half periods
  /// apart; extreme last + 1 must be there).
  Decay decay(unsigned int first, unsigned int last) const
  {
    Decay d;
    if (last + 1 >= value.size() || last <= first)
      return d;
    // The swing from one extreme to the next does not depend on where the
    // oscillation is centred.
    const unsigned int halves = last - first;
    const double delta = 2.0 *
                         std::log(std::abs(value[first] - value[first + 1]) /
                                  std::abs(value[last] - value[last + 1])) /
                         halves;
    d.xi = delta / std::sqrt(4.0 * M_PI * M_PI + delta * delta);
    const double omega_damped = M_PI * halves / (time[last] - time[first]);
    d.omega = omega_damped / std::sqrt(1.0 - d.xi * d.xi);
    d.extremes = static_cast<unsigned int>(value.size());
    return d;
  }
};
