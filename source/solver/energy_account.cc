#include <talus/solver/energy_account.h>

#include <algorithm>
#include <cmath>

namespace talus
{

double EnergyAccount::scale() const
{
  double s = 0.0;
  for (double term : {gravity_work, boundary_work, initial_stored, kinetic, joint_elastic,
                      zone_elastic, friction, plastic, damping})
    s = std::max(s, std::abs(term));
  return s;
}

} // namespace talus
