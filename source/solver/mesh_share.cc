#include <talus/contact/cell_partition.h>
#include <talus/solver/mesh_share.h>

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace talus
{

std::vector<unsigned int> gridpoint_owners(const TetMesh& mesh, const Box& domain, double cell_size,
                                           unsigned int ranks, const std::vector<char>* removed)
{
  const unsigned int ng = mesh.n_gridpoints();
  std::vector<Vec3> point(ng);
  std::vector<double> work(ng, 0.0);
  for (unsigned int p = 0; p < ng; ++p)
    point[p] = Vec3(mesh.position[3 * p], mesh.position[3 * p + 1], mesh.position[3 * p + 2]);
  for (unsigned int z = 0; z < mesh.n_zones(); ++z)
    if (removed == nullptr || !(*removed)[z])
      for (unsigned int p : mesh.zone_gridpoint[z])
        work[p] += 0.25;
  const CellPartition partition(domain, domain.lo, Vec3::Constant(cell_size), point, work, ranks);
  std::vector<unsigned int> owner(ng);
  for (unsigned int p = 0; p < ng; ++p)
    owner[p] = partition.owner(point[p]);
  return owner;
}

MeshShare share_mesh(const TetMesh& whole, const std::vector<unsigned int>& owner,
                     unsigned int rank, unsigned int ranks, MPI_Comm comm,
                     const std::vector<char>* also_ghosts)
{
  const unsigned int ng = whole.n_gridpoints(), nz = whole.n_zones();
  // Numbers in the whole model's vectors: rank by rank, each rank's
  // gridpoints in the mesh's order.
  std::vector<unsigned int> count(ranks, 0), number(ng);
  for (unsigned int g = 0; g < ng; ++g)
    ++count[owner[g]];
  std::vector<unsigned int> offset(ranks, 0);
  for (unsigned int r = 1; r < ranks; ++r)
    offset[r] = offset[r - 1] + count[r - 1];
  std::fill(count.begin(), count.end(), 0);
  for (unsigned int g = 0; g < ng; ++g)
    number[g] = offset[owner[g]] + count[owner[g]]++;

  // A zone is held when one of its nodes is owned (a 10-node zone's edge
  // midpoints count); a hexahedral zone's ten tetrahedra go together, since
  // its mixed discretization averages over them (eqs. 64-67).
  const bool quadratic = whole.quadratic();
  std::vector<char> held_zone(nz, 0), held_gridpoint(ng, 0);
  for (unsigned int z = 0; z < nz; ++z)
  {
    for (unsigned int g : whole.zone_gridpoint[z])
      held_zone[z] |= owner[g] == rank;
    if (quadratic)
      for (unsigned int g : whole.zone_edge_gridpoint[z])
        held_zone[z] |= owner[g] == rank;
  }
  for (unsigned int h = 0; h < whole.n_hexes(); ++h)
  {
    char held = 0;
    for (unsigned int g : whole.hex_gridpoint[h])
      held |= owner[g] == rank;
    for (unsigned int k = 0; k < TetMesh::tets_per_hex; ++k)
      held_zone[whole.hex_first_zone[h] + k] = held;
  }
  for (unsigned int z = 0; z < nz; ++z)
    if (held_zone[z])
    {
      for (unsigned int g : whole.zone_gridpoint[z])
        held_gridpoint[g] = 1;
      if (quadratic)
        for (unsigned int g : whole.zone_edge_gridpoint[z])
          held_gridpoint[g] = 1;
    }
  if (also_ghosts != nullptr)
    for (unsigned int g = 0; g < ng; ++g)
      held_gridpoint[g] |= (*also_ghosts)[g];
  MeshShare s;
  s.mesh.ten_node = quadratic; // also with no zone of this rank's
  s.share.comm = comm;
  std::vector<std::pair<unsigned int, unsigned int>> ghosts; // number, gridpoint
  for (unsigned int g = 0; g < ng; ++g)
    if (owner[g] == rank)
      s.gridpoint.push_back(g);
    else if (held_gridpoint[g])
      ghosts.emplace_back(number[g], g);
  s.share.n_owned = static_cast<unsigned int>(s.gridpoint.size());
  std::sort(ghosts.begin(), ghosts.end());
  for (const auto& [n, g] : ghosts)
  {
    s.share.ghost_index.push_back(n);
    s.gridpoint.push_back(g);
  }
  s.share.whole_gridpoint = s.gridpoint;
  std::vector<int> local(ng, -1);
  for (unsigned int i = 0; i < s.gridpoint.size(); ++i)
  {
    local[s.gridpoint[i]] = static_cast<int>(i);
    for (int d = 0; d < 3; ++d)
      s.mesh.position.push_back(whole.position[3 * s.gridpoint[i] + d]);
    s.mesh.gridpoint_block.push_back(whole.gridpoint_block[s.gridpoint[i]]);
  }
  for (unsigned int z = 0; z < nz; ++z)
    if (held_zone[z])
    {
      std::array<unsigned int, 4> corners;
      for (int k = 0; k < 4; ++k)
        corners[k] = static_cast<unsigned int>(local[whole.zone_gridpoint[z][k]]);
      s.mesh.zone_gridpoint.push_back(corners);
      s.mesh.zone_block.push_back(whole.zone_block[z]);
      s.zone.push_back(z);
      if (quadratic)
      {
        std::array<unsigned int, 6> edges;
        for (int k = 0; k < 6; ++k)
          edges[k] = static_cast<unsigned int>(local[whole.zone_edge_gridpoint[z][k]]);
        s.mesh.zone_edge_gridpoint.push_back(edges);
      }
    }
  std::vector<int> local_zone(nz, -1);
  for (unsigned int z = 0, k = 0; z < nz; ++z)
    if (held_zone[z])
      local_zone[z] = static_cast<int>(k++);
  for (unsigned int h = 0; h < whole.n_hexes(); ++h)
    if (held_zone[whole.hex_first_zone[h]])
    {
      std::array<unsigned int, 8> corners;
      for (int k = 0; k < 8; ++k)
        corners[k] = static_cast<unsigned int>(local[whole.hex_gridpoint[h][k]]);
      s.mesh.hex_gridpoint.push_back(corners);
      s.mesh.hex_first_zone.push_back(
          static_cast<unsigned int>(local_zone[whole.hex_first_zone[h]]));
    }
  // The second overlay's boundary triangles (no zone named): those with an
  // owned corner, whose hexahedron is then held, and so all three corners.
  for (unsigned int f = 0; f < whole.second_overlay_face_gridpoint.size(); ++f)
  {
    const auto& face = whole.second_overlay_face_gridpoint[f];
    if (owner[face[0]] == rank || owner[face[1]] == rank || owner[face[2]] == rank)
    {
      std::array<unsigned int, 3> corners;
      for (int k = 0; k < 3; ++k)
        corners[k] = static_cast<unsigned int>(local[face[k]]);
      s.mesh.second_overlay_face_gridpoint.push_back(corners);
      s.second_overlay_face.push_back(f);
    }
  }
  for (unsigned int f = 0; f < whole.n_faces(); ++f)
    if (held_zone[whole.face_zone[f]])
    {
      std::array<unsigned int, 3> corners;
      for (int k = 0; k < 3; ++k)
        corners[k] = static_cast<unsigned int>(local[whole.face_gridpoint[f][k]]);
      s.mesh.face_gridpoint.push_back(corners);
      s.mesh.face_zone.push_back(static_cast<unsigned int>(local_zone[whole.face_zone[f]]));
      s.face.push_back(f);
    }
  return s;
}

} // namespace talus
