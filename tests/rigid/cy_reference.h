#pragma once

// The continuously yielding joint model (Cundall and Lemos 1990) in one
// dimension, written here apart from talus's source and stepped in far
// finer shear increments than a talus run takes, as the reference of the
// tests: shear stress tau under a constant normal stress sigma_n,
//   d tau = F ks du,  F = (1 - tau/tau_m) / (1 - r) in [0, 1],
//   tau/tau_m with the sign of du,  du_p = (1 - F) |du|,
//   tau_m = sigma_n tan(phi + (phi_i - phi) exp(-u_p / R)),  |tau| <= tau_m,
//   r = 0 at first, tau/tau_m (at most 0.75) when du changes sign.

#include <algorithm>
#include <cmath>

struct CyReference
{
  double sigma, ks, phi, phi_i, roughness; // Pa, Pa/m, rad, rad, m
  double tau = 0.0, u = 0.0, u_p = 0.0, r = 0.0;
  int direction = 0; // sign of the last increment (0: none yet)

  double bound() const
  {
    return sigma * std::tan(phi + (phi_i - phi) * std::exp(-u_p / roughness));
  }

  /// Shears to displacement `target` in increments of at most `h` (m).
  void shear_to(double target, double h = 1e-9)
  {
    const long n = static_cast<long>(std::ceil(std::abs(target - u) / h));
    const double du = n > 0 ? (target - u) / n : 0.0;
    for (long k = 0; k < n; ++k)
    {
      const int sign = du > 0.0 ? 1 : -1;
      const double ratio = sign * tau / bound();
      if (direction != 0 && sign != direction)
        r = std::min(ratio, 0.75);
      direction = sign;
      const double f = std::clamp((1.0 - ratio) / (1.0 - r), 0.0, 1.0);
      tau += f * ks * du;
      u_p += (1.0 - f) * std::abs(du);
      tau = std::clamp(tau, -bound(), bound());
    }
    u = target;
  }
};
