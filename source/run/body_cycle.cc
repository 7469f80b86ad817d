#include "stage_changes.h"
#include <talus/base/wall_clock.h>
#include <talus/io/checkpoint.h>
#include <talus/io/scene_checks.h>
#include <talus/run/body_cycle.h>
#include <talus/run/rank_balance.h>
#include <talus/run/rank_share.h>
#include <talus/run/rank_zones.h>
#include <talus/scene/block_system.h>
#include <talus/solver/implicit_check.h>
#include <talus/solver/mesh_share.h>
#include <talus/solver/zone_migration.h>
#include <talus/zone/hex_mixed.h>
#include <talus/zone/tet10_mesh.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

namespace talus
{

namespace
{
/// Why the implicit check cannot be made for this scene (empty: it can).
std::string implicit_check_refusal(const Scene& scene)
{
  if (scene.solver.dynamic)
    return "the run is dynamic";
  if (scene.deformable.material.model != ZoneModel::elastic)
    return "the zones are not elastic";
  if (scene.has_initial_stress)
    return "the zones have an initial stress";
  if (!scene.stages.empty())
    return "the run has stages";
  for (const GridpointCondition& c : scene.gridpoint_conditions)
    if (c.velocity.norm() > 0.0 || c.velocity_gradient.norm() > 0.0)
      return "a boundary moves at a velocity";
  return "";
}

/// Solves the static elastic problem of the body implicitly, the explicit
/// kernels' own discrete problem, and prints how far the explicit answer
/// (`explicit_u`, or the solver's own) is from it: at the history points
/// (or the gridpoint of largest displacement) and the largest difference
/// anywhere.
void implicit_check(const Scene& scene, DeformableSolver& solver,
                    const std::vector<double>* explicit_u = nullptr)
{
  const auto refuse = [](const std::string& why)
  { std::printf("Implicit check: not made (%s)\n", why.c_str()); };
  const std::string why = implicit_check_refusal(scene);
  if (!why.empty())
    return refuse(why);
  ImplicitCheck check;
  try
  {
    check = check_implicitly(solver, scene.solver.history_points, 1e-10, explicit_u);
  }
  catch (const SolverError& e)
  {
    return refuse(e.what());
  }
  std::printf("Implicit check: the explicit kernels' operator applied matrix-free, %s with AMG of "
              "the 4-node stiffness, %u iterations\n",
              check.implicit.method, check.implicit.iterations);
  for (const ImplicitCheckPoint& p : check.points)
  {
    const Vec3 &e = p.explicit_displacement, &i = p.implicit_displacement;
    std::printf("Implicit check: %s (%.6g, %.6g, %.6g), gridpoint %u: explicit (%.6g, %.6g, %.6g) "
                "m, implicit (%.6g, %.6g, %.6g) m\n",
                scene.solver.history_points.empty() ? "largest displacement at" : "history point",
                p.position[0], p.position[1], p.position[2], p.gridpoint, e[0], e[1], e[2], i[0],
                i[1], i[2]);
  }
  std::printf("Implicit check: largest displacement component %.6g m; largest difference from "
              "the explicit answer %.3g m, %.2g of it\n",
              check.largest, check.difference,
              check.largest > 0.0 ? check.difference / check.largest : 0.0);
}

} // namespace

TetMesh BodyCycle::zones_of(const Scene& scene, const BlockModel& model, MeshReport& report)
{
  if (scene.deformable.mesh_file.empty())
    return mesh_deformable_blocks(scene, model, {0}, report);
  TetMesh mesh = *scene.deformable.mesh;
  // Read in slabs, before the body's group was known.
  order_for_locality(mesh, deformable_zone_order(scene, model));
  if (scene.deformable.material.element == ZoneElement::tet10)
    make_quadratic(mesh);
  report = measure_mesh(mesh);
  return mesh;
}

BodyCycle::BodyCycle(Scene& scene, BlockModel& model, const std::string& prefix)
    : scene_(scene), model_(model), prefix_(prefix), series_(prefix + "_zones.pvd")
{
  print_zone_estimate(scene, model);
  mesh_ = std::make_unique<TetMesh>(zones_of(scene, model, report_));
  const bool from_file = !scene.deformable.mesh_file.empty();
  check_boundary_selections(scene, model, *mesh_);
  std::printf(
      "Zones:        %u %s, %u gridpoints, %u boundary faces (%s; largest edge %.4g m, "
      "smallest height %.4g m), zone volume %.9g m^3\n",
      report_.zones, mesh_->quadratic() ? "10-node tetrahedra" : "tetrahedra", report_.gridpoints,
      report_.boundary_faces,
      from_file ? ("from " + std::filesystem::path(scene.deformable.mesh_file).filename().string())
                      .c_str()
                : edge_length_text(scene.deformable.edge_length).c_str(),
      report_.largest_edge, report_.smallest_height, report_.zone_volume);
  if (report_.hexes > 0)
    std::printf("Hexahedra:    %u (mixed discretization: the tetrahedra are their two overlays of "
                "five)\n",
                report_.hexes);
  // Before anything is written: a stage's region must hold zones.
  for (const StageSpec& stage : scene.stages)
    for (const ExcavationSpec& e : stage.excavations)
    {
      bool any = false;
      for (unsigned int z = 0; z < mesh_->n_zones() && !any; ++z)
        any = e.region.contains(zone_centroid(z), 0.0);
      if (!any)
        throw scene_error(scene, e.section, "",
                          "removes no zone (no zone's centroid lies in the region)",
                          "a region that holds zones of the body");
    }
  points_ = std::make_unique<PointHistory>(*mesh_, scene.solver.history_points);
  points_->water = has_water(scene);
  points_->gravity = scene.solver.gravity.norm();
  whole_zones_ = mesh_->n_zones();
  // Split among ranks, the whole mesh stays until the summary has named
  // the gridpoint of the time step.
  TetMesh whole;
  if (world_ranks() > 1)
  {
    whole = std::move(*mesh_);
    split_among_ranks(whole);
  }
  parallel_ = ParallelEnvironment::unless_running();
  make_solver();
  print_mesh_quality(report_, split_ ? whole : *mesh_, solver_->time_step_gridpoint(), model);
  whole = TetMesh();
  print_nodal_mixed(*solver_);
  std::printf("Time step:    %.6g s (eq. 84%s)\n", solver_->dt(),
              !scene.solver.dynamic && scene.solver.density_scaling ? ", density scaling: unit step"
                                                                    : "");
  print_dynamic_damping(scene.solver, solver_->dt(),
                        scene.solver.time_step > 0.0 ? solver_->dt()
                                                     : solver_->stable_time_step({}, 0.0));
  print_added_mass(scene.solver, solver_->added_mass());
  writer_ = std::make_unique<ZoneWriter>(split_ ? piece_ : *mesh_, scene.output.vtu_encoding);
  for (const GridpointCondition& c : scene.gridpoint_conditions)
    if (std::isfinite(c.velocity_until))
      moving_until_ = std::max(moving_until_, c.velocity_until);
}

void BodyCycle::make_solver()
{
  ZoneMaterials materials = zone_materials(scene_, model_, *mesh_);
  solver_ = std::make_unique<DeformableSolver>(
      *mesh_, std::move(materials.materials), std::move(materials.of_zone), scene_.solver,
      scene_.gridpoint_conditions, scene_.face_pressures,
      scene_.has_initial_stress ? &scene_.initial_stress : nullptr, split_ ? &share_ : nullptr);
}

double BodyCycle::work_ratio() const
{
  double work = 0.0;
  for (unsigned int z = 0; z < mesh_->n_zones(); ++z)
    work += counts(z) && !solver_->zone_removed(z) ? 1.0 : 0.0;
  double largest = work;
  MPI_Allreduce(MPI_IN_PLACE, &largest, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  const double mean = sum_over_ranks(work) / world_ranks();
  return mean > 0.0 ? largest / mean : 1.0;
}

void BodyCycle::rebalance_after_excavation()
{
  const double threshold = rebalance_threshold();
  const double before = work_ratio();
  if (threshold == 0.0 || before <= threshold)
    return;
  const auto start = std::chrono::steady_clock::now();
  // The zones removed so far, by their numbers in the whole mesh.
  std::vector<unsigned char> gone(whole_zones_, 0);
  for (unsigned int z = 0; z < mesh_->n_zones(); ++z)
    if (solver_->zone_removed(z))
      gone[zone_whole_[z]] = 1;
  MPI_Allreduce(MPI_IN_PLACE, gone.data(), static_cast<int>(gone.size()), MPI_UNSIGNED_CHAR,
                MPI_MAX, MPI_COMM_WORLD);
  std::vector<unsigned int> removed;
  for (unsigned int z = 0; z < whole_zones_; ++z)
    if (gone[z])
      removed.push_back(z);
  split_again(removed, true);
  ++rebalances_;
  ratio_before_ = before;
  ratio_after_ = work_ratio();
  // (Indented Time lines are left out when outputs are compared: one rank
  // has no such line.)
  std::printf("   Time = %.3f s to split the zones again (the ranks' largest work over the mean: "
              "%.3f after the excavation, %.3f now)\n",
              seconds_since(start), ratio_before_, ratio_after_);
}

void BodyCycle::split_again(const std::vector<unsigned int>& removed, bool move_state)
{
  // Meshing (or reading the mesh file) gives the same whole mesh again; it
  // lives only while the split is made, as at the start.
  MeshReport report;
  const TetMesh whole = zones_of(scene_, model_, report);
  std::vector<char> gone(whole.n_zones(), 0);
  for (unsigned int z : removed)
    gone[z] = 1;
  const std::vector<unsigned int> old_owner = owner_, old_zone = zone_whole_;
  // The solver until now keeps its mesh until the state has moved (the
  // mesh declared first is destroyed last).
  const std::unique_ptr<TetMesh> before_mesh = std::move(mesh_);
  std::unique_ptr<DeformableSolver> before = std::move(solver_);
  split_among_ranks(whole, &gone);
  make_solver();
  writer_ = std::make_unique<ZoneWriter>(piece_, scene_.output.vtu_encoding);
  split_removed_ = removed;
  if (!move_state)
    return; // a restart: the checkpoint's state follows
  move_zone_state(
      *before, old_zone, *solver_, zone_whole_,
      [&](unsigned int g) { return static_cast<int>(old_owner[g]); },
      [&](unsigned int z) { return static_cast<int>(old_owner[whole.zone_gridpoint[z][0]]); },
      MPI_COMM_WORLD);
  before.reset();
  // What the stages begun changed (materials, boundaries, water), set
  // again as a restart sets it; the damping's running state and the time
  // step with its masses are the run's.
  const DeformableSolver::DampingState damping = solver_->damping_state();
  const DeformableSolver::StepState steps = solver_->step_state();
  for (const StageSpec& stage : stages_begun_)
    set_stage_again(stage);
  solver_->set_damping_state(damping);
  solver_->set_step_state(steps);
}

void BodyCycle::split_among_ranks(const TetMesh& whole, const std::vector<char>* removed)
{
  // Owners from a partition of the body's box into cells, balanced by the
  // zones around the gridpoints (gridpoint_owners).
  Box box{Vec3(whole.position[0], whole.position[1], whole.position[2]), Vec3::Zero()};
  box.hi = box.lo;
  for (unsigned int g = 0; g < whole.n_gridpoints(); ++g)
  {
    const Vec3 p(whole.position[3 * g], whole.position[3 * g + 1], whole.position[3 * g + 2]);
    box.lo = box.lo.cwiseMin(p);
    box.hi = box.hi.cwiseMax(p);
  }
  const unsigned int rank = static_cast<unsigned int>(world_rank()),
                     ranks = static_cast<unsigned int>(world_ranks());
  // About 64 cells along the longest side: fine enough to balance.
  const double cell = std::max((box.hi - box.lo).maxCoeff() / 64.0, 1e-12);
  owner_ = gridpoint_owners(whole, box, cell, ranks, removed);
  MeshShare part = share_mesh(whole, owner_, rank, ranks, MPI_COMM_WORLD);
  // A new object: a solver of the split before keeps its mesh (move_zone_state).
  mesh_ = std::make_unique<TetMesh>(std::move(part.mesh));
  share_ = std::move(part.share);
  zone_whole_ = part.zone;
  split_ = true;
  point_gridpoint_.clear();
  point_zone_.clear();
  piece_zone_.clear();
  piece_ = TetMesh();
  // The history points: a gridpoint reported by its owner, a zone by the
  // owner of its first corner (the rank that counts it).
  for (std::size_t k = 0; k < points_->gridpoint.size(); ++k)
  {
    const unsigned int g = points_->gridpoint[k], z = points_->zone[k];
    int local_g = -1, local_z = -1;
    if (owner_[g] == rank)
      local_g = static_cast<int>(
          std::lower_bound(part.gridpoint.begin(), part.gridpoint.begin() + share_.n_owned, g) -
          part.gridpoint.begin());
    if (owner_[whole.zone_gridpoint[z][0]] == rank)
      local_z = static_cast<int>(std::lower_bound(part.zone.begin(), part.zone.end(), z) -
                                 part.zone.begin());
    point_gridpoint_.push_back(local_g);
    point_zone_.push_back(local_z);
  }
  // This rank's output piece: the zones it counts; a hexahedral zone whole,
  // by the rank that counts its first tetrahedron.
  piece_.position = mesh_->position;
  piece_.gridpoint_block = mesh_->gridpoint_block;
  const std::vector<char> in_hex = zones_in_hexes(*mesh_);
  const auto add = [&](unsigned int z)
  {
    piece_zone_.push_back(z);
    piece_.zone_gridpoint.push_back(mesh_->zone_gridpoint[z]);
    piece_.zone_block.push_back(mesh_->zone_block[z]);
    if (mesh_->quadratic())
      piece_.zone_edge_gridpoint.push_back(mesh_->zone_edge_gridpoint[z]);
  };
  for (unsigned int z = 0; z < mesh_->n_zones(); ++z)
    if (!in_hex[z] && share_.counts(mesh_->zone_gridpoint[z][0]))
      add(z);
  for (unsigned int h = 0; h < mesh_->n_hexes(); ++h)
  {
    const unsigned int first = mesh_->hex_first_zone[h];
    if (!share_.counts(mesh_->zone_gridpoint[first][0]))
      continue;
    piece_.hex_gridpoint.push_back(mesh_->hex_gridpoint[h]);
    piece_.hex_first_zone.push_back(static_cast<unsigned int>(piece_zone_.size()));
    for (unsigned int k = 0; k < TetMesh::tets_per_hex; ++k)
      add(first + k);
  }
}

double BodyCycle::sum_over_ranks(double value) const
{
  if (split_)
    MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  return value;
}

Vec3 BodyCycle::whole_gridpoint_position(unsigned int g) const
{
  const std::vector<double> x = solver_->positions();
  if (!split_)
    return Vec3(x[3 * g], x[3 * g + 1], x[3 * g + 2]);
  Vec3 p = Vec3::Zero();
  if (owner_[g] == static_cast<unsigned int>(world_rank()))
  {
    const auto& whole = share_.whole_gridpoint;
    const std::size_t i =
        std::lower_bound(whole.begin(), whole.begin() + share_.n_owned, g) - whole.begin();
    p = Vec3(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
  }
  MPI_Bcast(p.data(), 3, MPI_DOUBLE, static_cast<int>(owner_[g]), MPI_COMM_WORLD);
  return p;
}

void BodyCycle::add_point_values(std::vector<double>& row) const
{
  if (!split_)
    points_->add_values(row, *solver_);
  else
    add_point_values_on_ranks(row, *solver_, *points_, point_gridpoint_, point_zone_,
                              MPI_COMM_WORLD);
}

Vec3 BodyCycle::zone_centroid(unsigned int z) const
{
  Vec3 c = Vec3::Zero();
  for (int a = 0; a < 4; ++a)
  {
    const unsigned int g = mesh_->zone_gridpoint[z][a];
    c +=
        0.25 * Vec3(mesh_->position[3 * g], mesh_->position[3 * g + 1], mesh_->position[3 * g + 2]);
  }
  return c;
}

std::vector<std::string> BodyCycle::history_columns() const
{
  std::vector<std::string> columns{"step", "time (s)", "unbalanced ratio",
                                   "largest displacement (m)"};
  points_->add_columns(columns);
  for (const ReactionReport& r : scene_.reactions)
    for (const char* q : {" reaction x (N)", " reaction y (N)", " reaction z (N)"})
      columns.push_back(r.name + q);
  // The energy account (see EnergyAccount), last so that the columns
  // before keep their places.
  for (const char* q : {"kinetic energy (J)", "work of gravity (J)", "work of boundaries (J)",
                        "zone elastic energy (J)", "plastic dissipation (J)",
                        "damping dissipation (J)", "energy balance error (J)"})
    columns.push_back(q);
  return columns;
}

std::vector<double> BodyCycle::history_row()
{
  const DeformableSolver& solver = *solver_;
  std::vector<double> row{double(solver.steps_done()), solver.time(), solver.unbalanced_ratio(),
                          largest_gridpoint_displacement(solver)};
  add_point_values(row);
  for (const ReactionReport& r : scene_.reactions)
  {
    const Vec3 f = -solver.support_force(r.region, r.held);
    row.insert(row.end(), {f[0], f[1], f[2]});
  }
  EnergyAccount e;
  solver.add_energy(e);
  row.insert(row.end(), {e.kinetic, e.gravity_work, e.boundary_work, e.zone_elastic, e.plastic,
                         e.damping, e.error()});
  return row;
}

void BodyCycle::write_frame(bool diverged)
{
  if (!scene_.output.write_vtu)
    return;
  if (!split_)
  {
    write_zone_frame(scene_, *mesh_, *solver_, *writer_, series_, frame_++, !diverged);
    return;
  }
  // A piece per rank (the zones it counts) and, by rank 0, the .pvtu that
  // joins them and the series.
  char name[64];
  std::snprintf(name, sizeof name, "_zones_%05u", frame_++);
  const std::string base = scene_.output.base_name + name, &folder = scene_.output.directory;
  std::vector<std::string> pieces;
  for (int r = 0; r < world_ranks(); ++r)
    pieces.push_back(base + "_" + std::to_string(r) + ".vtu");
  const int rank = world_rank();
  write_zone_file(folder + "/" + pieces[std::size_t(rank)], piece_, *solver_, *writer_, !diverged,
                  &piece_zone_);
  if (rank == 0)
  {
    write_pvtu(folder + "/" + base + ".pvtu", folder + "/" + pieces[0], pieces);
    series_.add(solver_->time(), base + ".pvtu");
  }
  MPI_Barrier(MPI_COMM_WORLD); // the frame whole before the run goes on
}

void BodyCycle::register_checkpoint(Checkpoint& checkpoint)
{
  checkpoint.add(series_);
  checkpoint.add(frame_);
  if (!split_)
    return;
  // The split the run has now: a restart makes it again before the zones'
  // state is read.
  checkpoint.add_split(
      [this](CheckpointWriter& out)
      {
        out.put(split_removed_);
        out.put(rebalances_);
        out.put(ratio_before_);
        out.put(ratio_after_);
      },
      [this](CheckpointReader& in)
      {
        std::vector<unsigned int> removed;
        in.get(removed);
        in.get(rebalances_);
        in.get(ratio_before_);
        in.get(ratio_after_);
        for (unsigned int z : removed)
          if (z >= whole_zones_)
            in.mismatch("zone removed when the zones were split again", z, whole_zones_);
        if (!removed.empty())
          split_again(removed, false);
      },
      [this]() { return solver_.get(); });
}

void BodyCycle::begin_stage(const StageSpec& stage)
{
  // A body alone is not cut: a region removes the zones whose centroid
  // lies inside it (exactly its volume when the mesh follows its boundary).
  if (!stage.excavations.empty())
  {
    const std::vector<double> x = solver_->positions();
    std::vector<char> gone(mesh_->n_zones(), 0);
    unsigned int count = 0;
    double volume = 0.0;
    for (unsigned int z = 0; z < mesh_->n_zones(); ++z)
    {
      if (solver_->zone_removed(z))
        continue;
      const bool counted = counts(z);
      const auto& t = mesh_->zone_gridpoint[z];
      Vec3 c = Vec3::Zero(), p[4];
      for (int a = 0; a < 4; ++a)
      {
        p[a] = Vec3(mesh_->position[3 * t[a]], mesh_->position[3 * t[a] + 1],
                    mesh_->position[3 * t[a] + 2]);
        c += 0.25 * p[a];
      }
      for (const ExcavationSpec& e : stage.excavations)
        if (e.region.contains(c, 0.0))
          gone[z] = 1;
      if (gone[z] && counted)
      {
        ++count;
        volume += std::abs((p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0]))) / 6.0;
      }
    }
    solver_->remove_zones(gone);
    count = static_cast<unsigned int>(sum_over_ranks(count));
    volume = sum_over_ranks(volume);
    // Hexahedral zones count twice, once per overlay.
    std::printf("  Excavated:  %u zones, %.9g m^3\n", count,
                report_.hexes > 0 ? 0.5 * volume : volume);
    if (split_)
      rebalance_after_excavation();
  }
  change_rock_materials(stage, true);
  if (stage.changes_water)
  {
    solver_->set_water(stage.water);
    std::printf("  Water:      as '%s / Water' gives it\n", stage.section.c_str());
  }
  if (stage.dynamic != solver_->dynamic())
  {
    solver_->set_dynamic(stage.dynamic);
    std::printf("  Mode:       %s, time step %.6g s\n", stage.dynamic ? "dynamic" : "static",
                solver_->dt());
    SolverSettings now = scene_.solver;
    now.dynamic = stage.dynamic;
    print_dynamic_damping(now, solver_->dt(),
                          now.time_step > 0.0 ? solver_->dt() : solver_->stable_time_step({}, 0.0),
                          "  ");
    print_added_mass(now, solver_->added_mass(), "  ");
  }
  if (stage.changes_boundaries)
  {
    solver_->set_boundaries(stage.boundaries.gridpoint_conditions, stage.boundaries.face_pressures);
    std::printf("  Boundaries: ");
    for (std::size_t k = 0; k < stage.boundary_changes.size(); ++k)
      std::printf("%s%s", k == 0 ? "" : ", ", stage.boundary_changes[k].c_str());
    std::printf("\n");
  }
  if (stage.reset_displacements)
    solver_->reset_displacements();
  stages_begun_.push_back(stage);
}

void BodyCycle::change_rock_materials(const StageSpec& stage, bool account)
{
  // The body is one block: a change of its group takes every zone.
  for (const RockMaterialChange& c : stage.rock_materials)
  {
    if (c.group != model_.group_names[model_.group[0]])
      continue;
    const RockMaterialSpec* rock =
        c.material < 0 ? nullptr : &scene_.rock_materials[std::size_t(c.material)];
    const ZoneMaterial zone = stage_zone_material(scene_, c);
    solver_->change_material(std::vector<char>(mesh_->n_zones(), 1), zone, account);
    if (account)
      std::printf("  Rock:       the body takes %s\n",
                  rock ? ("rock material " + rock->name).c_str() : "the default rock");
  }
}

int BodyCycle::factor_of_safety(const std::vector<StageSpec>&, unsigned int)
{
  // Refused before the run (check_stages): the search's trials are block systems.
  throw InputError("internal: a stage's factor of safety needs blocks");
}

void BodyCycle::set_stage_again(const StageSpec& stage)
{
  change_rock_materials(stage, false);
  if (stage.changes_water)
    solver_->set_water(stage.water);
  if (stage.changes_boundaries)
    solver_->set_boundaries(stage.boundaries.gridpoint_conditions, stage.boundaries.face_pressures);
}

void BodyCycle::restore_stage(const StageSpec& stage)
{
  // The checkpoint's damping state is the run's: the rock remakes the damper.
  DeformableSolver::DampingState damping = solver_->damping_state();
  set_stage_again(stage);
  solver_->set_damping_state(std::move(damping));
  stages_begun_.push_back(stage);
}

std::string BodyCycle::displacement_text() const
{
  char text[64];
  std::snprintf(text, sizeof text, "%.6g m (gridpoints)", largest_gridpoint_displacement(*solver_));
  return text;
}

void BodyCycle::print_end()
{
  const DeformableSolver& solver = *solver_;
  std::printf("Steps:        %lu (time %.6g s)\n", solver.steps_done(), solver.time());
  if (solver.water().active())
  {
    const auto [faces, force] = solver.whole_water(); // on ranks, collective
    std::printf("%s\n",
                water_summary(solver.water(), static_cast<unsigned int>(faces), force).c_str());
  }
  std::printf("Unbalanced force ratio: %.3g\n", solver.unbalanced_ratio());
  std::printf("Largest displacement: %.6g m\n", largest_gridpoint_displacement(solver));
  {
    EnergyAccount e;
    solver.add_energy(e);
    std::printf("Energy balance error: %.2g of the largest energy term (%.6g J; history has "
                "every term)\n",
                e.scale() > 0.0 ? std::abs(e.error()) / e.scale() : 0.0, e.scale());
  }
  unsigned int yielding = 0; // zones with a yielding stress point
  const unsigned int per_zone = solver.stress_points_per_zone();
  for (unsigned int z = 0; z < mesh_->n_zones(); ++z)
  {
    bool any = false;
    for (unsigned int q = 0; q < per_zone; ++q)
      any |= solver.plastic_state()[per_zone * z + q] != 0;
    yielding += any && counts(z);
  }
  yielding = static_cast<unsigned int>(sum_over_ranks(yielding));
  if (scene_.deformable.material.model == ZoneModel::mohr_coulomb)
    std::printf("Plastic zones: %u of %u\n", yielding, whole_zones_);
  for (const ReactionReport& r : scene_.reactions)
  {
    const Vec3 f = -solver.support_force(r.region, r.held);
    std::printf("Reaction of %s on the body: %.9g, %.9g, %.9g N\n", r.name.c_str(), f[0], f[1],
                f[2]);
  }
  if (scene_.deformable.implicit_check)
  {
    if (split_)
      implicit_check_on_ranks();
    else
      implicit_check(scene_, *solver_);
  }
  std::printf("Output:       %s_zones.pvd, %s_history.csv\n", prefix_.c_str(), prefix_.c_str());
  // On standard error: the summary is the serial run's, line for line.
  if (rebalances_ > 0 && world_rank() == 0)
    std::fprintf(stderr,
                 "talus: on %d ranks: %lu rebalances of the body's zones after excavations (the "
                 "ranks' largest work over the mean: %.3f before the last rebalance, %.3f after "
                 "it)\n",
                 world_ranks(), rebalances_, ratio_before_, ratio_after_);
}

void BodyCycle::implicit_check_on_ranks()
{
  const std::string why = implicit_check_refusal(scene_);
  if (!why.empty())
  {
    std::printf("Implicit check: not made (%s)\n", why.c_str());
    return;
  }
  // Each rank's own gridpoints: the whole mesh's number, then u.
  const std::vector<double> u = solver_->displacements();
  std::vector<double> mine;
  mine.reserve(4 * std::size_t(share_.n_owned));
  for (unsigned int i = 0; i < share_.n_owned; ++i)
  {
    mine.push_back(share_.whole_gridpoint[i]);
    mine.insert(mine.end(), u.begin() + 3 * std::ptrdiff_t(i),
                u.begin() + 3 * std::ptrdiff_t(i) + 3);
  }
  const int rank = world_rank(), ranks = world_ranks();
  int count = static_cast<int>(mine.size());
  std::vector<int> counts(static_cast<std::size_t>(ranks)), starts(counts.size(), 0);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  for (std::size_t r = 1; r < counts.size(); ++r)
    starts[r] = starts[r - 1] + counts[r - 1];
  std::vector<double> all(rank == 0 ? std::size_t(starts.back()) + counts.back() : 0);
  MPI_Gatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), starts.data(), MPI_DOUBLE,
              0, MPI_COMM_WORLD);
  if (rank != 0)
    return;
  // The whole body again (the mesher is deterministic), its solver made
  // as one run makes it: the same operator, loads and held components.
  MeshReport report;
  TetMesh whole = zones_of(scene_, model_, report);
  std::vector<double> whole_u(3 * std::size_t(whole.n_gridpoints()), 0.0);
  for (std::size_t k = 0; k + 3 < all.size(); k += 4)
    std::copy(all.begin() + k + 1, all.begin() + k + 4,
              whole_u.begin() + 3 * static_cast<std::ptrdiff_t>(all[k]));
  ZoneMaterials materials = zone_materials(scene_, model_, whole);
  DeformableSolver solver(whole, std::move(materials.materials), std::move(materials.of_zone),
                          scene_.solver, scene_.gridpoint_conditions, scene_.face_pressures,
                          nullptr, nullptr);
  implicit_check(scene_, solver, &whole_u);
}

std::string BodyCycle::unbalanced_where() const
{
  const unsigned int g = solver_->unbalanced_gridpoint();
  const Vec3 x = whole_gridpoint_position(g);
  char where[160];
  std::snprintf(where, sizeof where, "gridpoint %u at %.4g, %.4g, %.4g m", g, x[0], x[1], x[2]);
  return where;
}

} // namespace talus
