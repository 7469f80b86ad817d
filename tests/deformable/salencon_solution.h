#pragma once

// Salencon's closed form for a circular opening in Mohr-Coulomb rock under
// an isotropic far-field stress (the plastic radius and the stresses in the
// plastic and elastic zones). Shared by salencon_01 (structured mesh) and
// salencon_02 (the mesher's).

#include <talus/base/exceptions.h>
#include <talus/zone/tet_mesh.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace talus;

namespace
{
const double a = 1.0, R = 20.0, p0 = 1e5, p_i = 0.0;
const double E = 2e10, nu = 0.4, phi = 20.0 * M_PI / 180.0, c = 17e3;
const double eps = 1e-9, big = 1e3;

Vec3 point(const TetMesh& m, unsigned int g)
{
  return Vec3(m.position[3 * g], m.position[3 * g + 1], m.position[3 * g + 2]);
}

/// Salencon's solution, stresses tension positive (Pa).
struct Salencon
{
  double Kp, C, Rp, s_re;
  Salencon()
      : Kp((1.0 + std::sin(phi)) / (1.0 - std::sin(phi))), C(c / std::tan(phi)),
        Rp(a * std::pow(2.0 / (Kp + 1.0) * (p0 + C) / (p_i + C), 1.0 / (Kp - 1.0))),
        s_re((2.0 * p0 - 2.0 * c * std::sqrt(Kp)) / (Kp + 1.0))
  {
  }
  void stress(double r, double& s_r, double& s_t) const
  {
    if (r <= Rp)
    {
      s_r = C - (p_i + C) * std::pow(r / a, Kp - 1.0);
      s_t = Kp * s_r - 2.0 * c * std::sqrt(Kp);
    }
    else
    {
      s_r = -p0 + (p0 - s_re) * std::pow(Rp / r, 2);
      s_t = -p0 - (p0 - s_re) * std::pow(Rp / r, 2);
    }
  }
  /// Plastic radius for a finite outer radius R loaded by p0 (compression
  /// positive: elastic sigma_r,t = A -/+ B/r^2 with A - B/R^2 = p0, yield
  /// at R_p and sigma_r continuous there), by bisection.
  double finite_Rp() const
  {
    const auto mismatch = [&](double rp)
    {
      const double B = ((Kp - 1.0) * p0 + 2.0 * c * std::sqrt(Kp)) /
                       ((Kp + 1.0) / (rp * rp) - (Kp - 1.0) / (R * R));
      const double A = p0 + B / (R * R);
      return (p_i + C) * std::pow(rp / a, Kp - 1.0) - C - (A - B / (rp * rp));
    };
    double lo = a, hi = 0.5 * R;
    for (int k = 0; k < 100; ++k)
      (mismatch(0.5 * (lo + hi)) < 0.0 ? lo : hi) = 0.5 * (lo + hi);
    return 0.5 * (lo + hi);
  }
};

/// Whether computed is within tolerance p0 of the closed form; the values
/// and the error go to standard error (their last digits follow the CPU's
/// rounding: a static run stopped at a ratio after a plastic path).
void check_over_p0(const std::string& name, double computed, double exact, double tolerance)
{
  const double error = std::abs(computed - exact) / p0;
  std::fprintf(stderr, "%s: %.6g (closed form %.6g, error %.1e of p0)\n", name.c_str(), computed,
               exact, error);
  std::printf("%s: within %.1e p0 of the closed form: %s\n", name.c_str(), tolerance,
              talus_test::verdict(error <= tolerance));
}
} // namespace
