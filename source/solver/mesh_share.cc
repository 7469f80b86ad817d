#include <talus/contact/cell_partition.h>
#include <talus/solver/mesh_share.h>

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace talus
{

std::vector<unsigned int> gridpoint_owners(const TetMesh& mesh, const Box& domain, double cell_size,
                                           unsigned int ranks)
{
  const unsigned int ng = mesh.n_gridpoints();
  std::vector<Vec3> point(ng);
  std::vector<double> work(ng, 0.0);
  for (unsigned int p = 0; p < ng; ++p)
    point[p] = Vec3(mesh.position[3 * p], mesh.position[3 * p + 1], mesh.position[3 * p + 2]);
  for (const auto& zone : mesh.zone_gridpoint)
    for (unsigned int p : zone)
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
  if (whole.quadratic() || whole.n_hexes() > 0)
    throw std::logic_error("share_mesh: 4-node zones only");
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

  std::vector<char> held_zone(nz, 0), held_gridpoint(ng, 0);
  for (unsigned int z = 0; z < nz; ++z)
    for (unsigned int g : whole.zone_gridpoint[z])
      held_zone[z] |= owner[g] == rank;
  for (unsigned int z = 0; z < nz; ++z)
    if (held_zone[z])
      for (unsigned int g : whole.zone_gridpoint[z])
        held_gridpoint[g] = 1;
  if (also_ghosts != nullptr)
    for (unsigned int g = 0; g < ng; ++g)
      held_gridpoint[g] |= (*also_ghosts)[g];
  MeshShare s;
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
    }
  std::vector<int> local_zone(nz, -1);
  for (unsigned int z = 0, k = 0; z < nz; ++z)
    if (held_zone[z])
      local_zone[z] = static_cast<int>(k++);
  for (unsigned int f = 0; f < whole.n_faces(); ++f)
    if (held_zone[whole.face_zone[f]])
    {
      std::array<unsigned int, 3> corners;
      for (int k = 0; k < 3; ++k)
        corners[k] = static_cast<unsigned int>(local[whole.face_gridpoint[f][k]]);
      s.mesh.face_gridpoint.push_back(corners);
      s.mesh.face_zone.push_back(static_cast<unsigned int>(local_zone[whole.face_zone[f]]));
    }
  return s;
}

} // namespace talus
