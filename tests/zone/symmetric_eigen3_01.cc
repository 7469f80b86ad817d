// symmetric_eigen3 (closed-form eigen-decomposition of a symmetric 3x3)
// against tensors built from known values and random rotations: general
// values, an exactly repeated pair (both ends), pairs a relative 1e-6,
// 1e-10 and 1e-14 apart, a nearly isotropic tensor, a large mean with a
// small deviator (stresses of deep rock), diagonal and zero tensors. For
// each family, over many random rotations: the largest error of the values
// relative to |t| (the largest |value|), the largest departure of the axes
// from orthonormal, and the largest error of the reconstruction
// sum_p value_p axis_p axis_p^T relative to |t|. The values must be ordered.

#include <talus/zone/symmetric_eigen3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

namespace
{
struct Errors
{
  double value = 0.0, orthonormal = 0.0, reconstruction = 0.0;
  bool ordered = true;
};

/// A random rotation (the columns of q), from a random unit quaternion.
void random_rotation(std::mt19937_64& rng, double (&q)[3][3])
{
  std::normal_distribution<double> normal;
  double w = normal(rng), x = normal(rng), y = normal(rng), z = normal(rng);
  const double s = 1.0 / std::sqrt(w * w + x * x + y * y + z * z);
  w *= s, x *= s, y *= s, z *= s;
  q[0][0] = 1 - 2 * (y * y + z * z), q[0][1] = 2 * (x * y - z * w), q[0][2] = 2 * (x * z + y * w);
  q[1][0] = 2 * (x * y + z * w), q[1][1] = 1 - 2 * (x * x + z * z), q[1][2] = 2 * (y * z - x * w);
  q[2][0] = 2 * (x * z - y * w), q[2][1] = 2 * (y * z + x * w), q[2][2] = 1 - 2 * (x * x + y * y);
}

void check_one(const double (&exact)[3], const double (&q)[3][3], Errors& e)
{
  // t = q diag(exact) q^T, as (xx, yy, zz, xy, yz, zx).
  double m[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      m[i][j] = q[i][0] * exact[0] * q[j][0] + q[i][1] * exact[1] * q[j][1] +
                q[i][2] * exact[2] * q[j][2];
  const double t[6] = {m[0][0], m[1][1], m[2][2], m[0][1], m[1][2], m[2][0]};
  double values[3], axes[3][3];
  talus::symmetric_eigen3(t, values, axes);
  double sorted[3] = {exact[0], exact[1], exact[2]};
  std::sort(sorted, sorted + 3);
  const double size = std::max({std::abs(sorted[0]), std::abs(sorted[2]), 1e-300});
  e.ordered = e.ordered && values[0] <= values[1] && values[1] <= values[2];
  for (int p = 0; p < 3; ++p)
    e.value = std::max(e.value, std::abs(values[p] - sorted[p]) / size);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
    {
      const double d = axes[a][0] * axes[b][0] + axes[a][1] * axes[b][1] + axes[a][2] * axes[b][2];
      e.orthonormal = std::max(e.orthonormal, std::abs(d - (a == b ? 1.0 : 0.0)));
      double r = 0.0;
      for (int p = 0; p < 3; ++p)
        r += values[p] * axes[p][a] * axes[p][b];
      e.reconstruction = std::max(e.reconstruction, std::abs(r - m[a][b]) / size);
    }
}

void family(const char* name, double a, double b, double c, std::mt19937_64& rng)
{
  Errors e;
  std::uniform_real_distribution<double> jitter(0.5, 1.5);
  for (int trial = 0; trial < 20000; ++trial)
  {
    double q[3][3];
    random_rotation(rng, q);
    // The same pattern at random scales and in random order.
    const double s = jitter(rng);
    double exact[3] = {a * s, b * s, c * s};
    std::shuffle(exact, exact + 3, rng);
    check_one(exact, q, e);
  }
  {
    // Unrotated (diagonal) too.
    const double identity[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const double exact[3] = {a, b, c};
    check_one(exact, identity, e);
  }
  const double limit = 1e-13;
  std::printf("%-34s values %s, ordered %s, axes orthonormal %s, reconstruction %s\n", name,
              e.value <= limit ? "OK" : "WRONG", e.ordered ? "OK" : "WRONG",
              e.orthonormal <= limit ? "OK" : "WRONG", e.reconstruction <= limit ? "OK" : "WRONG");
  if (e.value > limit || e.orthonormal > limit || e.reconstruction > limit)
    std::printf("  errors: values %.1e, orthonormal %.1e, reconstruction %.1e (limit %.0e)\n",
                e.value, e.orthonormal, e.reconstruction, limit);
}
} // namespace

int main()
{
  std::mt19937_64 rng(4);
  std::printf("Largest errors relative to |t| over 20001 rotations each, limit 1e-13:\n");
  family("general (-3e6, 1e5, 2e6)", -3e6, 1e5, 2e6, rng);
  family("general, one zero (-1, 0, 2)", -1.0, 0.0, 2.0, rng);
  family("repeated pair below (-5, -5, 1)", -5.0, -5.0, 1.0, rng);
  family("repeated pair above (-5, 1, 1)", -5.0, 1.0, 1.0, rng);
  family("pair 1e-6 apart", -5.0, -5.0 * (1 + 1e-6), 1.0, rng);
  family("pair 1e-10 apart", -5.0, 1.0, 1.0 + 1e-10, rng);
  family("pair 1e-14 apart", -5.0, 1.0, 1.0 + 1e-14, rng);
  family("nearly isotropic (1e-9 deviator)", -1e6, -1e6 * (1 + 1e-9), -1e6 * (1 - 1e-9), rng);
  family("isotropic", 7.0, 7.0, 7.0, rng);
  family("large mean, small deviator", -1e8 + 3e2, -1e8 - 1e2, -1e8 + 5e1, rng);
  family("uniaxial (0, 0, -1e6)", 0.0, 0.0, -1e6, rng);
  {
    double values[3], axes[3][3];
    const double zero[6] = {0, 0, 0, 0, 0, 0};
    talus::symmetric_eigen3(zero, values, axes);
    std::printf("zero tensor: values %g %g %g\n", values[0], values[1], values[2]);
  }
}
