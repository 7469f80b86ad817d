#include <talus/zone/hex_mixed.h>

namespace talus
{

namespace
{
constexpr unsigned int G = TetMesh::tets_per_hex; ///< the averaging group: both overlays
} // namespace

void hex_mixed_average_strain(unsigned int n, double* de, const double* volume)
{
  for (unsigned int first = 0; first < n; first += G)
  {
    // Eq. 62: the volume-weighted first invariant of the group.
    double sum = 0.0, total = 0.0;
    for (unsigned int z = first; z < first + G; ++z)
    {
      sum += (de[6 * z] + de[6 * z + 1] + de[6 * z + 2]) * volume[z];
      total += volume[z];
    }
    const double mean = sum / total;
    // Eq. 63: deviatoric part kept, first invariant replaced.
    for (unsigned int z = first; z < first + G; ++z)
    {
      const double shift = (mean - (de[6 * z] + de[6 * z + 1] + de[6 * z + 2])) / 3.0;
      for (int c = 0; c < 3; ++c)
        de[6 * z + c] += shift;
    }
  }
}

void hex_mixed_average_mean_stress(unsigned int n, double* stress, const double* volume)
{
  for (unsigned int first = 0; first < n; first += G)
  {
    // Eq. 66: the volume-weighted mean stress of the group.
    double sum = 0.0, total = 0.0;
    for (unsigned int z = first; z < first + G; ++z)
    {
      sum += (stress[6 * z] + stress[6 * z + 1] + stress[6 * z + 2]) * volume[z];
      total += volume[z];
    }
    const double mean = sum / (3.0 * total);
    // Eq. 67: deviatoric stress kept, mean stress replaced.
    for (unsigned int z = first; z < first + G; ++z)
    {
      const double shift = mean - (stress[6 * z] + stress[6 * z + 1] + stress[6 * z + 2]) / 3.0;
      for (int c = 0; c < 3; ++c)
        stress[6 * z + c] += shift;
    }
  }
}

void hex_mixed_overlay_weight(unsigned int n, double* volume)
{
  for (unsigned int z = 0; z < n; ++z)
    volume[z] *= 0.5;
}

std::vector<char> zones_in_hexes(const TetMesh& mesh)
{
  std::vector<char> in(mesh.n_zones(), 0);
  for (unsigned int first : mesh.hex_first_zone)
    for (unsigned int z = first; z < first + TetMesh::tets_per_hex; ++z)
      in[z] = 1;
  return in;
}

std::vector<double> hex_zone_stress(const TetMesh& mesh, const std::vector<double>& x,
                                    const std::vector<double>& stress)
{
  std::vector<double> out(6 * mesh.n_hexes(), 0.0);
  for (unsigned int h = 0; h < mesh.n_hexes(); ++h)
  {
    double total = 0.0;
    for (unsigned int z = mesh.hex_first_zone[h];
         z < mesh.hex_first_zone[h] + TetMesh::tets_per_hex; ++z)
    {
      const auto& t = mesh.zone_gridpoint[z];
      double e[3][3];
      for (int a = 0; a < 3; ++a)
        for (int d = 0; d < 3; ++d)
          e[a][d] = x[3 * t[a + 1] + d] - x[3 * t[0] + d];
      const double V = (e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                        e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                        e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) /
                       6.0;
      for (int c = 0; c < 6; ++c)
        out[6 * h + c] += V * stress[6 * z + c];
      total += V;
    }
    for (int c = 0; c < 6; ++c)
      out[6 * h + c] /= total;
  }
  return out;
}

} // namespace talus
