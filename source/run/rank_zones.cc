#include <talus/base/exceptions.h>
#include <talus/io/scene_checks.h>
#include <talus/run/rank_share.h>
#include <talus/run/rank_zones.h>
#include <talus/run/run_summary.h>
#include <talus/solver/mesh_share.h>
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
  zones->zones_of_block.assign(whole.n_blocks(), 0.0);
  for (unsigned int b : zones->mesh.zone_block)
    zones->zones_of_block[b] += 1.0;
  zones->meshing_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
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

BlockSystem build_block_system_on_ranks(const Scene& scene, const BlockModel& whole,
                                        BlockModel& local, const WholeZones& zones,
                                        const RankShare& share, RankZones& kept)
{
  const TetMesh& w = zones.mesh;
  const unsigned int rank = static_cast<unsigned int>(share.rank());
  // Each block's owner (every block has one; a deformable block keeps its
  // first: BlockMigration).
  std::vector<int> block_owner(whole.n_blocks(), -1);
  for (unsigned int l = 0; l < local.n_blocks(); ++l)
    if (share.blocks().owned[l])
      block_owner[share.global_of(l)] = static_cast<int>(rank);
  MPI_Allreduce(MPI_IN_PLACE, block_owner.data(), static_cast<int>(block_owner.size()), MPI_INT,
                MPI_MAX, share.comm());
  std::vector<unsigned int> owner(w.n_gridpoints());
  for (unsigned int g = 0; g < w.n_gridpoints(); ++g)
    owner[g] = static_cast<unsigned int>(block_owner[w.gridpoint_block[g]]);
  // Ghost entries without their zones: the surfaces of the other ranks'
  // deformable blocks whose boxes come within 2 (reach + s) of a box of
  // this rank's blocks (s: the longest side of a block that may move, one
  // not of 'Fixed groups': a large fixed boundary block would make every
  // surface near), the distance within which a migration makes a moving
  // block a ghost here (BlockMigration), and those of its deformable ghosts now.
  std::vector<Box> box(whole.n_blocks());
  double longest = 0.0;
  for (unsigned int b = 0; b < whole.n_blocks(); ++b)
  {
    box[b] = Box{whole.vertex[whole.vertex_start[b]], whole.vertex[whole.vertex_start[b]]};
    for (unsigned int v = whole.vertex_start[b]; v < whole.vertex_start[b + 1]; ++v)
    {
      box[b].lo = box[b].lo.cwiseMin(whole.vertex[v]);
      box[b].hi = box[b].hi.cwiseMax(whole.vertex[v]);
    }
    const auto& fixed = scene.solver.fixed_groups;
    if (std::find(fixed.begin(), fixed.end(), whole.group[b]) == fixed.end())
      longest = std::max(longest, (box[b].hi - box[b].lo).maxCoeff());
  }
  const double span = 2.0 * (share.reach() + longest);
  const auto near = [&](const Box& a, const Box& b)
  {
    return (a.lo.array() - span <= b.hi.array()).all() &&
           (b.lo.array() <= a.hi.array() + span).all();
  };
  std::vector<char> ghost_surface(w.n_gridpoints(), 0);
  std::vector<unsigned int> surfaces; // deformable blocks of other ranks held by their surfaces
  for (unsigned int b = 0; b < whole.n_blocks(); ++b)
  {
    if (zones.vertex_gridpoint[whole.vertex_start[b]] < 0 || block_owner[b] == int(rank))
      continue;
    bool held = false;
    for (unsigned int l = 0; l < local.n_blocks() && !held; ++l)
      held = share.blocks().owned[l] && near(box[share.global_of(l)], box[b]);
    held |= share.local_of(b) >= 0; // a ghost now
    if (!held)
      continue;
    surfaces.push_back(b);
    for (unsigned int v = whole.vertex_start[b]; v < whole.vertex_start[b + 1]; ++v)
      ghost_surface[std::size_t(zones.vertex_gridpoint[v])] = 1;
  }
  MeshShare part = share_mesh(w, owner, rank, static_cast<unsigned int>(share.ranks()),
                              share.comm(), &ghost_surface);
  std::vector<int> local_gridpoint(w.n_gridpoints(), -1);
  for (unsigned int i = 0; i < part.gridpoint.size(); ++i)
    local_gridpoint[part.gridpoint[i]] = static_cast<int>(i);

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
  const PointHistory points(w, scene.solver.history_points);
  kept.point_gridpoint.clear();
  kept.point_zone.clear();
  for (std::size_t k = 0; k < points.gridpoint.size(); ++k)
  {
    const unsigned int g = points.gridpoint[k], z = points.zone[k];
    kept.point_gridpoint.push_back(owner[g] == rank ? local_gridpoint[g] : -1);
    int local_zone = -1;
    if (block_owner[w.zone_block[z]] == static_cast<int>(rank))
      local_zone = static_cast<int>(std::lower_bound(part.zone.begin(), part.zone.end(), z) -
                                    part.zone.begin());
    kept.point_zone.push_back(local_zone);
  }

  BlockSystem s;
  s.mesh = std::move(part.mesh);
  kept.zone_global_block = s.mesh.zone_block;
  kept.gridpoint_global_block = s.mesh.gridpoint_block;
  kept.renumber(s.mesh, share);
  s.mesh_report = zones.report;
  for (unsigned int l = 0; l < local.n_blocks(); ++l)
  {
    const unsigned int b = share.global_of(l);
    if (whole.vertex_start[b + 1] - whole.vertex_start[b] !=
        local.vertex_start[l + 1] - local.vertex_start[l])
      throw std::logic_error("build_block_system_on_ranks: the local model is not the whole's");
    for (unsigned int v = whole.vertex_start[b]; v < whole.vertex_start[b + 1]; ++v)
    {
      const int g = zones.vertex_gridpoint[v];
      if (g >= 0 && local_gridpoint[std::size_t(g)] < 0)
        throw std::logic_error("build_block_system_on_ranks: a deformable block's surface "
                               "gridpoint is not held");
      s.vertex_gridpoint.push_back(g < 0 ? -1 : local_gridpoint[std::size_t(g)]);
    }
    if (s.vertex_gridpoint[local.vertex_start[l]] >= 0)
      s.deformable_blocks.push_back(l);
  }
  // Each held deformable block's vertices on their local gridpoints.
  std::unordered_map<unsigned int, std::vector<int>> held_surfaces;
  for (unsigned int b = 0; b < whole.n_blocks(); ++b)
    if (block_owner[b] == int(rank) || std::binary_search(surfaces.begin(), surfaces.end(), b))
      if (zones.vertex_gridpoint[whole.vertex_start[b]] >= 0)
      {
        std::vector<int>& gridpoints = held_surfaces[b];
        for (unsigned int v = whole.vertex_start[b]; v < whole.vertex_start[b + 1]; ++v)
          gridpoints.push_back(local_gridpoint[std::size_t(zones.vertex_gridpoint[v])]);
      }
  ZoneMaterials m = zone_materials(scene, local, s.mesh);
  s.zones = std::make_unique<DeformableSolver>(
      s.mesh, std::move(m.materials), std::move(m.of_zone), scene.solver,
      scene.gridpoint_conditions, scene.face_pressures,
      scene.has_initial_stress ? &scene.initial_stress : nullptr, &part.share);
  if (!zones.face_origins.empty())
  {
    // The origins of the faces this rank holds.
    const std::vector<int>& all = zones.face_origins;
    std::vector<int> origins;
    for (unsigned int f : part.face)
      origins.push_back(all[f]);
    for (unsigned int f : part.second_overlay_face)
      origins.push_back(all[w.n_faces() + f]);
    s.zones->set_face_origins(std::move(origins));
  }
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
