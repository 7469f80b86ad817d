#pragma once

#include <algorithm>

namespace talus
{

/// Partial density scaling of dynamics (the theory manual's mass scaling,
/// eq. 89): only the gridpoints and rigid blocks whose own stable step
/// (eq. 84 per gridpoint, eq. 87 per block) is below the step the user
/// asked for get inertial mass added, just enough to reach it. The added
/// mass is inertia only: gravity and body forces keep the true mass.

/// The least inertial mass (kg) at which a mass on a spring of stiffness
/// `k` (N/m) is stable at the step `dt` (s) of the central difference
/// scheme, with `beta` (s) Rayleigh's stiffness-proportional coefficient
/// (0: none): the step 2 / omega (sqrt(1 + xi^2) - xi), xi = beta omega / 2
/// (stiffness_damping_step_factor), equals dt at omega^2 = 4 / (dt^2 + 2
/// dt beta), hence m = k (dt^2 + 2 dt beta) / 4; beta = 0 is eq. 84's m = k
/// dt^2 / 4. A mass at least this large is left as it is.
inline double mass_for_step(double k, double dt, double beta)
{
  return 0.25 * k * (dt * dt + 2.0 * dt * beta);
}

/// What partial density scaling added, for the run summary and the limit
/// of 'Added mass limit'.
struct AddedMass
{
  unsigned int gridpoints = 0; ///< gridpoints given mass
  unsigned int blocks = 0;     ///< rigid blocks given mass (and rotational inertia)
  double added = 0.0;          ///< kg added in all
  double total = 0.0;          ///< kg: true mass of the free rigid blocks and of the zones
  double largest_factor = 1.0; ///< largest scaled mass over true mass
  double fraction() const { return total > 0.0 ? added / total : 0.0; }
  AddedMass& operator+=(const AddedMass& o)
  {
    gridpoints += o.gridpoints;
    blocks += o.blocks;
    added += o.added;
    total += o.total;
    largest_factor = std::max(largest_factor, o.largest_factor);
    return *this;
  }
};

} // namespace talus
