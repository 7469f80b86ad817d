#pragma once

#include <talus/zone/tet_mesh.h>

#include <cmath>

namespace talus
{

// Nodal mixed discretization of 4-node zones (eqs. 68-76): a zone's
// volumetric strain increment, and its plastic pressure, are replaced by
// the mean over its four gridpoints of volume-weighted gridpoint averages.
// The functions below work on one batch of zones [first, first + n) of one
// material; per-zone arrays of the batch start at zone `first`, gridpoint
// arrays hold one number per gridpoint. Zones are taken in order, so each
// gridpoint sum is added up in the same order whatever the batch size.

/// a b + c, rounded once where the hardware multiplies and adds in one
/// instruction (as GCC contracts a * b + c there) and twice elsewhere:
/// spelled out so that the sums do not depend on how the compiler happens
/// to contract a particular loop.
inline double multiply_add(double a, double b, double c)
{
#if defined(__FP_FAST_FMA)
  return std::fma(a, b, c);
#else
  return a * b + c;
#endif
}

/// Eq. 75: adds value V to `weighted_sum` at each gridpoint of every zone
/// of the batch (V the zone's volume, m^3); zones with value 0 change no
/// sum and are left out.
void add_volume_weighted(const TetMesh& mesh, unsigned int first, unsigned int n,
                         const double* value, const double* volume, double* weighted_sum);

/// Eq. 69 with the two sums side by side (`pairs`: two per gridpoint, the
/// sum of value V, then the sum of V), rounded as one multiply-add and one
/// add per gridpoint would round them, with one access to each gridpoint
/// of every zone of the batch.
void add_volume_weighted_pairs(const TetMesh& mesh, unsigned int first, unsigned int n,
                               const double* value, const double* volume, double* pairs);
/// The first number of each listed gridpoint's pair divided by the second
/// (its average), in place, where that is positive: for the `count`
/// gridpoints whose sums are complete while others are still growing.
void average_pairs(const unsigned int* gridpoints, unsigned int count, double* pairs);

/// Eq. 75's averages at the `count` listed gridpoints (those whose sums
/// are complete): weighted_sum / V in place (one number per gridpoint), V
/// the second number of each gridpoint's pair, where V is positive.
void divide_by_pair_volume(const unsigned int* gridpoints, unsigned int count, double* weighted_sum,
                           const double* pairs);

/// Mean of the gridpoint averages at the four gridpoints of zone z, the
/// averages `stride` numbers apart. Each quarter is exact, so this is the
/// sum of a quarter of each average, in corner order, whether the quarter
/// is taken before or after the division.
inline double corner_mean(const TetMesh& mesh, unsigned int z, const double* average,
                          unsigned int stride = 1)
{
  double mean = 0.0;
  for (unsigned int g : mesh.zone_gridpoint[z])
    mean += 0.25 * average[std::size_t(stride) * g];
  return mean;
}

/// Eqs. 70-71: each zone of the batch keeps the deviatoric part of its
/// strain increment (6 per zone, xx yy zz xy yz zx) and takes the mean of
/// its gridpoints' averages of the volumetric increment as its volumetric
/// part (the first number of each gridpoint's pair, see average_pairs);
/// with `own`, each zone's own volumetric part tr(d eps) / 3 there.
void replace_volumetric_strain(const TetMesh& mesh, unsigned int first, unsigned int n,
                               const double* average_pairs, double* strain_increment,
                               double* own = nullptr);

/// The energy account of nodal mixed discretization. Its nodal forces act
/// with each zone's own strain increment (eq. 55), while its stress follows
/// the replaced one (eqs. 70-71), so the forces do V sigma : d(eps) of work
/// where the zone's elastic energy gains V sigma : d(eps~); the difference,
/// V p (tr d(eps) - tr d(eps~)) with p = tr(sigma) / 3, is stored all the
/// same (the stiffness of eqs. 68-71 is symmetric: for linear elasticity it
/// holds K / 2 sum_g (W_g / 4) e_g^2 over the gridpoints, W_g the zone
/// volumes around g and e_g their average volumetric strain, at least the
/// zones' own K / 2 sum_z V_z e~_z^2). This returns the sum of V (p - b
/// tr d(eps~)) (3 own - tr d(eps~)) over the batch (J), from the replaced
/// increments `strain_increment`, the zones' `own` volumetric parts, their
/// stresses (6 per zone) and volumes (m^3). Taken before and after the
/// zone model with b = 0, the mean is the step's share (the midpoint rule of
/// the stress work); an elastic zone's mean stress rises by K tr d(eps~),
/// so after its model b = K / 2 gives the same in one pass.
double replaced_strain_work(unsigned int n, const double* own, const double* strain_increment,
                            const double* stress, const double* volume, double b = 0.0);

} // namespace talus
