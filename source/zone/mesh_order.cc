#include <talus/zone/mesh_order.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace talus
{

std::uint64_t hilbert_index(std::uint32_t x, std::uint32_t y, std::uint32_t z)
{
  // J. Skilling, "Programming the Hilbert curve" (AIP Conf. Proc. 707,
  // 2004): turn the axes into the "transpose" of the index in place, then
  // read its bits out, most significant level first.
  constexpr int bits = 21, n = 3;
  std::uint32_t X[n] = {x, y, z};
  const std::uint32_t top = 1u << (bits - 1);
  for (std::uint32_t q = top; q > 1; q >>= 1)
  {
    const std::uint32_t p = q - 1;
    for (int i = 0; i < n; ++i)
      if (X[i] & q)
        X[0] ^= p; // invert the low bits
      else
      {
        const std::uint32_t t = (X[0] ^ X[i]) & p; // exchange the low bits
        X[0] ^= t;
        X[i] ^= t;
      }
  }
  for (int i = 1; i < n; ++i) // Gray encode
    X[i] ^= X[i - 1];
  std::uint32_t t = 0;
  for (std::uint32_t q = top; q > 1; q >>= 1)
    if (X[n - 1] & q)
      t ^= q - 1;
  for (int i = 0; i < n; ++i)
    X[i] ^= t;
  std::uint64_t index = 0;
  for (int b = bits - 1; b >= 0; --b)
    for (int i = 0; i < n; ++i)
      index = (index << 1) | ((X[i] >> b) & 1u);
  return index;
}

namespace
{
/// Signed volume of zone z (m^3).
double zone_volume(const TetMesh& mesh, unsigned int z)
{
  const auto& t = mesh.zone_gridpoint[z];
  double e[3][3];
  for (int a = 0; a < 3; ++a)
    for (int d = 0; d < 3; ++d)
      e[a][d] = mesh.position[3 * t[a + 1] + d] - mesh.position[3 * t[0] + d];
  return (e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
          e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
          e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) /
         6.0;
}
} // namespace

MeshPermutation order_for_locality(TetMesh& mesh, MeshOrder order, unsigned int column_cells)
{
  if (order == MeshOrder::generator)
  {
    MeshPermutation perm;
    perm.old_zone.resize(mesh.n_zones());
    perm.old_gridpoint.resize(mesh.n_gridpoints());
    std::iota(perm.old_zone.begin(), perm.old_zone.end(), 0u);
    std::iota(perm.old_gridpoint.begin(), perm.old_gridpoint.end(), 0u);
    return perm;
  }
  return order_for_locality(
      mesh, [order](unsigned int) { return order; }, column_cells);
}

MeshPermutation order_for_locality(TetMesh& mesh, const BlockMeshOrder& order_of_block,
                                   unsigned int column_cells)
{
  const unsigned int nz = mesh.n_zones(), ng = mesh.n_gridpoints();
  MeshPermutation perm;
  constexpr unsigned int none = std::numeric_limits<unsigned int>::max();
  // Units that move together: a hexahedral zone's ten tetrahedra, or one
  // plain zone. unit_hex: the hexahedron of a unit, or none.
  std::vector<unsigned int> hex_at(nz, none);
  for (unsigned int h = 0; h < mesh.n_hexes(); ++h)
    hex_at[mesh.hex_first_zone[h]] = h;
  std::vector<unsigned int> unit_first, unit_size;
  for (unsigned int z = 0; z < nz;)
  {
    const unsigned int size = hex_at[z] != none ? TetMesh::tets_per_hex : 1;
    unit_first.push_back(z);
    unit_size.push_back(size);
    z += size;
  }
  const std::size_t nu = unit_first.size();
  // Centroid of each unit (of its zones' corners), and the run of blocks
  // it is in: blocks keep their order, only zones within a run move.
  std::vector<double> centroid(3 * nu, 0.0);
  std::vector<unsigned int> run(nu, 0);
  for (std::size_t u = 0; u < nu; ++u)
  {
    const unsigned int z0 = unit_first[u];
    if (u > 0)
      run[u] = run[u - 1] + (mesh.zone_block[z0] != mesh.zone_block[unit_first[u - 1]]);
    for (unsigned int z = z0; z < z0 + unit_size[u]; ++z)
      for (unsigned int g : mesh.zone_gridpoint[z])
        for (int d = 0; d < 3; ++d)
          centroid[3 * u + d] += mesh.position[3 * g + d] / (4.0 * unit_size[u]);
  }
  // The sort key of each unit, within the bounding box of its run, and
  // the order of each run (of its block).
  std::vector<std::uint64_t> key(nu, 0);
  std::vector<MeshOrder> run_order;
  // Columns only: the column of each unit and whether it is a seam unit.
  std::vector<unsigned int> column(nu, 0);
  std::vector<unsigned char> seam(nu, 0);
  bool any_columns = false;
  constexpr std::uint32_t cells = (1u << 21) - 1; // per axis, at most
  for (std::size_t begin = 0, end = 0; begin < nu; begin = end)
  {
    const MeshOrder order = order_of_block(mesh.zone_block[unit_first[begin]]);
    run_order.push_back(order);
    any_columns |= order == MeshOrder::columns;
    double lo[3], hi[3];
    for (int d = 0; d < 3; ++d)
      lo[d] = hi[d] = centroid[3 * begin + d];
    for (end = begin; end < nu && run[end] == run[begin]; ++end)
      for (int d = 0; d < 3; ++d)
      {
        lo[d] = std::min(lo[d], centroid[3 * end + d]);
        hi[d] = std::max(hi[d], centroid[3 * end + d]);
      }
    const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    if (order == MeshOrder::generator) // as they are
    {
      for (std::size_t u = begin; u < end; ++u)
        key[u] = u;
      continue;
    }
    // Lattice cells: for the curve, the finest the key holds; for slabs,
    // of the zone size, cbrt(5 V) for mean zone volume V (a hexahedron of
    // the brick generator, whose five tetrahedra then share a cell), shifted
    // by a quarter cell so that their centroids (a quarter to three
    // quarters across the hexahedron) stay clear of the cell faces.
    double cell = extent / cells, shift = 0.0;
    if (order != MeshOrder::hilbert)
    {
      double volume = 0.0;
      const unsigned int first = unit_first[begin];
      const unsigned int last = unit_first[end - 1] + unit_size[end - 1];
      for (unsigned int z = first; z < last; ++z)
        volume += std::abs(zone_volume(mesh, z));
      cell = std::max(cell, std::cbrt(5.0 * volume / (last - first)));
      shift = 0.25;
    }
    // Columns: column_cells x column_cells cells across, numbered along x
    // first.
    const std::uint32_t per_row =
        cell > 0.0 ? (static_cast<std::uint32_t>(std::floor((hi[0] - lo[0]) / cell + shift)) +
                      column_cells) /
                         column_cells
                   : 1u;
    for (std::size_t u = begin; u < end; ++u)
    {
      std::uint32_t c[3];
      for (int d = 0; d < 3; ++d)
        c[d] = cell > 0.0 ? static_cast<std::uint32_t>(std::min<double>(
                                cells, std::floor((centroid[3 * u + d] - lo[d]) / cell + shift)))
                          : 0u;
      // Slabs: z slowest, x fastest, as the brick generator.
      key[u] = order == MeshOrder::hilbert
                   ? hilbert_index(c[0], c[1], c[2])
                   : (std::uint64_t(c[2]) << 42) | (std::uint64_t(c[1]) << 21) | c[0];
      if (order == MeshOrder::columns)
        column[u] = (c[1] / column_cells) * per_row + c[0] / column_cells;
    }
  }
  if (any_columns)
  {
    // A unit is a seam unit if one of its gridpoints is also used by a unit
    // of a later column: every gridpoint is then used by seam units and by
    // the other units of one column at most, so that nodal mixed
    // discretization's sums at a gridpoint are complete within that
    // column's sweep. (Column numbers of different blocks do not meet:
    // blocks have gridpoints of their own.)
    std::vector<unsigned int> last_column(ng, 0);
    const auto for_gridpoints = [&](std::size_t u, auto&& visit)
    {
      for (unsigned int z = unit_first[u]; z < unit_first[u] + unit_size[u]; ++z)
        for (unsigned int g : mesh.zone_gridpoint[z])
          visit(g);
    };
    for (std::size_t u = 0; u < nu; ++u)
      for_gridpoints(u,
                     [&](unsigned int g) { last_column[g] = std::max(last_column[g], column[u]); });
    for (std::size_t u = 0; u < nu; ++u)
      if (run_order[run[u]] == MeshOrder::columns)
        for_gridpoints(u, [&](unsigned int g) { seam[u] |= last_column[g] > column[u]; });
  }
  std::vector<unsigned int> unit_order(nu);
  std::iota(unit_order.begin(), unit_order.end(), 0u);
  std::stable_sort(unit_order.begin(), unit_order.end(),
                   [&](unsigned int a, unsigned int b)
                   {
                     if (run[a] != run[b])
                       return run[a] < run[b];
                     if (run_order[run[a]] == MeshOrder::columns)
                     {
                       // Seams first, in slabs; then column by column.
                       if (seam[a] != seam[b])
                         return seam[a] > seam[b];
                       if (!seam[a] && column[a] != column[b])
                         return column[a] < column[b];
                     }
                     return key[a] < key[b];
                   });

  perm.old_zone.reserve(nz);
  for (unsigned int u : unit_order)
    for (unsigned int z = unit_first[u]; z < unit_first[u] + unit_size[u]; ++z)
      perm.old_zone.push_back(z);
  // Gridpoints in first use by the zones in their new order; any gridpoint
  // no zone uses keeps its relative place at the end.
  std::vector<unsigned int> new_gridpoint(ng, none);
  perm.old_gridpoint.reserve(ng);
  const auto use = [&](unsigned int g)
  {
    if (new_gridpoint[g] == none)
    {
      new_gridpoint[g] = static_cast<unsigned int>(perm.old_gridpoint.size());
      perm.old_gridpoint.push_back(g);
    }
  };
  for (unsigned int z : perm.old_zone)
  {
    for (unsigned int g : mesh.zone_gridpoint[z])
      use(g);
    if (mesh.quadratic())
      for (unsigned int g : mesh.zone_edge_gridpoint[z])
        use(g);
  }
  for (unsigned int g = 0; g < ng; ++g)
    use(g);
  std::vector<unsigned int> new_zone(nz);
  for (unsigned int z = 0; z < nz; ++z)
    new_zone[perm.old_zone[z]] = z;

  // Apply.
  const auto renumber_all = [&](auto& list)
  {
    for (auto& item : list)
      for (unsigned int& g : item)
        g = new_gridpoint[g];
  };
  {
    std::vector<double> position(3 * std::size_t(ng));
    std::vector<unsigned int> gridpoint_block(ng);
    for (unsigned int g = 0; g < ng; ++g)
    {
      const unsigned int old = perm.old_gridpoint[g];
      for (int d = 0; d < 3; ++d)
        position[3 * g + d] = mesh.position[3 * old + d];
      gridpoint_block[g] = mesh.gridpoint_block[old];
    }
    mesh.position = std::move(position);
    mesh.gridpoint_block = std::move(gridpoint_block);
  }
  {
    std::vector<std::array<unsigned int, 4>> zone_gridpoint(nz);
    std::vector<unsigned int> zone_block(nz);
    std::vector<std::array<unsigned int, 6>> zone_edge_gridpoint(mesh.zone_edge_gridpoint.size());
    for (unsigned int z = 0; z < nz; ++z)
    {
      const unsigned int old = perm.old_zone[z];
      zone_gridpoint[z] = mesh.zone_gridpoint[old];
      zone_block[z] = mesh.zone_block[old];
      if (mesh.quadratic())
        zone_edge_gridpoint[z] = mesh.zone_edge_gridpoint[old];
    }
    mesh.zone_gridpoint = std::move(zone_gridpoint);
    mesh.zone_block = std::move(zone_block);
    mesh.zone_edge_gridpoint = std::move(zone_edge_gridpoint);
  }
  renumber_all(mesh.zone_gridpoint);
  renumber_all(mesh.zone_edge_gridpoint);
  renumber_all(mesh.face_gridpoint);
  renumber_all(mesh.second_overlay_face_gridpoint);
  for (unsigned int& z : mesh.face_zone)
    z = new_zone[z];
  // Hexahedra in the order of their zones.
  {
    std::vector<std::array<unsigned int, 8>> hex_gridpoint;
    std::vector<unsigned int> hex_first_zone;
    for (unsigned int u : unit_order)
      if (hex_at[unit_first[u]] != none)
      {
        const unsigned int h = hex_at[unit_first[u]];
        hex_gridpoint.push_back(mesh.hex_gridpoint[h]);
        hex_first_zone.push_back(new_zone[unit_first[u]]);
      }
    mesh.hex_gridpoint = std::move(hex_gridpoint);
    mesh.hex_first_zone = std::move(hex_first_zone);
    renumber_all(mesh.hex_gridpoint);
  }
  return perm;
}

} // namespace talus
