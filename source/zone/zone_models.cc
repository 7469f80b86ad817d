#include <talus/zone/symmetric_eigen3.h>
#include <talus/zone/zone_models.h>

#include <algorithm>
#include <cmath>

namespace talus
{

namespace
{

/// Eq. 59 for one zone (3D: the volumetric increment is the full trace):
/// stress += lambda tr(de) I + 2 G de; tensor shear components.
inline void add_elastic_increment(double lame_lambda, double two_g, const double* de, double* s)
{
  const double volumetric = lame_lambda * (de[0] + de[1] + de[2]);
  s[0] += volumetric + two_g * de[0];
  s[1] += volumetric + two_g * de[1];
  s[2] += volumetric + two_g * de[2];
  s[3] += two_g * de[3];
  s[4] += two_g * de[4];
  s[5] += two_g * de[5];
}

// The Mohr-Coulomb model in principal stress space (tension positive). The
// trial values come ordered, s1 <= s2 <= s3 (s1 most compressive). Every
// yield condition is a plane
//   F_k(s) = a_k . s - b_k   (F_k > 0: beyond the surface),
// and its plastic strain increment is lambda_k m_k (lambda_k >= 0), where
// m_k is the gradient of the plastic potential. With the elastic matrix in
// principal space D = [[a1 a2 a2] [a2 a1 a2] [a2 a2 a1]], a1 = K + 4G/3,
// a2 = K - 2G/3, the returned stress is s = s_trial - sum_k lambda_k D m_k
// and each active surface k ends on itself:
//   sum_j (a_k . D m_j) lambda_j = F_k(s_trial).
// Shear: f_s = s1 - N_phi s3 + 2c sqrt(N_phi) (yield for f_s < 0), so
// F = -f_s, with potential g_s = s1 - N_psi s3 (m = -grad g_s, so that
// lambda >= 0 and the volume change is lambda (N_psi - 1) >= 0: dilation).
// Tension: f_t = s3 - sigma_t, potential g_t = s3 (m = e3).
// With one active surface this is the standard explicit return of
// FLAC3D-type codes. A single return may however carry s2 past s1 or s3
// (then the stress belongs on an edge of the Mohr-Coulomb pyramid) or leave
// s2 and s1 beyond sigma_t. So the same two criteria are also written with
// every other pair of principal stresses as the least and the greatest
// (N_phi s_j - s_i - 2c sqrt(N_phi), and s_i - sigma_t), nine planes in all,
// and further surfaces are taken in until the stress is admissible.
constexpr int n_shear_surfaces = 6, n_surfaces = 9;
constexpr int shear_13 = 0;  // s1 least, s3 greatest: the main shear plane
constexpr int tension_3 = 6; // s3 beyond sigma_t: the main tension plane
/// (least, greatest) principal axes of the shear planes.
constexpr int shear_axes[n_shear_surfaces][2] = {{0, 2}, {1, 2}, {0, 1}, {1, 0}, {2, 0}, {2, 1}};
/// More than three planes do not meet in a single point of principal space
/// but at special points, where three of them carry the return.
constexpr int max_active = 3;

struct PrincipalSurfaces
{
  double normal[n_surfaces][3];            ///< a_k
  double offset[n_surfaces];               ///< b_k, Pa
  double flow_stress[n_surfaces][3];       ///< D m_k, Pa per unit multiplier
  double flow_trace[n_surfaces];           ///< tr(m_k): plastic volume change per unit multiplier
  double coupling[n_surfaces][n_surfaces]; ///< a_k . D m_j, Pa

  PrincipalSurfaces(double alpha1, double alpha2, double n_phi, double n_psi, double shear_offset,
                    double tension_limit)
  {
    double m[n_surfaces][3] = {};
    for (int k = 0; k < n_surfaces; ++k)
    {
      normal[k][0] = normal[k][1] = normal[k][2] = 0.0;
      if (k < n_shear_surfaces)
      {
        const int least = shear_axes[k][0], greatest = shear_axes[k][1];
        normal[k][least] = m[k][least] = -1.0;
        normal[k][greatest] = n_phi;
        m[k][greatest] = n_psi;
        offset[k] = shear_offset;
      }
      else
      {
        const int axis = 2 - (k - tension_3); // tension_3, tension_2, tension_1
        normal[k][axis] = m[k][axis] = 1.0;
        offset[k] = tension_limit;
      }
      flow_trace[k] = m[k][0] + m[k][1] + m[k][2];
      for (int d = 0; d < 3; ++d)
        flow_stress[k][d] = alpha1 * m[k][d] + alpha2 * (m[k][(d + 1) % 3] + m[k][(d + 2) % 3]);
    }
    for (int k = 0; k < n_surfaces; ++k)
      for (int j = 0; j < n_surfaces; ++j)
        coupling[k][j] = normal[k][0] * flow_stress[j][0] + normal[k][1] * flow_stress[j][1] +
                         normal[k][2] * flow_stress[j][2];
  }

  double value(int k, const double* s) const
  {
    return normal[k][0] * s[0] + normal[k][1] * s[1] + normal[k][2] * s[2] - offset[k];
  }
};

/// Solves the n x n system a x = b (n <= max_active) by Gaussian
/// elimination with partial pivoting; false when a is (nearly) singular,
/// i.e. the surfaces do not meet in a single point.
bool solve_small_system(int n, double a[max_active][max_active], double* b, double* x)
{
  double largest = 0.0;
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c)
      largest = std::max(largest, std::abs(a[r][c]));
  for (int col = 0; col < n; ++col)
  {
    int pivot = col;
    for (int r = col + 1; r < n; ++r)
      if (std::abs(a[r][col]) > std::abs(a[pivot][col]))
        pivot = r;
    if (std::abs(a[pivot][col]) <= 1e-12 * largest)
      return false;
    if (pivot != col)
    {
      for (int c = 0; c < n; ++c)
        std::swap(a[col][c], a[pivot][c]);
      std::swap(b[col], b[pivot]);
    }
    for (int r = col + 1; r < n; ++r)
    {
      const double factor = a[r][col] / a[col][col];
      for (int c = col; c < n; ++c)
        a[r][c] -= factor * a[col][c];
      b[r] -= factor * b[col];
    }
  }
  for (int r = n - 1; r >= 0; --r)
  {
    double sum = b[r];
    for (int c = r + 1; c < n; ++c)
      sum -= a[r][c] * x[c];
    x[r] = sum / a[r][r];
  }
  return true;
}

/// Multipliers that put the stress on every surface of `set`, and that
/// stress; false when the surfaces do not meet in a point.
bool solve_active_set(const PrincipalSurfaces& y, const double* trial, const double* trial_value,
                      const int* set, int n, double* multiplier, double* s)
{
  double matrix[max_active][max_active], rhs[max_active];
  for (int r = 0; r < n; ++r)
  {
    rhs[r] = trial_value[set[r]];
    for (int c = 0; c < n; ++c)
      matrix[r][c] = y.coupling[set[r]][set[c]];
  }
  if (!solve_small_system(n, matrix, rhs, multiplier))
    return false;
  s[0] = trial[0];
  s[1] = trial[1];
  s[2] = trial[2];
  for (int r = 0; r < n; ++r)
    for (int d = 0; d < 3; ++d)
      s[d] -= multiplier[r] * y.flow_stress[set[r]][d];
  return true;
}

/// The surface outside `set` that s violates most, measured by the
/// multiplier it alone would need; -1 if s is admissible. Tension planes
/// come first, as in the return itself (beyond the cut-off the tensile
/// correction is made before the shear one).
int most_violated(const PrincipalSurfaces& y, const double* s, double tolerance, const int* set,
                  int n)
{
  int worst = -1;
  double worst_multiplier = 0.0;
  for (int i = 0; i < n_surfaces; ++i)
  {
    const int k = (i + tension_3) % n_surfaces; // tension planes first
    if (k == 0 && worst >= 0)
      break;
    if (std::find(set, set + n, k) != set + n)
      continue;
    const double value = y.value(k, s);
    if (value > tolerance && value / y.coupling[k][k] > worst_multiplier)
    {
      worst_multiplier = value / y.coupling[k][k];
      worst = k;
    }
  }
  return worst;
}

/// Plastic correction of the ordered trial principal stresses, starting
/// from the surface `first`: active-set iteration (solve for the
/// multipliers of the active surfaces, let one with a negative multiplier
/// go, take in the most violated other one) until the stress is admissible.
/// Should that not settle (about one plastic trial in a thousand in random
/// tests, all far beyond the apex or the tension corner, where the set
/// would have to trade a plane for another), every set of up to three
/// surfaces is tried and the first that is admissible with non-negative
/// multipliers is taken.
/// Returns the corrected principal stresses, the plastic volume change and
/// the "now" flags.
void return_to_surfaces(const PrincipalSurfaces& y, const double* trial, double tolerance,
                        int first, double* corrected, double& plastic_volumetric,
                        unsigned char& flags_now)
{
  double trial_value[n_surfaces];
  for (int k = 0; k < n_surfaces; ++k)
    trial_value[k] = y.value(k, trial);

  int active[max_active] = {first};
  int n_active = 1;
  double multiplier[max_active] = {0.0};
  bool settled = false;
  for (int pass = 0; pass < 4 * max_active; ++pass)
  {
    if (!solve_active_set(y, trial, trial_value, active, n_active, multiplier, corrected))
      break;
    int most_negative = -1;
    for (int r = 0; r < n_active; ++r)
      if (multiplier[r] < 0.0 && (most_negative < 0 || multiplier[r] < multiplier[most_negative]))
        most_negative = r;
    if (most_negative >= 0)
    {
      if (n_active == 1)
        break;
      active[most_negative] = active[--n_active];
      continue;
    }
    const int next = most_violated(y, corrected, tolerance, active, n_active);
    if (next < 0)
    {
      settled = true;
      break;
    }
    if (n_active == max_active)
      break;
    active[n_active++] = next;
  }

  if (!settled)
  {
    // Sets of one, two and three surfaces, fewest first, tension planes
    // before shear planes (where several sets give the same stress, as at
    // the apex, the failure is then reported as tensile).
    for (int size = 1; size <= max_active && !settled; ++size)
      for (unsigned int bits = 1; bits < (1u << n_surfaces) && !settled; ++bits)
      {
        if (__builtin_popcount(bits) != size)
          continue;
        n_active = 0;
        for (int b = 0; b < n_surfaces; ++b)
          if (bits & (1u << b))
            active[n_active++] = (b + tension_3) % n_surfaces;
        if (!solve_active_set(y, trial, trial_value, active, n_active, multiplier, corrected))
          continue;
        settled =
            std::all_of(multiplier, multiplier + n_active, [](double m) { return m >= 0.0; }) &&
            most_violated(y, corrected, tolerance, active, n_active) < 0;
      }
  }

  plastic_volumetric = 0.0;
  flags_now = zone_elastic;
  // Not met in 2e6 random trials (all materials, all regions); should it
  // happen, the trial stress is left rather than a guess.
  if (!settled)
  {
    std::copy(trial, trial + 3, corrected);
    return;
  }
  for (int r = 0; r < n_active; ++r)
  {
    const int k = active[r];
    plastic_volumetric += multiplier[r] * y.flow_trace[k];
    if (multiplier[r] > 0.0)
      flags_now |= k < n_shear_surfaces ? shear_now : tension_now;
  }
}

} // namespace

void elastic_update(const ZoneMaterial& material, StressBatch& batch)
{
  const double g = material.shear_modulus;
  const double lame_lambda = material.bulk_modulus - 2.0 * g / 3.0, two_g = 2.0 * g;
  const double* de = batch.strain_increment;
  double* s = batch.stress;
  for (unsigned int i = 0; i < batch.size; ++i)
    add_elastic_increment(lame_lambda, two_g, de + 6 * i, s + 6 * i);
}

void mohr_coulomb_update(const ZoneMaterial& material, StressBatch& batch)
{
  const double deg = M_PI / 180.0;
  const double k = material.bulk_modulus, g = material.shear_modulus;
  const double lame_lambda = k - 2.0 * g / 3.0, two_g = 2.0 * g;
  const double alpha1 = k + 4.0 * g / 3.0, alpha2 = k - 2.0 * g / 3.0;
  const double phi = material.friction_angle * deg, psi = material.dilation_angle * deg;
  const double n_phi = (1.0 + std::sin(phi)) / (1.0 - std::sin(phi));
  const double n_psi = (1.0 + std::sin(psi)) / (1.0 - std::sin(psi));
  const double c = material.cohesion;
  const double shear_offset = 2.0 * c * std::sqrt(n_phi); // Pa
  // The shear surface closes at its apex s1 = s2 = s3 = c / tan(phi): a
  // larger tensile strength could never be reached.
  const double tension_limit = phi > 0.0 ? std::min(material.tensile_strength, c / std::tan(phi))
                                         : material.tensile_strength;
  const PrincipalSurfaces surfaces(alpha1, alpha2, n_phi, n_psi, shear_offset, tension_limit);

  // Which surface the return starts from when the trial is beyond the
  // shear plane, the tension plane or both. In the (s1, s3) plane the two
  // lines f_s = 0 and f_t = 0 meet at P = (sigma_p, sigma_t), with
  // sigma_p = sigma_t N_phi - 2c sqrt(N_phi). Beyond P the shear line runs
  // along u = (N_phi, 1) / sqrt(1 + N_phi^2) (s3 rising) and the tension
  // line along v = (-1, 0) (s1 falling); both are violated in the wedge
  // between them. Its bisector u + v is parallel to
  // (N_phi - sqrt(1 + N_phi^2), 1), hence orthogonal to (alpha_p, 1) with
  // alpha_p = 1 / (sqrt(1 + N_phi^2) - N_phi) = sqrt(1 + N_phi^2) + N_phi,
  // and the bisector through P is
  //   h = s3 - sigma_t + alpha_p (s1 - sigma_p) = 0.
  // h > 0 lies on the tension side (e.g. straight above P, where only the
  // tension cut-off is crossed by s3), h <= 0 on the shear side.
  const double sigma_p = tension_limit * n_phi - shear_offset;
  const double alpha_p = std::sqrt(1.0 + n_phi * n_phi) + n_phi;

  // W zones at once, one per lane: elastic trial, the cheap bound and, for
  // groups that may yield, the principal stresses and directions of every
  // lane without branches. Only the zones beyond a surface then take the
  // (scalar) return.
  constexpr unsigned int W = lane_count;
  const Lanes lanes_lambda = broadcast(lame_lambda), lanes_two_g = broadcast(two_g);
  const double* de = batch.strain_increment;
  for (unsigned int k0 = 0; k0 < batch.size; k0 += W)
  {
    const unsigned int count = std::min(W, batch.size - k0);
    // The group's zones lane by lane (lanes past the end repeat the last
    // zone and are not written back).
    alignas(64) double stress[6][W], increment[6][W];
    for (unsigned int l = 0; l < W; ++l)
    {
      const unsigned int i = k0 + std::min(l, count - 1);
      for (int c = 0; c < 6; ++c)
      {
        stress[c][l] = batch.stress[6 * i + c];
        increment[c][l] = de[6 * i + c];
      }
    }
    Lanes s[6], e[6];
    for (int c = 0; c < 6; ++c)
    {
      s[c] = load_lanes(stress[c]);
      e[c] = load_lanes(increment[c]);
    }
    // Eq. 59, as add_elastic_increment.
    const Lanes volumetric = lanes_lambda * (e[0] + e[1] + e[2]);
    for (int c = 0; c < 3; ++c)
      s[c] += volumetric + lanes_two_g * e[c];
    for (int c = 3; c < 6; ++c)
      s[c] += lanes_two_g * e[c];

    // Cheap bounds first: every principal stress lies within r of the mean
    // stress, with r = sqrt(2/3) |deviator| (the largest share one of three
    // numbers summing to zero can take of their squares is 2/3). Groups
    // clearly inside the yield surface skip the eigen solve.
    const Lanes mean = (s[0] + s[1] + s[2]) / 3.0;
    const Lanes d0 = s[0] - mean, d1 = s[1] - mean, d2 = s[2] - mean;
    const Lanes radius =
        lane_sqrt(2.0 / 3.0 *
                  (d0 * d0 + d1 * d1 + d2 * d2 + 2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5])));
    const Lanes lowest = mean - radius, highest = mean + radius;
    const LaneMask maybe_plastic =
        (lowest - n_phi * highest + shear_offset <= 0.0) | (highest > tension_limit);

    LaneMask beyond = LaneMask{};
    Lanes trial[3], axes[3][3], tolerance, shear_excess, tension_excess;
    if (any(maybe_plastic))
    {
      // Principal stresses and directions in closed form, all lanes.
      symmetric_eigen3(s, trial, axes); // ascending: s1 <= s2 <= s3
      tolerance = 1e-12 * (lane_abs(trial[0]) + lane_abs(trial[2]) + shear_offset +
                           std::abs(tension_limit));
      // With ordered values no other plane is violated unless one of these is.
      shear_excess = n_phi * trial[2] - trial[0] - shear_offset; // surfaces.value(shear_13)
      tension_excess = trial[2] - tension_limit;                 // surfaces.value(tension_3)
      beyond = maybe_plastic & ((shear_excess > tolerance) | (tension_excess > tolerance));
    }
    for (int c = 0; c < 6; ++c)
      store_lanes(stress[c], s[c]);

    for (unsigned int l = 0; l < count; ++l)
    {
      const unsigned int i = k0 + l;
      double plastic_volumetric = 0.0;
      unsigned char flags_now = zone_elastic;
      if (beyond[l])
      {
        const double principal[3] = {trial[0][l], trial[1][l], trial[2][l]};
        const double h = principal[2] - tension_limit + alpha_p * (principal[0] - sigma_p);
        const bool tension_side = tension_excess[l] > tolerance[l];
        const int first =
            tension_side && (h > 0.0 || shear_excess[l] <= tolerance[l]) ? tension_3 : shear_13;
        double corrected[3];
        return_to_surfaces(surfaces, principal, tolerance[l], first, corrected, plastic_volumetric,
                           flags_now);
        // Back to the zone axes: the principal directions do not change, so
        // only the change of each principal stress is rotated (this keeps
        // the full accuracy of the trial stress in the parts not corrected).
        for (int p = 0; p < 3; ++p)
        {
          const double change = corrected[p] - principal[p];
          const double x = axes[p][0][l], y = axes[p][1][l], z = axes[p][2][l];
          stress[0][l] += change * x * x;
          stress[1][l] += change * y * y;
          stress[2][l] += change * z * z;
          stress[3][l] += change * x * y;
          stress[4][l] += change * y * z;
          stress[5][l] += change * z * x;
        }
      }
      for (int c = 0; c < 6; ++c)
        batch.stress[6 * i + c] = stress[c][l];
      if (batch.plastic_volumetric)
        batch.plastic_volumetric[i] = plastic_volumetric;
      if (batch.state)
      {
        const unsigned char past = (batch.state[i] & (shear_past | tension_past)) |
                                   (flags_now & shear_now ? shear_past : 0) |
                                   (flags_now & tension_now ? tension_past : 0);
        batch.state[i] = past | flags_now;
      }
    }
  }
}

void apply_zone_model(const ZoneMaterial& material, StressBatch& batch)
{
  switch (material.model)
  {
  case ZoneModel::elastic:
    elastic_update(material, batch);
    return;
  case ZoneModel::mohr_coulomb:
    mohr_coulomb_update(material, batch);
    return;
  }
}

} // namespace talus
