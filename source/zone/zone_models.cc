#include <talus/base/exceptions.h>
#include <talus/zone/zone_models.h>

namespace talus
{

void elastic_update(const ZoneMaterial& m, StressBatch& b)
{
  const double lambda = m.bulk_modulus - 2.0 / 3.0 * m.shear_modulus, two_g = 2.0 * m.shear_modulus;
  for (unsigned int i = 0; i < b.size; ++i)
  {
    const double* de = b.strain_increment + 6 * i;
    double* s = b.stress + 6 * i;
    const double ev = de[0] + de[1] + de[2];
    for (int c = 0; c < 3; ++c)
      s[c] += lambda * ev + two_g * de[c];
    for (int c = 3; c < 6; ++c)
      s[c] += two_g * de[c];
  }
}

void apply_zone_model(const ZoneMaterial& m, StressBatch& b)
{
  switch (m.model)
  {
  case ZoneModel::elastic:
    elastic_update(m, b);
    return;
  case ZoneModel::mohr_coulomb:
    throw InputError("the Mohr-Coulomb zone model is not available in this build yet");
  }
}

} // namespace talus
