#include <talus/base/exceptions.h>
#include <talus/zone/hex_mesher.h>

#include <algorithm>
#include <map>

namespace talus
{

namespace
{
/// The two five-tetrahedron splits of a hexahedron, by local corner
/// (i + 2j + 4k). Even split: the central tetrahedron on the corners of
/// even parity (0, 3, 5, 6) and one tetrahedron at each odd corner with its
/// three neighbours; odd split: the mirror image.
constexpr unsigned int even_split[5][4] = {
    {0, 3, 5, 6}, {1, 0, 3, 5}, {2, 0, 3, 6}, {4, 0, 5, 6}, {7, 3, 5, 6}};
constexpr unsigned int odd_split[5][4] = {
    {1, 2, 4, 7}, {0, 1, 2, 4}, {3, 1, 2, 7}, {5, 1, 4, 7}, {6, 2, 4, 7}};

/// The faces that appear once among zones [first, last): the block
/// boundary of one overlay, each turned to face away from its zone.
void boundary_faces(const TetMesh& mesh, unsigned int first, unsigned int last, unsigned int stride,
                    unsigned int offset, std::vector<std::array<unsigned int, 3>>& faces,
                    std::vector<unsigned int>* face_zone)
{
  const auto P = [&](unsigned int g)
  { return Vec3(mesh.position[3 * g], mesh.position[3 * g + 1], mesh.position[3 * g + 2]); };
  static const int face_of[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  std::map<std::array<unsigned int, 3>, std::pair<unsigned int, int>> seen;
  for (unsigned int hex = first; hex < last; hex += stride)
    for (unsigned int z = hex + offset; z < hex + offset + 5; ++z)
      for (int f = 0; f < 4; ++f)
      {
        std::array<unsigned int, 3> key{{mesh.zone_gridpoint[z][face_of[f][0]],
                                        mesh.zone_gridpoint[z][face_of[f][1]],
                                        mesh.zone_gridpoint[z][face_of[f][2]]}};
        std::sort(key.begin(), key.end());
        auto [it, fresh] = seen.emplace(key, std::make_pair(z, f));
        if (!fresh)
          seen.erase(it);
      }
  for (const auto& [key, where] : seen)
  {
    const auto& t = mesh.zone_gridpoint[where.first];
    std::array<unsigned int, 3> face{{t[face_of[where.second][0]], t[face_of[where.second][1]],
                                     t[face_of[where.second][2]]}};
    const Vec3 n = (P(face[1]) - P(face[0])).cross(P(face[2]) - P(face[0]));
    if (n.dot(P(face[0]) - P(t[where.second])) < 0.0)
      std::swap(face[1], face[2]);
    faces.push_back(face);
    if (face_zone != nullptr)
      face_zone->push_back(where.first);
  }
}
} // namespace

void append_hex_mixed_brick(TetMesh& mesh, const Box& box, const std::array<unsigned int, 3>& n,
                            unsigned int block)
{
  const auto P = [&](unsigned int g)
  { return Vec3(mesh.position[3 * g], mesh.position[3 * g + 1], mesh.position[3 * g + 2]); };
  // Gridpoints, lexicographic (x fastest).
  const unsigned int offset = mesh.n_gridpoints();
  const auto gridpoint = [&](unsigned int i, unsigned int j, unsigned int k)
  { return offset + i + (n[0] + 1) * (j + (n[1] + 1) * k); };
  for (unsigned int k = 0; k <= n[2]; ++k)
    for (unsigned int j = 0; j <= n[1]; ++j)
      for (unsigned int i = 0; i <= n[0]; ++i)
      {
        const unsigned int ijk[3] = {i, j, k};
        for (int d = 0; d < 3; ++d)
          mesh.position.push_back(ijk[d] == n[d] ? box.hi[d]
                                                 : box.lo[d] + (box.hi[d] - box.lo[d]) * ijk[d] /
                                                                   static_cast<double>(n[d]));
        mesh.gridpoint_block.push_back(block);
      }
  const unsigned int first_zone = mesh.n_zones();
  for (unsigned int k = 0; k < n[2]; ++k)
    for (unsigned int j = 0; j < n[1]; ++j)
      for (unsigned int i = 0; i < n[0]; ++i)
      {
        std::array<unsigned int, 8> corner;
        for (unsigned int c = 0; c < 8; ++c)
          corner[c] = gridpoint(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1));
        mesh.hex_gridpoint.push_back(corner);
        mesh.hex_first_zone.push_back(mesh.n_zones());
        // First overlay: the central tetrahedron on globally even
        // gridpoints, which are the locally even corners when corner 0 is
        // even.
        const bool corner0_even = (i + j + k) % 2 == 0;
        for (const auto* split :
             {corner0_even ? even_split : odd_split, corner0_even ? odd_split : even_split})
          for (int t = 0; t < 5; ++t)
          {
            std::array<unsigned int, 4> tet{{corner[split[t][0]], corner[split[t][1]],
                                            corner[split[t][2]], corner[split[t][3]]}};
            if ((P(tet[1]) - P(tet[0])).dot((P(tet[2]) - P(tet[0])).cross(P(tet[3]) - P(tet[0]))) <
                0.0)
              std::swap(tet[1], tet[2]);
            mesh.zone_gridpoint.push_back(tet);
            mesh.zone_block.push_back(block);
          }
      }
  const unsigned int last_zone = mesh.n_zones();
  boundary_faces(mesh, first_zone, last_zone, TetMesh::tets_per_hex, 0, mesh.face_gridpoint,
                 &mesh.face_zone);
  boundary_faces(mesh, first_zone, last_zone, TetMesh::tets_per_hex, 5,
                 mesh.second_overlay_face_gridpoint, nullptr);
}

} // namespace talus
