#include <talus/base/exceptions.h>
#include <talus/base/gather.h>
#include <talus/base/wall_clock.h>
#include <talus/io/scene_checks.h>
#include <talus/run/rank_share.h>
#include <talus/run/rank_zones.h>
#include <talus/run/run_summary.h>
#include <talus/solver/mesh_share.h>
#include <talus/solver/zone_migration.h>
#include <talus/zone/zone_surface.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <stdexcept>
#include <unordered_map>

namespace talus
{

std::unique_ptr<WholeZones> mesh_zones_on_ranks(const Scene& scene, BlockModel& whole)
{
  if (world_ranks() < 2 || scene.deformable.groups.empty() || whole.n_blocks() < 2)
    return nullptr;
  std::vector<unsigned int> deformable;
  for (unsigned int b = 0; b < whole.n_blocks(); ++b)
    for (const std::string& g : scene.deformable.groups)
      if (whole.group_names[whole.group[b]] == g)
        deformable.push_back(b);
  if (deformable.empty())
    return nullptr;
  print_zone_estimate(scene, whole);
  auto zones = std::make_unique<WholeZones>();
  const auto start = std::chrono::steady_clock::now();
  zones->mesh = mesh_deformable_blocks(scene, whole, deformable, zones->report, MPI_COMM_WORLD);
  if (has_joint_pressures(scene)) // on the blocks' own faces, as one run finds them
    zones->face_origins = zone_face_origins(whole, zones->mesh);
  zones->vertex_gridpoint = use_zone_surfaces(whole, zones->mesh);
  zones->vertex_start = whole.vertex_start;
  zones->zones_of_block.assign(whole.n_blocks(), 0.0);
  for (unsigned int b : zones->mesh.zone_block)
    zones->zones_of_block[b] += 1.0;
  zones->meshing_seconds = seconds_since(start);
  return zones;
}

unsigned int RankZones::block_of_whole_gridpoint(unsigned int g) const
{
  const auto it = std::upper_bound(run_first.begin(), run_first.end(), g);
  return run_block[std::size_t(it - run_first.begin()) - 1];
}

void RankZones::renumber(TetMesh& mesh, const RankShare& share) const
{
  for (std::size_t z = 0; z < mesh.zone_block.size(); ++z)
    mesh.zone_block[z] = static_cast<unsigned int>(share.local_of(zone_global_block[z]));
  for (std::size_t g = 0; g < mesh.gridpoint_block.size(); ++g)
    mesh.gridpoint_block[g] =
        static_cast<unsigned int>(std::max(0, share.local_of(gridpoint_global_block[g])));
}

namespace
{
Box box_of(const BlockModel& m, unsigned int b)
{
  Box box{m.vertex[m.vertex_start[b]], m.vertex[m.vertex_start[b]]};
  for (unsigned int v = m.vertex_start[b]; v < m.vertex_start[b + 1]; ++v)
  {
    box.lo = box.lo.cwiseMin(m.vertex[v]);
    box.hi = box.hi.cwiseMax(m.vertex[v]);
  }
  return box;
}

/// Each global block's owner (every block has one), from every rank's
/// owned blocks (`local`: global numbers).
std::vector<int> owners_of_blocks(std::size_t n_blocks, const std::vector<unsigned int>& local,
                                  const std::vector<char>& owned, int rank, MPI_Comm comm)
{
  std::vector<int> owner(n_blocks, -1);
  for (std::size_t l = 0; l < local.size(); ++l)
    if (owned[l])
      owner[local[l]] = rank;
  MPI_Allreduce(MPI_IN_PLACE, owner.data(), static_cast<int>(owner.size()), MPI_INT, MPI_MAX, comm);
  return owner;
}

/// The deformable blocks of other ranks whose surfaces a rank holds as
/// ghost gridpoints (without their zones): those whose boxes come within
/// `span` of a box of the rank's own blocks (`own`), and its deformable
/// ghosts (`ghosts`, global numbers). `box`: per global block, read for the
/// deformable ones. Ascending.
std::vector<unsigned int>
surfaces_near(const std::vector<Box>& box, const std::vector<char>& deformable,
              const std::vector<int>& block_owner, const std::vector<Box>& own,
              const std::vector<unsigned int>& ghosts, double span, int rank)
{
  const auto near = [&](const Box& a, const Box& b)
  {
    return (a.lo.array() - span <= b.hi.array()).all() &&
           (b.lo.array() <= a.hi.array() + span).all();
  };
  std::vector<char> held(block_owner.size(), 0);
  for (unsigned int b : ghosts)
    held[b] = deformable[b];
  std::vector<unsigned int> surfaces;
  for (unsigned int b = 0; b < block_owner.size(); ++b)
  {
    if (!deformable[b] || block_owner[b] == rank)
      continue;
    for (std::size_t k = 0; k < own.size() && !held[b]; ++k)
      held[b] = near(own[k], box[b]);
    if (held[b])
      surfaces.push_back(b);
  }
  return surfaces;
}

/// This rank's part of the zones for owners `block_owner` (per global
/// block), with the surfaces of the deformable blocks `surfaces` as ghost
/// gridpoints; `local_gridpoint`: per gridpoint of the whole mesh, its
/// local number here or -1.
MeshShare zone_part(const WholeZones& zones, const std::vector<int>& block_owner,
                    const std::vector<unsigned int>& surfaces, int rank, int ranks, MPI_Comm comm,
                    std::vector<int>& local_gridpoint)
{
  const TetMesh& w = zones.mesh;
  std::vector<unsigned int> owner(w.n_gridpoints());
  for (unsigned int g = 0; g < w.n_gridpoints(); ++g)
    owner[g] = static_cast<unsigned int>(block_owner[w.gridpoint_block[g]]);
  std::vector<char> ghost_surface(w.n_gridpoints(), 0);
  for (unsigned int b : surfaces)
    for (unsigned int v = zones.vertex_start[b]; v < zones.vertex_start[b + 1]; ++v)
      ghost_surface[std::size_t(zones.vertex_gridpoint[v])] = 1;
  MeshShare part = share_mesh(w, owner, static_cast<unsigned int>(rank),
                              static_cast<unsigned int>(ranks), comm, &ghost_surface);
  local_gridpoint.assign(w.n_gridpoints(), -1);
  for (unsigned int i = 0; i < part.gridpoint.size(); ++i)
    local_gridpoint[part.gridpoint[i]] = static_cast<int>(i);
  return part;
}

/// What the rank keeps of its part (RankZones): the global blocks of its
/// zones and gridpoints, the runs of the whole mesh's gridpoints, the
/// history points it reports; and its mesh's blocks as local numbers of
/// the blocks it holds (`local`, global numbers, ascending).
void keep_part(RankZones& kept, TetMesh& mesh, const MeshShare& part, const WholeZones& zones,
               const std::vector<int>& block_owner, const std::vector<int>& local_gridpoint,
               const PointHistory& points, const std::vector<unsigned int>& local, int rank)
{
  const TetMesh& w = zones.mesh;
  kept.run_first.clear();
  kept.run_block.clear();
  for (unsigned int g = 0; g < w.n_gridpoints(); ++g)
    if (g == 0 || w.gridpoint_block[g] != w.gridpoint_block[g - 1])
    {
      kept.run_first.push_back(g);
      kept.run_block.push_back(w.gridpoint_block[g]);
    }
  // History points: a gridpoint reported by its owner, a zone by its
  // block's owner (which alone holds it).
  kept.point_gridpoint.clear();
  kept.point_zone.clear();
  for (std::size_t k = 0; k < points.gridpoint.size(); ++k)
  {
    const unsigned int g = points.gridpoint[k], z = points.zone[k];
    kept.point_gridpoint.push_back(block_owner[w.gridpoint_block[g]] == rank ? local_gridpoint[g]
                                                                             : -1);
    int local_zone = -1;
    if (block_owner[w.zone_block[z]] == rank)
      local_zone = static_cast<int>(std::lower_bound(part.zone.begin(), part.zone.end(), z) -
                                    part.zone.begin());
    kept.point_zone.push_back(local_zone);
  }
  kept.zone = part.zone;
  kept.zone_global_block = mesh.zone_block;
  kept.gridpoint_global_block = mesh.gridpoint_block;
  const auto local_of = [&](unsigned int global)
  {
    const auto it = std::lower_bound(local.begin(), local.end(), global);
    return it != local.end() && *it == global ? static_cast<int>(it - local.begin()) : -1;
  };
  for (std::size_t z = 0; z < mesh.zone_block.size(); ++z)
    mesh.zone_block[z] = static_cast<unsigned int>(local_of(kept.zone_global_block[z]));
  for (std::size_t g = 0; g < mesh.gridpoint_block.size(); ++g)
    mesh.gridpoint_block[g] =
        static_cast<unsigned int>(std::max(0, local_of(kept.gridpoint_global_block[g])));
}

/// The local gridpoint of each vertex of the blocks held (`local`, global
/// numbers; -1 on rigid blocks), and the surfaces of the deformable blocks
/// held (owned ones and `surfaces`) on their local gridpoints.
void surfaces_on_gridpoints(const WholeZones& zones, const std::vector<unsigned int>& local,
                            const std::vector<int>& block_owner,
                            const std::vector<unsigned int>& surfaces,
                            const std::vector<int>& local_gridpoint, int rank,
                            std::vector<int>& vertex_gridpoint,
                            std::unordered_map<unsigned int, std::vector<int>>& held)
{
  vertex_gridpoint.clear();
  for (unsigned int b : local)
    for (unsigned int v = zones.vertex_start[b]; v < zones.vertex_start[b + 1]; ++v)
    {
      const int g = zones.vertex_gridpoint[v];
      if (g >= 0 && local_gridpoint[std::size_t(g)] < 0)
        throw std::logic_error("talus: a deformable block's surface gridpoint is not held");
      vertex_gridpoint.push_back(g < 0 ? -1 : local_gridpoint[std::size_t(g)]);
    }
  held.clear();
  for (unsigned int b = 0; b < block_owner.size(); ++b)
    if (block_owner[b] == rank || std::binary_search(surfaces.begin(), surfaces.end(), b))
      if (zones.vertex_gridpoint[zones.vertex_start[b]] >= 0)
      {
        std::vector<int>& gridpoints = held[b];
        for (unsigned int v = zones.vertex_start[b]; v < zones.vertex_start[b + 1]; ++v)
          gridpoints.push_back(local_gridpoint[std::size_t(zones.vertex_gridpoint[v])]);
      }
}

/// The zone solver of a rank's part (`mesh`: its blocks by local numbers
/// of `local`).
std::unique_ptr<DeformableSolver> part_solver(const Scene& scene, const BlockModel& local,
                                              const TetMesh& mesh, const MeshShare& part,
                                              const WholeZones& zones)
{
  ZoneMaterials m = zone_materials(scene, local, mesh);
  auto solver = std::make_unique<DeformableSolver>(
      mesh, std::move(m.materials), std::move(m.of_zone), scene.solver, scene.gridpoint_conditions,
      scene.face_pressures, scene.has_initial_stress ? &scene.initial_stress : nullptr,
      &part.share);
  if (!zones.face_origins.empty())
  {
    // The origins of the faces this rank holds.
    const std::vector<int>& all = zones.face_origins;
    std::vector<int> origins;
    for (unsigned int f : part.face)
      origins.push_back(all[f]);
    for (unsigned int f : part.second_overlay_face)
      origins.push_back(all[zones.mesh.n_faces() + f]);
    solver->set_face_origins(std::move(origins));
  }
  return solver;
}
} // namespace

BlockSystem build_block_system_on_ranks(const Scene& scene, const BlockModel& whole,
                                        BlockModel& local, const WholeZones& zones,
                                        const RankShare& share, RankZones& kept,
                                        const std::vector<unsigned int>* saved_surfaces)
{
  const int rank = share.rank();
  const std::vector<int> block_owner = owners_of_blocks(whole.n_blocks(), share.blocks().local,
                                                        share.blocks().owned, rank, share.comm());
  // Ghost entries without their zones: the surfaces of the other ranks'
  // deformable blocks whose boxes come within 2 (reach + s) of a box of
  // this rank's blocks (s: the longest side of a block that may move, one
  // not of 'Fixed groups': a large fixed boundary block would make every
  // surface near), the distance within which a migration makes a moving
  // block a ghost here (BlockMigration), and those of its deformable ghosts
  // now. On a restart, those the rank held at its checkpoint.
  std::vector<unsigned int> surfaces;
  if (saved_surfaces)
    surfaces = *saved_surfaces;
  else
  {
    std::vector<Box> box(whole.n_blocks()), own;
    std::vector<char> deformable(whole.n_blocks(), 0);
    double longest = 0.0;
    const auto& fixed = scene.solver.fixed_groups;
    for (unsigned int b = 0; b < whole.n_blocks(); ++b)
    {
      box[b] = box_of(whole, b);
      deformable[b] = zones.vertex_gridpoint[whole.vertex_start[b]] >= 0;
      if (std::find(fixed.begin(), fixed.end(), whole.group[b]) == fixed.end())
        longest = std::max(longest, (box[b].hi - box[b].lo).maxCoeff());
    }
    std::vector<unsigned int> ghosts;
    for (unsigned int l = 0; l < local.n_blocks(); ++l)
      if (share.blocks().owned[l])
        own.push_back(box[share.global_of(l)]);
      else
        ghosts.push_back(share.global_of(l));
    surfaces = surfaces_near(box, deformable, block_owner, own, ghosts,
                             2.0 * (share.reach() + longest), rank);
  }
  std::vector<int> local_gridpoint;
  MeshShare part =
      zone_part(zones, block_owner, surfaces, rank, share.ranks(), share.comm(), local_gridpoint);
  BlockSystem s;
  s.mesh = std::move(part.mesh);
  keep_part(kept, s.mesh, part, zones, block_owner, local_gridpoint,
            PointHistory(zones.mesh, scene.solver.history_points), share.blocks().local, rank);
  kept.surfaces = surfaces;
  s.mesh_report = zones.report;
  for (unsigned int l = 0; l < local.n_blocks(); ++l)
  {
    const unsigned int b = share.global_of(l);
    if (whole.vertex_start[b + 1] - whole.vertex_start[b] !=
        local.vertex_start[l + 1] - local.vertex_start[l])
      throw std::logic_error("build_block_system_on_ranks: the local model is not the whole's");
  }
  std::unordered_map<unsigned int, std::vector<int>> held_surfaces;
  surfaces_on_gridpoints(zones, share.blocks().local, block_owner, surfaces, local_gridpoint, rank,
                         s.vertex_gridpoint, held_surfaces);
  for (unsigned int l = 0; l < local.n_blocks(); ++l)
    if (s.vertex_gridpoint[local.vertex_start[l]] >= 0)
      s.deformable_blocks.push_back(l);
  s.zones = part_solver(scene, local, s.mesh, part, zones);
  SolverSettings settings = scene.solver;
  if (!scene.rock_materials.empty())
    for (unsigned int b = 0; b < local.n_blocks(); ++b)
      settings.block_density.push_back(scene.density_of(local.group_names[local.group[b]]));
  if (scene.has_initial_stress)
    settings.initial_stress = &scene.initial_stress;
  s.solver = std::make_unique<RigidSolver>(local, scene.density, settings, s.zones.get(),
                                           s.vertex_gridpoint);
  s.solver->set_face_loads(scene.face_pressures);
  s.solver->hold_surfaces(std::move(held_surfaces));
  return s;
}

MovedZones move_zones_on_ranks(const Scene& scene, const WholeZones& zones,
                               const PointHistory& points, const DeformableSolver& before,
                               RankZones& kept, const RankBlocks& held_before,
                               const RankBlocks& next, const BlockModel& next_model, double reach,
                               MPI_Comm comm)
{
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  const std::size_t n_blocks = zones.vertex_start.size() - 1;
  const std::vector<int> old_owner =
      owners_of_blocks(n_blocks, held_before.local, held_before.owned, rank, comm);
  const std::vector<int> block_owner =
      owners_of_blocks(n_blocks, next.local, next.owned, rank, comm);
  // The boxes as the blocks are now: this rank's own, and every deformable
  // block's from its new owner (6 numbers a deformable block, to every rank).
  std::vector<Box> own, box(n_blocks);
  std::vector<char> deformable(n_blocks, 0);
  for (std::size_t b = 0; b < n_blocks; ++b)
    deformable[b] = zones.vertex_gridpoint[zones.vertex_start[b]] >= 0;
  std::vector<double> mine;
  double longest = 0.0;
  const auto& fixed = scene.solver.fixed_groups;
  std::vector<unsigned int> ghosts;
  for (unsigned int l = 0; l < next.local.size(); ++l)
  {
    const unsigned int b = next.local[l];
    if (!next.owned[l])
    {
      ghosts.push_back(b);
      continue;
    }
    const Box e = box_of(next_model, l);
    own.push_back(e);
    if (std::find(fixed.begin(), fixed.end(), next_model.group[l]) == fixed.end())
      longest = std::max(longest, (e.hi - e.lo).maxCoeff());
    if (deformable[b])
    {
      mine.push_back(b);
      mine.insert(mine.end(), e.lo.data(), e.lo.data() + 3);
      mine.insert(mine.end(), e.hi.data(), e.hi.data() + 3);
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, &longest, 1, MPI_DOUBLE, MPI_MAX, comm);
  {
    const std::vector<double> all = gathered_on_every_rank(mine, comm);
    for (std::size_t k = 0; k < all.size(); k += 7)
      box[std::size_t(all[k])] =
          Box{Vec3(all[k + 1], all[k + 2], all[k + 3]), Vec3(all[k + 4], all[k + 5], all[k + 6])};
  }
  const std::vector<unsigned int> surfaces =
      surfaces_near(box, deformable, block_owner, own, ghosts, 2.0 * (reach + longest), rank);

  MovedZones moved;
  std::vector<int> local_gridpoint;
  MeshShare part = zone_part(zones, block_owner, surfaces, rank, ranks, comm, local_gridpoint);
  moved.mesh = std::make_unique<TetMesh>(std::move(part.mesh));
  const std::vector<unsigned int> zones_before = kept.zone;
  keep_part(kept, *moved.mesh, part, zones, block_owner, local_gridpoint, points, next.local, rank);
  kept.surfaces = surfaces;
  surfaces_on_gridpoints(zones, next.local, block_owner, surfaces, local_gridpoint, rank,
                         moved.vertex_gridpoint, moved.held_surfaces);
  moved.solver = part_solver(scene, next_model, *moved.mesh, part, zones);
  const TetMesh& w = zones.mesh;
  move_zone_state(
      before, zones_before, *moved.solver, kept.zone,
      [&](unsigned int g) { return old_owner[w.gridpoint_block[g]]; },
      [&](unsigned int z) { return old_owner[w.zone_block[z]]; }, comm);
  return moved;
}

void add_point_values_on_ranks(std::vector<double>& row, const DeformableSolver& zones,
                               const PointHistory& points, const std::vector<int>& point_gridpoint,
                               const std::vector<int>& point_zone, MPI_Comm comm)
{
  // Every rank fills what it reports and -infinity elsewhere: the maximum
  // over the ranks is the reporting rank's value, bit for bit (a sign of
  // zero included).
  const double none = -std::numeric_limits<double>::infinity();
  const std::vector<double> u = zones.displacements(), v = zones.velocities();
  const std::vector<double> x = points.water ? zones.positions() : std::vector<double>();
  std::vector<double> values;
  for (std::size_t k = 0; k < point_gridpoint.size(); ++k)
  {
    const int g = point_gridpoint[k], z = point_zone[k];
    for (const std::vector<double>* q : {&u, &v})
      for (int d = 0; d < 3; ++d)
        values.push_back(g >= 0 ? (*q)[3 * std::size_t(g) + d] : none);
    // The zone's mean over its stress points, as PointHistory::add_values.
    const unsigned int p = zones.stress_points_per_zone();
    for (int c = 0; c < 6; ++c)
    {
      double sum = 0.0;
      for (unsigned int q = 0; z >= 0 && q < p; ++q)
        sum += zones.stress()[6 * (p * std::size_t(z) + q) + c];
      values.push_back(z >= 0 ? sum / p : none);
    }
    if (points.water)
      values.push_back(g >= 0 ? pore_pressure(zones.water(), points.gravity,
                                              Vec3(x[3 * std::size_t(g)], x[3 * std::size_t(g) + 1],
                                                   x[3 * std::size_t(g) + 2]))
                              : none);
  }
  MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_MAX,
                comm);
  row.insert(row.end(), values.begin(), values.end());
}

} // namespace talus
