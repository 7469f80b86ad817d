// Verification: the normal stiffness of a continuously yielding joint
// grows with the normal stress, kn = a_n sigma_n^e_n (never below the
// 'Normal stiffness'), so the joint stiffens as it closes
// (parameters/verification/continuously_yielding.prm, not sheared). The
// plate settles under its weight at two densities (sigma_n 5.2 and
// 21 kPa), and at each 1 % heavier: the closures must be those of the law
// integrated here (d c = d sigma / kn(sigma), Simpson's rule), and the
// stiffness measured from the 1 % step must be a_n sigma^e_n there.

#include <cmath>
#include <cstdio>

#include "../tests.h"
#include "rigid_scene.h"

namespace
{
/// Closure that carries sigma: the integral of d sigma / kn(sigma).
double closure_of(const talus::JointProperties& j, double sigma)
{
  const auto compliance = [&](double s)
  {
    const double k = j.normal_stiffness_factor * std::pow(s, j.normal_stiffness_exponent);
    return 1.0 / std::min(std::max(k, j.normal_stiffness), j.maximum_stiffness);
  };
  // Simpson's rule in sqrt(sigma) (the integrand has a kink where kn
  // leaves its minimum; many panels make its error negligible).
  const int n = 200000;
  const double h = std::sqrt(sigma) / n;
  double sum = 0.0;
  for (int k = 0; k <= n; ++k)
  {
    const double t = k * h, w = (k == 0 || k == n) ? 1.0 : (k % 2 ? 4.0 : 2.0);
    sum += w * compliance(t * t) * 2.0 * t; // d sigma = 2 t dt
  }
  return sum * h / 3.0;
}

/// Closure of the plate at rest at density rho (m), and its normal stress.
double settled_closure(double rho, double& sigma)
{
  RigidScene s("verification/continuously_yielding.prm",
               [&](talus::Scene& sc) { sc.density = rho; });
  s.solver->velocity[1][0] = 0.0; // no shear; held: the solver keeps it
  const unsigned long steps = s.run_to_ratio(1e-9, 400000);
  std::fprintf(stderr, "density %g: %lu steps to the ratio\n", rho, steps);
  sigma = s.solver->mass[1] * 9.81 / 4.0;
  return -s.solver->displacement[1][2];
}
} // namespace

int main()
{
  RigidScene s("verification/continuously_yielding.prm");
  const talus::JointProperties j = s.scene.solver.joint_materials.at(0);
  double kn[2];
  int k = 0;
  for (const double rho : {2650.0, 4.0 * 2650.0})
  {
    double sigma = 0.0, sigma_up = 0.0;
    const double c = settled_closure(rho, sigma), c_up = settled_closure(1.01 * rho, sigma_up);
    // Both settle to a ratio of 1e-9, so their last digits follow the
    // CPU's rounding: verdicts here, figures on standard error.
    const double exact = closure_of(j, sigma);
    std::fprintf(stderr, "closure %.10g m, law %.10g m, relative error %.1e\n", c, exact,
                 talus_test::relative_error(c, exact));
    std::printf("sigma_n %.2g kPa: closure within 1e-6 of the law's: %s\n", 1e-3 * sigma,
                talus_test::verdict(talus_test::relative_error(c, exact) <= 1e-6));
    const double mid = 0.5 * (sigma + sigma_up);
    kn[k] = (sigma_up - sigma) / (c_up - c);
    const double law = j.normal_stiffness_factor * std::pow(mid, j.normal_stiffness_exponent);
    std::fprintf(stderr, "kn %.10g Pa/m, a_n sigma^e_n %.10g Pa/m, relative error %.1e\n", kn[k],
                 law, talus_test::relative_error(kn[k], law));
    std::printf(
        "sigma_n %.2g kPa: kn from a 1 %% step %.2g Pa/m, within 1e-4 of a_n sigma^e_n: %s\n",
        1e-3 * sigma, kn[k], talus_test::verdict(talus_test::relative_error(kn[k], law) <= 1e-4));
    ++k;
  }
  std::printf(
      "kn at 21 kPa over kn at 5.2 kPa: %.2f (4^e_n = %.2f) %s\n", kn[1] / kn[0],
      std::pow(4.0, j.normal_stiffness_exponent),
      talus_test::verdict(
          std::abs(kn[1] / kn[0] / std::pow(4.0, j.normal_stiffness_exponent) - 1.0) < 1e-3));
}
