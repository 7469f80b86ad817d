#include <talus/zone/viscous_stress.h>

namespace talus
{

void viscous_stress(unsigned int n, double bulk_modulus, double shear_modulus, double beta_over_dt,
                    const double* de, double* stress)
{
  const ViscousModuli moduli(bulk_modulus, shear_modulus, beta_over_dt);
  const double lambda = moduli.lambda, two_g = moduli.two_g;
  for (unsigned int k = 0; k < n; ++k)
  {
    const double* e = de + 6 * k;
    double* s = stress + 6 * k;
    const double volumetric = lambda * (e[0] + e[1] + e[2]);
    for (int c = 0; c < 3; ++c)
      s[c] = volumetric + two_g * e[c];
    for (int c = 3; c < 6; ++c)
      s[c] = two_g * e[c];
  }
}

} // namespace talus
