#include <talus/zone/nodal_mixed.h>

#include <cstring>
#if defined(__FMA__)
#include <immintrin.h>
#endif

namespace talus
{

void add_volume_weighted(const TetMesh& mesh, unsigned int first, unsigned int n,
                         const double* value, const double* volume, double* weighted_sum)
{
  for (unsigned int k = 0; k < n; ++k)
  {
    const double vk = value[k], V = volume[k];
    if (vk == 0.0)
      continue; // adds nothing (x + 0 = x, and +0 + -0 = +0)
    for (unsigned int g : mesh.zone_gridpoint[first + k])
      weighted_sum[g] = multiply_add(vk, V, weighted_sum[g]);
  }
}

void add_volume_weighted_pairs(const TetMesh& mesh, unsigned int first, unsigned int n,
                               const double* value, const double* volume, double* pairs)
{
  // (a, b) += (value, 1) V in one multiply-add: the second lane's product
  // is exact, so it rounds as b + V, the first as multiply_add(value, V, a).
  typedef double Pair __attribute__((vector_size(2 * sizeof(double))));
  for (unsigned int k = 0; k < n; ++k)
  {
    const Pair weight = {value[k], 1.0}, V = {volume[k], volume[k]};
    for (unsigned int g : mesh.zone_gridpoint[first + k])
    {
      Pair sum;
      std::memcpy(&sum, pairs + 2 * std::size_t(g), sizeof sum);
#if defined(__FMA__)
      sum = (Pair)_mm_fmadd_pd((__m128d)weight, (__m128d)V, (__m128d)sum);
#else
      sum = weight * V + sum; // no fused multiply-add on this machine
#endif
      std::memcpy(pairs + 2 * std::size_t(g), &sum, sizeof sum);
    }
  }
}

void average_pairs(const unsigned int* gridpoints, unsigned int count, double* pairs)
{
  for (unsigned int k = 0; k < count; ++k)
  {
    double* pair = pairs + 2 * std::size_t(gridpoints[k]);
    if (pair[1] > 0.0)
      pair[0] /= pair[1];
  }
}

void divide_by_pair_volume(const unsigned int* gridpoints, unsigned int count, double* weighted_sum,
                           const double* pairs)
{
  for (unsigned int k = 0; k < count; ++k)
  {
    const std::size_t g = gridpoints[k];
    if (pairs[2 * g + 1] > 0.0)
      weighted_sum[g] /= pairs[2 * g + 1];
  }
}

void replace_volumetric_strain(const TetMesh& mesh, unsigned int first, unsigned int n,
                               const double* average_pairs, double* strain_increment, double* own)
{
  for (unsigned int k = 0; k < n; ++k)
  {
    double* de = strain_increment + 6 * k;
    const double volumetric = (de[0] + de[1] + de[2]) / 3.0;
    if (own != nullptr)
      own[k] = volumetric;
    const double shift = corner_mean(mesh, first + k, average_pairs, 2) - volumetric;
    for (int c = 0; c < 3; ++c)
      de[c] += shift;
  }
}

double replaced_strain_work(unsigned int n, const double* own, const double* strain_increment,
                            const double* stress, const double* volume, double b)
{
  // Four sums side by side: one would wait for each add in turn.
  double work[4] = {0.0, 0.0, 0.0, 0.0};
  for (unsigned int k = 0; k < n; ++k)
  {
    const double* de = strain_increment + 6 * k;
    const double* s = stress + 6 * k;
    const double replaced = de[0] + de[1] + de[2];
    const double p = (s[0] + s[1] + s[2]) / 3.0 - b * replaced;
    work[k % 4] += volume[k] * p * (3.0 * own[k] - replaced);
  }
  return (work[0] + work[1]) + (work[2] + work[3]);
}

} // namespace talus
