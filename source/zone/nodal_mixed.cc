#include <talus/zone/nodal_mixed.h>

namespace talus
{

void add_volume_weighted(const TetMesh& mesh, unsigned int first, unsigned int n,
                         const double* value, const double* volume, double* weighted_sum,
                         double* volume_sum)
{
  for (unsigned int k = 0; k < n; ++k)
  {
    const double vk = value[k], V = volume[k];
    if (volume_sum == nullptr && vk == 0.0)
      continue; // adds nothing (x + 0 = x, and +0 + -0 = +0)
    for (unsigned int g : mesh.zone_gridpoint[first + k])
    {
      weighted_sum[g] = multiply_add(vk, V, weighted_sum[g]);
      if (volume_sum != nullptr)
        volume_sum[g] += V;
    }
  }
}

void divide_by_volume(unsigned int n_gridpoints, double* weighted_sum, const double* volume_sum)
{
  for (unsigned int g = 0; g < n_gridpoints; ++g)
    if (volume_sum[g] > 0.0)
      weighted_sum[g] /= volume_sum[g];
}

void divide_by_volume(const unsigned int* gridpoints, unsigned int count, double* weighted_sum,
                      const double* volume_sum)
{
  for (unsigned int k = 0; k < count; ++k)
  {
    const unsigned int g = gridpoints[k];
    if (volume_sum[g] > 0.0)
      weighted_sum[g] /= volume_sum[g];
  }
}

void replace_volumetric_strain(const TetMesh& mesh, unsigned int first, unsigned int n,
                               const double* gridpoint_average, double* strain_increment)
{
  for (unsigned int k = 0; k < n; ++k)
  {
    double* de = strain_increment + 6 * k;
    const double shift =
        corner_mean(mesh, first + k, gridpoint_average) - (de[0] + de[1] + de[2]) / 3.0;
    for (int c = 0; c < 3; ++c)
      de[c] += shift;
  }
}

} // namespace talus
