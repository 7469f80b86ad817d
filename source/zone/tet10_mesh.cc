#include <talus/zone/tet10_kernel.h>
#include <talus/zone/tet10_mesh.h>

#include <algorithm>
#include <map>
#include <utility>

namespace talus
{

void make_quadratic(TetMesh& mesh)
{
  if (mesh.quadratic())
    return;
  // One midpoint gridpoint per edge, keyed by its two vertex gridpoints
  // (gridpoints belong to one block, so midpoints are never shared across
  // blocks).
  std::map<std::pair<unsigned int, unsigned int>, unsigned int> midpoint;
  const auto midpoint_of = [&](unsigned int a, unsigned int b)
  {
    const std::pair<unsigned int, unsigned int> key(std::min(a, b), std::max(a, b));
    const auto [it, fresh] = midpoint.emplace(key, mesh.n_gridpoints());
    if (fresh)
    {
      for (int d = 0; d < 3; ++d)
        mesh.position.push_back(0.5 * (mesh.position[3 * a + d] + mesh.position[3 * b + d]));
      mesh.gridpoint_block.push_back(mesh.gridpoint_block[a]);
    }
    return it->second;
  };
  mesh.ten_node = true;
  mesh.zone_edge_gridpoint.resize(mesh.n_zones());
  for (unsigned int z = 0; z < mesh.n_zones(); ++z)
    for (int e = 0; e < 6; ++e)
      mesh.zone_edge_gridpoint[z][e] = midpoint_of(mesh.zone_gridpoint[z][tet10_edge[e][0]],
                                                   mesh.zone_gridpoint[z][tet10_edge[e][1]]);
  // Each boundary triangle a b c into four with the same orientation.
  std::vector<std::array<unsigned int, 3>> faces;
  std::vector<unsigned int> face_zone;
  for (unsigned int f = 0; f < mesh.n_faces(); ++f)
  {
    const auto [a, b, c] = mesh.face_gridpoint[f];
    const unsigned int ab = midpoint_of(a, b), bc = midpoint_of(b, c), ca = midpoint_of(c, a);
    const std::array<unsigned int, 3> four[4] = {
        {{a, ab, ca}}, {{ab, b, bc}}, {{ca, bc, c}}, {{ab, bc, ca}}};
    for (const std::array<unsigned int, 3>& t : four)
    {
      faces.push_back(t);
      face_zone.push_back(mesh.face_zone[f]);
    }
  }
  mesh.face_gridpoint = std::move(faces);
  mesh.face_zone = std::move(face_zone);
}

namespace
{
/// Barycentric coordinates of the ten nodes.
double node_bary(unsigned int node, unsigned int m)
{
  if (node < 4)
    return node == m ? 1.0 : 0.0;
  const unsigned int e = node - 4;
  return tet10_edge[e][0] == m || tet10_edge[e][1] == m ? 0.5 : 0.0;
}

/// Weights of the four Gauss points' values at the centroid of
/// sub-tetrahedron c: the linear function that is 1 at Gauss point q and 0
/// at the others is (L_q - a) / (b - a).
void subcell_weights(unsigned int c, double w[4])
{
  for (unsigned int q = 0; q < 4; ++q)
  {
    double L = 0.0;
    for (unsigned int k = 0; k < 4; ++k)
      L += 0.25 * node_bary(tet10_subcell[c][k], q);
    w[q] = (L - tet10_gauss_a) / (tet10_gauss_b - tet10_gauss_a);
  }
}
} // namespace

std::vector<double> tet10_subcell_values(const std::vector<double>& gauss_values,
                                         unsigned int components)
{
  const std::size_t nz = gauss_values.size() / (4 * components);
  std::vector<double> out(8 * components * nz, 0.0);
  for (unsigned int c = 0; c < 8; ++c)
  {
    double w[4];
    subcell_weights(c, w);
    for (std::size_t z = 0; z < nz; ++z)
      for (unsigned int q = 0; q < 4; ++q)
        for (unsigned int i = 0; i < components; ++i)
          out[(8 * z + c) * components + i] += w[q] * gauss_values[(4 * z + q) * components + i];
  }
  return out;
}

std::vector<unsigned char> tet10_subcell_flags(const std::vector<unsigned char>& gauss_flags)
{
  const std::size_t nz = gauss_flags.size() / 4;
  std::vector<unsigned char> out(8 * nz);
  for (unsigned int c = 0; c < 8; ++c)
  {
    double w[4];
    subcell_weights(c, w);
    unsigned int nearest = 0;
    for (unsigned int q = 1; q < 4; ++q)
      if (w[q] > w[nearest])
        nearest = q;
    for (std::size_t z = 0; z < nz; ++z)
      out[8 * z + c] = gauss_flags[4 * z + nearest];
  }
  return out;
}

} // namespace talus
