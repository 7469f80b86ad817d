// Renumbering zones and gridpoints for locality (mesh_order.h).
//
// 1. The Hilbert index on the 8^3 cells nearest the origin: a permutation
//    of 0..511, and consecutive cells share a face.
// 2. Meshes in generator order, renumbered by slabs and by the Hilbert
//    curve: brick (tet4), brick of hexahedral zones, a tetrahedral block
//    (refined), and 10-node zones. The renumbering must be a permutation of
//    zones and of gridpoints, and the renumbered mesh the same mesh: every
//    array (positions, zones with their corner order, faces, face zones,
//    hexahedra, midpoints, blocks) equal to the old one mapped through it;
//    each hexahedron's ten tetrahedra still consecutive and in order;
//    gridpoints in first use by the zones; a second renumbering changes
//    nothing. The zone order of the cube brick is the generator's.
//    The same in columns (MeshOrder::columns) of 2 or 3 cells; columns
//    wider than the brick are its slabs. With an order per block, each
//    block as in its own order. In a brick of 10,000 zones in
//    columns of 5 cells, the zones that wait long for the last zone around
//    their gridpoints are the seam zones, all at the start, and fewer than
//    in slabs.
// 3. A scrambled mesh (zones and gridpoints in a random order) comes back
//    local: the mean spread of the gridpoint numbers of a zone, over the
//    number of gridpoints, no more than in the generator's order.
// 4. The same answer: the cube (and its hexahedral and 10-node versions)
//    falling under gravity on its held base, 200 dynamic steps, in
//    generator order and renumbered (Hilbert; 4-node zones also columns). The displacements and
//    stresses differ by round-off only (the sums at gridpoints take their terms in another order):
//    the largest difference over the largest value must be below 1e-12.

#include <talus/base/parallel_environment.h>
#include <talus/solver/deformable_solver.h>
#include <talus/zone/block_mesher.h>
#include <talus/zone/mesh_order.h>
#include <talus/zone/tet10_mesh.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <random>
#include <set>

#include "../tests.h"

using namespace talus;

namespace
{
/// Mismatches between `before` renumbered by `perm` and `after`.
unsigned int count_mismatches(const TetMesh& before, const TetMesh& after,
                              const MeshPermutation& perm)
{
  unsigned int bad = 0;
  const unsigned int nz = before.n_zones(), ng = before.n_gridpoints();
  const auto is_permutation = [](std::vector<unsigned int> p, unsigned int n)
  {
    std::sort(p.begin(), p.end());
    std::vector<unsigned int> identity(n);
    std::iota(identity.begin(), identity.end(), 0u);
    return p == identity;
  };
  if (!is_permutation(perm.old_zone, nz) || !is_permutation(perm.old_gridpoint, ng) ||
      after.n_zones() != nz || after.n_gridpoints() != ng || after.n_faces() != before.n_faces() ||
      after.n_hexes() != before.n_hexes() || after.quadratic() != before.quadratic())
    return 1000000;
  const auto& og = perm.old_gridpoint;
  for (unsigned int g = 0; g < ng; ++g)
  {
    for (int d = 0; d < 3; ++d)
      bad += after.position[3 * g + d] != before.position[3 * og[g] + d];
    bad += after.gridpoint_block[g] != before.gridpoint_block[og[g]];
  }
  for (unsigned int z = 0; z < nz; ++z)
  {
    const unsigned int old = perm.old_zone[z];
    bad += after.zone_block[z] != before.zone_block[old];
    for (int a = 0; a < 4; ++a)
      bad += og[after.zone_gridpoint[z][a]] != before.zone_gridpoint[old][a];
    if (after.quadratic())
      for (int e = 0; e < 6; ++e)
        bad += og[after.zone_edge_gridpoint[z][e]] != before.zone_edge_gridpoint[old][e];
  }
  std::vector<unsigned int> new_zone(nz);
  for (unsigned int z = 0; z < nz; ++z)
    new_zone[perm.old_zone[z]] = z;
  for (unsigned int f = 0; f < after.n_faces(); ++f)
  {
    bad += after.face_zone[f] != new_zone[before.face_zone[f]];
    for (int a = 0; a < 3; ++a)
      bad += og[after.face_gridpoint[f][a]] != before.face_gridpoint[f][a];
  }
  for (std::size_t f = 0; f < after.second_overlay_face_gridpoint.size(); ++f)
    for (int a = 0; a < 3; ++a)
      bad += og[after.second_overlay_face_gridpoint[f][a]] !=
             before.second_overlay_face_gridpoint[f][a];
  // Hexahedra: each is an old one, its ten zones consecutive and in order.
  std::set<unsigned int> old_hexes;
  for (unsigned int h = 0; h < after.n_hexes(); ++h)
  {
    const unsigned int first = after.hex_first_zone[h];
    bad += h > 0 && first <= after.hex_first_zone[h - 1];
    const auto it =
        std::find(before.hex_first_zone.begin(), before.hex_first_zone.end(), perm.old_zone[first]);
    if (it == before.hex_first_zone.end())
    {
      ++bad;
      continue;
    }
    const unsigned int old = static_cast<unsigned int>(it - before.hex_first_zone.begin());
    old_hexes.insert(old);
    for (unsigned int k = 0; k < TetMesh::tets_per_hex; ++k)
      bad += perm.old_zone[first + k] != before.hex_first_zone[old] + k;
    for (int c = 0; c < 8; ++c)
      bad += og[after.hex_gridpoint[h][c]] != before.hex_gridpoint[old][c];
  }
  bad += old_hexes.size() != before.n_hexes();
  // Gridpoints numbered in first use by the zones in their new order.
  unsigned int next = 0;
  for (unsigned int z = 0; z < nz; ++z)
  {
    std::vector<unsigned int> nodes(after.zone_gridpoint[z].begin(), after.zone_gridpoint[z].end());
    if (after.quadratic())
      nodes.insert(nodes.end(), after.zone_edge_gridpoint[z].begin(),
                   after.zone_edge_gridpoint[z].end());
    for (unsigned int g : nodes)
    {
      bad += g > next;
      next += g == next;
    }
  }
  return bad;
}

/// Mean over zones of the spread of their gridpoint numbers, over the
/// number of gridpoints.
double mean_spread(const TetMesh& mesh)
{
  double sum = 0.0;
  for (const auto& t : mesh.zone_gridpoint)
    sum += *std::max_element(t.begin(), t.end()) - *std::min_element(t.begin(), t.end());
  return sum / mesh.n_zones() / mesh.n_gridpoints();
}

bool is_identity(const std::vector<unsigned int>& p)
{
  for (unsigned int i = 0; i < p.size(); ++i)
    if (p[i] != i)
      return false;
  return true;
}

/// Renumbers a copy of `mesh` in `order`, checks it and the renumbering of
/// that again; returns the renumbered mesh and its permutation.
TetMesh renumbered(const std::string& name, const TetMesh& mesh, MeshOrder order,
                   MeshPermutation& perm, unsigned int column_cells = 32)
{
  TetMesh out = mesh;
  perm = order_for_locality(out, order, column_cells);
  TetMesh again = out;
  const MeshPermutation second = order_for_locality(again, order, column_cells);
  std::printf("%-28s %-7s: %6u zones, %5u gridpoints; mismatches %u; zones moved %s; "
              "renumbered again: %s\n",
              name.c_str(),
              order == MeshOrder::slabs     ? "slabs"
              : order == MeshOrder::hilbert ? "hilbert"
                                            : "columns",
              mesh.n_zones(), mesh.n_gridpoints(), count_mismatches(mesh, out, perm),
              is_identity(perm.old_zone) ? "no" : "yes",
              is_identity(second.old_zone) && is_identity(second.old_gridpoint) ? "unchanged"
                                                                                : "CHANGED");
  return out;
}

/// The zones that wait more than `limit` zones for the last zone that
/// shares a gridpoint with them (nodal mixed discretization's wait between
/// its two stages), and whether they are all at the start.
unsigned int long_waits(const TetMesh& mesh, unsigned int limit, bool& first)
{
  std::vector<unsigned int> last(mesh.n_gridpoints(), 0);
  for (unsigned int z = 0; z < mesh.n_zones(); ++z)
    for (unsigned int g : mesh.zone_gridpoint[z])
      last[g] = z;
  unsigned int count = 0;
  first = true;
  for (unsigned int z = 0; z < mesh.n_zones(); ++z)
  {
    unsigned int wait = 0;
    for (unsigned int g : mesh.zone_gridpoint[z])
      wait = std::max(wait, last[g] - z);
    if (wait > limit)
      first &= count++ == z;
  }
  return count;
}

/// Displacements and stresses after 200 dynamic steps of the block falling
/// under gravity on its held base (z = 0).
void solve(const TetMesh& mesh, ZoneElement element, std::vector<double>& u,
           std::vector<double>& stress)
{
  ZoneMaterial rock;
  rock.density = 2650.0;
  rock.set_young_poisson(1e10, 0.25);
  rock.element = element;
  SolverSettings settings;
  settings.dynamic = true;
  settings.gravity = Vec3(0, 0, -9.81);
  GridpointCondition base;
  base.region = Box{Vec3(-1, -1, -1e-9), Vec3(3, 3, 1e-9)};
  DeformableSolver solver(mesh, {rock}, std::vector<unsigned int>(mesh.n_zones(), 0), settings,
                          {base});
  for (int k = 0; k < 200; ++k)
    solver.step();
  u = solver.displacements();
  stress = solver.stress();
}

/// Largest difference of the renumbered run from the generator's, over the
/// largest value, for displacements and stresses.
void compare_answers(const std::string& name, const TetMesh& mesh, const TetMesh& ordered,
                     const MeshPermutation& perm, ZoneElement element)
{
  std::vector<double> u0, s0, u1, s1;
  solve(mesh, element, u0, s0);
  solve(ordered, element, u1, s1);
  double u_max = 0.0, u_diff = 0.0, s_max = 0.0, s_diff = 0.0;
  for (unsigned int g = 0; g < ordered.n_gridpoints(); ++g)
    for (int d = 0; d < 3; ++d)
    {
      u_max = std::max(u_max, std::abs(u0[3 * perm.old_gridpoint[g] + d]));
      u_diff = std::max(u_diff, std::abs(u1[3 * g + d] - u0[3 * perm.old_gridpoint[g] + d]));
    }
  const unsigned int points = static_cast<unsigned int>(s1.size() / 6 / ordered.n_zones());
  for (unsigned int z = 0; z < ordered.n_zones(); ++z)
    for (unsigned int i = 0; i < 6 * points; ++i)
    {
      const double old = s0[6 * points * perm.old_zone[z] + i];
      s_max = std::max(s_max, std::abs(old));
      s_diff = std::max(s_diff, std::abs(s1[6 * points * z + i] - old));
    }
  std::fprintf(
      stderr, "%s: largest displacement %.3g m, stress %.3g Pa; differences over them %.0e, %.0e\n",
      name.c_str(), u_max, s_max, u_diff / u_max, s_diff / s_max);
  std::printf("%s, renumbered vs generator order: displacements %s, stresses %s\n", name.c_str(),
              u_max > 0.0 && u_diff <= 1e-12 * u_max ? "agree to 1e-12" : "DIFFER",
              s_max > 0.0 && s_diff <= 1e-12 * s_max ? "agree to 1e-12" : "DIFFER");
}
} // namespace

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);

  // 1. The Hilbert curve.
  {
    std::vector<std::array<unsigned int, 3>> at(512, {~0u, ~0u, ~0u});
    unsigned int outside = 0;
    for (unsigned int x = 0; x < 8; ++x)
      for (unsigned int y = 0; y < 8; ++y)
        for (unsigned int z = 0; z < 8; ++z)
        {
          const std::uint64_t i = hilbert_index(x, y, z);
          if (i < 512 && at[i][0] == ~0u)
            at[i] = {x, y, z};
          else
            ++outside;
        }
    unsigned int not_neighbours = 0;
    for (unsigned int i = 1; i < 512 && outside == 0; ++i)
    {
      int distance = 0;
      for (int d = 0; d < 3; ++d)
        distance += std::abs(int(at[i][d]) - int(at[i - 1][d]));
      not_neighbours += distance != 1;
    }
    std::printf("Hilbert index on 8^3 cells: %u outside 0..511 or repeated, %u consecutive pairs "
                "not sharing a face\n",
                outside, not_neighbours);
  }

  // 2. Renumbered meshes are the same meshes.
  BlockModel cube, long_brick, tetrahedron;
  cube.add_block(ConvexPolyhedron::box(Vec3::Zero(), Vec3(1, 1, 1)), 0);
  long_brick.add_block(ConvexPolyhedron::box(Vec3::Zero(), Vec3(2, 1, 0.5)), 0);
  long_brick.add_block(ConvexPolyhedron::box(Vec3(0, 0, 1), Vec3(1, 1, 2)), 0);
  tetrahedron.add_block(
      ConvexPolyhedron::tetrahedron(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0), Vec3(0, 0, 2)), 0);
  MeshReport report;
  const TetMesh cube_mesh =
      mesh_blocks(cube, {0}, 0.25, report, ZoneElement::tet4, MeshOrder::generator);
  const TetMesh two_bricks =
      mesh_blocks(long_brick, {0, 1}, 0.25, report, ZoneElement::tet4, MeshOrder::generator);
  const TetMesh hex_mesh =
      mesh_blocks(cube, {0}, 0.25, report, ZoneElement::hex_mixed, MeshOrder::generator);
  const TetMesh tet_mesh =
      mesh_blocks(tetrahedron, {0}, 0.3, report, ZoneElement::tet4, MeshOrder::generator);
  TetMesh tet10_mesh = cube_mesh;
  make_quadratic(tet10_mesh);

  MeshPermutation cube_slabs, cube_hilbert, hex_perm, tet10_perm, other;
  renumbered("cube brick", cube_mesh, MeshOrder::slabs, cube_slabs);
  std::printf("cube brick, slabs: zone order of the generator kept: %s\n",
              is_identity(cube_slabs.old_zone) ? "yes" : "NO");
  const TetMesh cube_ordered =
      renumbered("cube brick", cube_mesh, MeshOrder::hilbert, cube_hilbert);
  MeshPermutation bricks_slabs;
  renumbered("two bricks (2x1x0.5, 1x1x1)", two_bricks, MeshOrder::slabs, bricks_slabs);
  renumbered("two bricks (2x1x0.5, 1x1x1)", two_bricks, MeshOrder::hilbert, other);
  renumbered("tetrahedral block", tet_mesh, MeshOrder::slabs, other);
  renumbered("tetrahedral block", tet_mesh, MeshOrder::hilbert, other);
  renumbered("hexahedral zones", hex_mesh, MeshOrder::slabs, other);
  const TetMesh hex_ordered =
      renumbered("hexahedral zones", hex_mesh, MeshOrder::hilbert, hex_perm);
  const TetMesh tet10_ordered =
      renumbered("10-node zones", tet10_mesh, MeshOrder::hilbert, tet10_perm);
  MeshPermutation cube_columns;
  const TetMesh cube_in_columns =
      renumbered("cube brick, 2-cell columns", cube_mesh, MeshOrder::columns, cube_columns, 2);
  MeshPermutation bricks_columns;
  renumbered("two bricks, 2-cell columns", two_bricks, MeshOrder::columns, bricks_columns, 2);
  // An order per block (talus: columns for blocks with nodal mixed
  // discretization): the first brick's zones and gridpoints as in columns,
  // the second's as in slabs; a mesh's array checks as above.
  {
    TetMesh mixed = two_bricks;
    const MeshPermutation perm = order_for_locality(
        mixed,
        [](unsigned int block) { return block == 0 ? MeshOrder::columns : MeshOrder::slabs; }, 2);
    const unsigned int first_zone = static_cast<unsigned int>(
        std::count(two_bricks.zone_block.begin(), two_bricks.zone_block.end(), 0u));
    const unsigned int first_gridpoint = static_cast<unsigned int>(
        std::count(two_bricks.gridpoint_block.begin(), two_bricks.gridpoint_block.end(), 0u));
    unsigned int differ = 0;
    for (unsigned int z = 0; z < two_bricks.n_zones(); ++z)
      differ += perm.old_zone[z] != (z < first_zone ? bricks_columns : bricks_slabs).old_zone[z];
    for (unsigned int g = 0; g < two_bricks.n_gridpoints(); ++g)
      differ += perm.old_gridpoint[g] !=
                (g < first_gridpoint ? bricks_columns : bricks_slabs).old_gridpoint[g];
    std::printf("two bricks, the first in 2-cell columns and the second in slabs: mismatches %u; "
                "zones and gridpoints as in the two orders: %s\n",
                count_mismatches(two_bricks, mixed, perm), differ == 0 ? "yes" : "NO");
  }
  renumbered("tetrahedral block, columns 3", tet_mesh, MeshOrder::columns, other, 3);
  renumbered("hexahedral zones, columns 2", hex_mesh, MeshOrder::columns, other, 2);
  renumbered("cube brick, 32-cell columns", cube_mesh, MeshOrder::columns, other);
  std::printf("cube brick, columns wider than the brick: slab order: %s\n",
              is_identity(other.old_zone) && is_identity(other.old_gridpoint) ? "yes" : "NO");
  // Columns: a 2 x 1 x 1 brick of 20 x 10 x 10 cells (10,000 zones) in
  // columns of 5 x 5 cells, against slabs: the zones that wait more than
  // two slabs of a column (250 zones) for the last zone around their
  // gridpoints, all seam zones at the start; in slabs every zone but the
  // top slab's waits about one slab of the brick (1,000 zones).
  {
    BlockModel brick;
    brick.add_block(ConvexPolyhedron::box(Vec3::Zero(), Vec3(2, 1, 1)), 0);
    const TetMesh slabs = mesh_blocks(brick, {0}, 0.1, report);
    const TetMesh columns =
        mesh_blocks(brick, {0}, 0.1, report, ZoneElement::tet4, MeshOrder::columns);
    TetMesh narrow = slabs;
    order_for_locality(narrow, MeshOrder::columns, 5);
    bool first_slabs = false, first_narrow = false, first_columns = false;
    const unsigned int in_slabs = long_waits(slabs, 250, first_slabs);
    const unsigned int in_narrow = long_waits(narrow, 250, first_narrow);
    const unsigned int in_columns = long_waits(columns, 250, first_columns);
    std::printf("brick of 10000 zones, zones waiting more than 250 zones: slabs %u; columns of 5 "
                "cells %u, all at the start: %s; columns of 32 cells (the default) %u\n",
                in_slabs, in_narrow, first_narrow ? "yes" : "NO", in_columns);
  }

  // 3. A scrambled mesh.
  {
    TetMesh scrambled = tet_mesh;
    std::mt19937 random(4);
    std::vector<unsigned int> zone(scrambled.n_zones()), gridpoint(scrambled.n_gridpoints());
    std::iota(zone.begin(), zone.end(), 0u);
    std::iota(gridpoint.begin(), gridpoint.end(), 0u);
    std::shuffle(zone.begin(), zone.end(), random);
    std::shuffle(gridpoint.begin(), gridpoint.end(), random); // old -> new
    for (unsigned int z = 0; z < scrambled.n_zones(); ++z)
    {
      scrambled.zone_gridpoint[zone[z]] = tet_mesh.zone_gridpoint[z];
      for (unsigned int& g : scrambled.zone_gridpoint[zone[z]])
        g = gridpoint[g];
    }
    for (unsigned int g = 0; g < scrambled.n_gridpoints(); ++g)
      for (int d = 0; d < 3; ++d)
        scrambled.position[3 * gridpoint[g] + d] = tet_mesh.position[3 * g + d];
    for (std::size_t f = 0; f < scrambled.face_gridpoint.size(); ++f)
    {
      scrambled.face_zone[f] = zone[tet_mesh.face_zone[f]];
      for (unsigned int& g : scrambled.face_gridpoint[f])
        g = gridpoint[g];
    }
    const double spread = mean_spread(scrambled);
    MeshPermutation perm;
    const TetMesh back =
        renumbered("scrambled tetrahedral block", scrambled, MeshOrder::slabs, perm);
    std::printf("scrambled tetrahedral block: mean spread of a zone's gridpoint numbers %.3f of "
                "them; slabs: %.3f (generator order: %.3f) %s\n",
                spread, mean_spread(back), mean_spread(tet_mesh),
                mean_spread(back) <= mean_spread(tet_mesh) ? "OK" : "NOT LOCAL");
  }

  // 4. The same answer.
  compare_answers("cube, 4-node zones, Hilbert", cube_mesh, cube_ordered, cube_hilbert,
                  ZoneElement::tet4);
  compare_answers("cube, 4-node zones, 2-cell columns", cube_mesh, cube_in_columns, cube_columns,
                  ZoneElement::tet4);
  compare_answers("cube, hexahedral zones, Hilbert", hex_mesh, hex_ordered, hex_perm,
                  ZoneElement::hex_mixed);
  compare_answers("cube, 10-node zones, Hilbert", tet10_mesh, tet10_ordered, tet10_perm,
                  ZoneElement::tet10);
}
