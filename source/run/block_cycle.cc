#include "stage_changes.h"
#include <talus/base/exceptions.h>
#include <talus/base/memory.h>
#include <talus/io/checkpoint.h>
#include <talus/io/rank_checkpoint.h>
#include <talus/io/scene_checks.h>
#include <talus/run/block_cycle.h>
#include <talus/scene/build_blocks.h>
#include <talus/solver/mesh_share.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>

namespace talus
{

namespace
{
double now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// Group names resolved, the summary's zone estimate, and PETSc and MPI for
/// the zones of a scene with deformable blocks (none without): talus is
/// serial, so they are started for this process alone.
std::unique_ptr<ParallelEnvironment> prepare(Scene& scene, BlockModel& model, bool meshed)
{
  resolve_group_names(scene, model);
  if (!meshed) // (on ranks the zones were meshed first: mesh_zones_on_ranks)
    print_zone_estimate(scene, model);
  if (scene.deformable.groups.empty())
    return nullptr;
  return ParallelEnvironment::unless_running();
}

/// This rank's share of the model when talus runs on several MPI ranks
/// (null on one): ghosts within the contact tolerance plus three more of
/// motion; on a restart, the blocks the rank held at its checkpoint.
std::unique_ptr<RankShare> share_of(const Scene& scene, const BlockModel& model,
                                    const std::string& restart_from, const WholeZones* zones,
                                    std::vector<unsigned int>& surfaces,
                                    std::unique_ptr<RankShare> built)
{
  if (built)
    return built;
  if (world_ranks() < 2)
    return nullptr;
  const double reach = contact_reach(scene);
  const std::vector<double>* work = zones ? &zones->zones_of_block : nullptr;
  if (!restart_from.empty())
  {
    const RankBlocks saved = read_rank_blocks(restart_from, &surfaces);
    return std::make_unique<RankShare>(model, reach, MPI_COMM_WORLD, &saved, work);
  }
  return std::make_unique<RankShare>(model, reach, MPI_COMM_WORLD, nullptr, work);
}

bool needs_built_model(const Scene& scene)
{
  for (const StageSpec& stage : scene.stages)
    if (stage.changes_boundaries || stage.factor_of_safety)
      return true;
  return false;
}

/// On ranks, deformable blocks among others are meshed before the model is
/// split (with the blocks as built kept first, when a stage needs them).
std::unique_ptr<WholeZones> zones_before_split(Scene& scene, BlockModel& model)
{
  if (world_ranks() < 2)
    return nullptr;
  resolve_group_names(scene, model);
  BlockModel built = needs_built_model(scene) ? model : BlockModel();
  std::unique_ptr<WholeZones> zones = mesh_zones_on_ranks(scene, model);
  if (zones)
    zones->as_built = std::move(built);
  return zones;
}

} // namespace

double contact_reach(const Scene& scene)
{
  return 4.0 * scene.solver.contact.tolerance;
}

bool builds_by_region(const Scene& scene)
{
  // TALUS_SETUP=whole: the whole model on every rank, to compare (benchmarks).
  if (const char* text = std::getenv("TALUS_SETUP"); text != nullptr && *text != '\0')
  {
    if (std::strcmp(text, "whole") == 0)
      return false;
    if (std::strcmp(text, "region") != 0)
      throw InputError(std::string("environment variable TALUS_SETUP: '") + text +
                       "' is not allowed; allowed: region (the default: each rank builds the "
                       "blocks of its region, where the scene allows it) or whole (every rank "
                       "builds the whole model)");
  }
  bool factor_of_safety = scene.strength_reduction.enabled;
  for (const StageSpec& stage : scene.stages)
    factor_of_safety = factor_of_safety || stage.factor_of_safety;
  return scene.deformable.groups.empty() && !factor_of_safety && steps_to_run(scene) > 0;
}

BlockCycle::BlockCycle(Scene& scene, BlockModel& model, const std::string& prefix,
                       const std::string& restart_from, std::unique_ptr<RankShare> share,
                       const ModelDigest* region_digest)
    : whole_zones_(region_digest ? nullptr : zones_before_split(scene, model)),
      share_(share_of(scene, model, restart_from, whole_zones_.get(), saved_surfaces_,
                      std::move(share))),
      region_digest_(region_digest), scene_(scene), model_(share_ ? share_->local() : model),
      prefix_(prefix), parallel_(prepare(scene, model, whole_zones_ != nullptr)),
      // (model: the whole model, on ranks too)
      built_model_(!region_digest && needs_built_model(scene)
                       ? std::make_unique<BlockModel>(whole_zones_ ? whole_zones_->as_built : model)
                       : nullptr),
      meshing_start_(now()),
      // Deformable blocks among rigid ones: their zones, and their surfaces
      // as their shapes for the contacts.
      system_(whole_zones_ ? build_block_system_on_ranks(
                                 scene, model, model_, *whole_zones_, *share_, rank_zones_,
                                 restart_from.empty() ? nullptr : &saved_surfaces_)
                           : build_block_system(scene, model_)),
      block_series_(prefix + "_blocks.pvd"), contact_series_(prefix + "_contacts.pvd"),
      zone_series_(prefix + "_zones.pvd"),
      // the whole model's, by global number
      built_centroid_(region_digest ? region_digest->centroid() : model.centroid)
{
  // (on ranks the meshing came first, before the model was split)
  const double meshing_seconds =
      now() - meshing_start_ + (whole_zones_ ? whole_zones_->meshing_seconds : 0.0);
  // On ranks, on the whole model: every rank finds what one rank would.
  if (region_digest)
    check_boundary_selections(scene, *region_digest, system_.mesh);
  else
    check_boundary_selections(scene, share_ ? model : model_,
                              whole_zones_ ? whole_zones_->mesh : system_.mesh);
  if (share_)
  {
    system_.solver->split_among_ranks(share_->ghost_flags(), reductions_over(share_->comm()));
    system_.solver->share_subcontacts(share_->subcontacts());
    system_.solver->localize_loads(share_->blocks().local);
    // 'Boundary N' face loads selected on the whole model, as on one rank.
    if (!scene.face_pressures.empty())
      system_.solver->set_face_load_table(
          region_digest
              ? region_digest->face_load_table(scene.face_pressures, 0)
              : RigidFaceLoads(model, std::vector<char>(model.n_blocks(), 1), scene.face_pressures)
                    .relative_to(model),
          share_->blocks().local);
  }
  const RigidSolver& solver = *system_.solver;
  const DeformableSolver* zones = system_.zones.get();
  if (zones)
  {
    std::printf("Zones:        %u %s in %u deformable blocks, %u gridpoints (%s)\n",
                system_.mesh_report.zones,
                scene.deformable.material.element == ZoneElement::tet10 ? "10-node tetrahedra"
                                                                        : "tetrahedra",
                system_.mesh_report.blocks, system_.mesh_report.gridpoints,
                edge_length_text(scene.deformable.edge_length).c_str());
    // Indented "Time =" lines are ignored when test output is compared.
    std::printf("   Time = %.3f s to mesh and set up the zones (%.3g zones/s); peak memory %s\n",
                meshing_seconds, system_.mesh_report.zones / meshing_seconds,
                memory_text(peak_memory()).c_str());
    if (system_.mesh_report.hexes > 0)
      std::printf("Hexahedra:    %u (mixed discretization: the tetrahedra are their two overlays "
                  "of five)\n",
                  system_.mesh_report.hexes);
    if (whole_zones_) // the gridpoint named in the whole mesh, of the whole model
      print_mesh_quality(system_.mesh_report, whole_zones_->mesh, zones->time_step_gridpoint(),
                         model);
    else
      print_mesh_quality(system_.mesh_report, system_.mesh, zones->time_step_gridpoint(), model_);
    print_nodal_mixed(*zones);
  }
  if (scene.solver.time_step > 0.0 && solver.stable_time_step() < 1e300)
    std::printf("Time step:    %.6g s (given; eq. 87 allows %.6g s%s)\n", solver.dt(),
                solver.stable_time_step() / scene.solver.time_step_fraction,
                zones ? "; eq. 84 for the zones" : "");
  else if (scene.solver.time_step > 0.0)
    std::printf("Time step:    %.6g s (given; eq. 84 for the zones)\n", solver.dt());
  else
    std::printf("Time step:    %.6g s (eq. 87, fraction %g%s)\n", solver.dt(),
                scene.solver.time_step_fraction, zones ? "; eq. 84 for the zones" : "");
  print_dynamic_damping(scene.solver, solver.dt(), solver.time_step_without_stiffness_damping());
  print_added_mass(scene.solver, solver.added_mass());
  if (zones && share_)
    make_zone_piece();
  else if (zones)
    zone_writer_ = std::make_unique<ZoneWriter>(system_.mesh, scene.output.vtu_encoding);
  // (On ranks, with zones: the points as the whole mesh has them, reported
  // by the ranks rank_zones_ names.)
  points_ =
      std::make_unique<PointHistory>(whole_zones_ ? whole_zones_->mesh : system_.mesh,
                                     zones ? scene.solver.history_points : std::vector<Vec3>{});
  if (whole_zones_ && zones)
  {
    // Kept to split the zones again when deformable blocks change rank.
    whole_zones_->as_built = BlockModel();
    share_->set_zone_surfaces(rank_zones_.surfaces);
    share_->let_zones_follow(
        [this](const RankBlocks& before, const RankBlocks& next, const BlockModel& next_model)
        {
          const double start = now();
          MovedZones moved =
              move_zones_on_ranks(scene_, *whole_zones_, *points_, *system_.zones, rank_zones_,
                                  before, next, next_model, share_->reach(), share_->comm());
          zone_move_seconds_ += now() - start;
          // The old solver lives until the migration has ended (it sends
          // the contacts' gridpoints by their old numbers).
          retired_zones_ = std::move(system_.zones);
          retired_mesh_ = std::move(zone_mesh_);
          system_.zones = std::move(moved.solver);
          zone_mesh_ = std::move(moved.mesh);
          zones_moved_ = true;
          return BlockMigration::ZonesMoved{system_.zones.get(), std::move(moved.vertex_gridpoint),
                                            std::move(moved.held_surfaces)};
        });
  }
  else
    whole_zones_.reset();
  points_->water = has_water(scene);
  points_->gravity = scene.solver.gravity.norm();
  if (!zones && !scene.solver.history_points.empty())
    std::printf("Warning: 'History points' follow deformable blocks; this scene has none\n");
  // 'Joint set N' and 'Joint N' as N, for the contacts' joint_set and joint.
  for (const std::string& section : scene.joint_set_sections)
    joint_numbers_.joint_set_number.push_back(std::stoi(section.substr(section.rfind(' ') + 1)));
  for (const std::string& section : scene.joint_plane_sections)
    joint_numbers_.joint_number.push_back(std::stoi(section.substr(section.rfind(' ') + 1)));
}

namespace
{
/// A stage's boundaries and loads ('Boundary N' face loads selected on the
/// blocks as built, `built`: on ranks (`share`) the whole model, or the
/// `table` of the whole model's digest when the rank built only its
/// region, and each rank takes those of its blocks) into `system`.
void apply_boundaries(BlockSystem& system, const BlockModel* built, const BoundarySet& set,
                      const RankShare* share = nullptr, const RigidFaceLoads* table = nullptr)
{
  RigidSolver& solver = *system.solver;
  if (set.face_pressures.empty())
    solver.set_face_loads(RigidFaceLoads());
  else if (share && table)
    solver.set_face_load_table(*table, share->blocks().local);
  else if (share)
    solver.set_face_load_table(
        RigidFaceLoads(*built, std::vector<char>(built->n_blocks(), 1), set.face_pressures)
            .relative_to(*built),
        share->blocks().local);
  else
  {
    std::vector<char> rigid(built->n_blocks(), 1);
    for (unsigned int b = 0; b < built->n_blocks(); ++b)
      rigid[b] = !solver.is_deformable(b);
    solver.set_face_loads(RigidFaceLoads(*built, rigid, set.face_pressures));
  }
  if (system.zones)
    system.zones->set_boundaries(set.gridpoint_conditions, set.face_pressures);
}

} // namespace

ZoneMaterial stage_zone_material(const Scene& scene, const RockMaterialChange& c)
{
  const RockMaterialSpec* rock =
      c.material < 0 ? nullptr : &scene.rock_materials[std::size_t(c.material)];
  ZoneMaterial zone = rock ? rock->zone : scene.deformable.material;
  zone.element = scene.deformable.material.element;
  zone.nodal_mixed = scene.deformable.nodal_mixed(c.group);
  zone.density = rock ? rock->density : scene.density;
  return zone;
}

namespace
{
/// A stage's 'Rock materials' (of `scene`) into `system`; prints what
/// changed when `account` (a stage's start, not a restart). On ranks
/// (`share`), every rank changes its blocks, ghosts too, and the count is
/// of the blocks owned, summed.
void change_rock_materials(const Scene& scene, const BlockModel& model, BlockSystem& system,
                           const StageSpec& stage, bool account, const RankShare* share = nullptr)
{
  RigidSolver& solver = *system.solver;
  for (const RockMaterialChange& c : stage.rock_materials)
  {
    const RockMaterialSpec* rock =
        c.material < 0 ? nullptr : &scene.rock_materials[std::size_t(c.material)];
    std::vector<char> blocks(model.n_blocks(), 0);
    unsigned int count = 0;
    for (unsigned int b = 0; b < model.n_blocks(); ++b)
      if (model.group_names[model.group[b]] == c.group && !solver.removed(b))
      {
        blocks[b] = 1;
        count += !share || share->blocks().owned[b];
      }
    if (share)
      count = static_cast<unsigned int>(share->sum(static_cast<unsigned long>(count)));
    const ZoneMaterial zone = stage_zone_material(scene, c);
    solver.change_rock(blocks, zone.density, zone, account);
    if (account)
      std::printf("  Rock:       %u blocks of group %s take %s\n", count, c.group.c_str(),
                  rock ? ("rock material " + rock->name).c_str() : "the default rock");
  }
}

} // namespace

void restore_changes(const Scene& scene, const BlockModel& model, const BlockModel* built,
                     BlockSystem& system, const StageSpec& stage, const RankShare* share,
                     const RigidFaceLoads* table)
{
  change_rock_materials(scene, model, system, stage, false);
  if (stage.changes_boundaries)
    apply_boundaries(system, built, stage.boundaries, share, table);
  RigidSolver& solver = *system.solver;
  if (stage.changes_water)
    solver.set_water(stage.water);
  else if (solver.water().active())
    solver.set_water(solver.water()); // on the blocks the state has moving
}

std::optional<RigidFaceLoads> BlockCycle::stage_face_loads(const StageSpec& stage) const
{
  if (!region_digest_ || !stage.changes_boundaries)
    return std::nullopt;
  // Its place among the digest's face loads: the scene's own, then each
  // stage's that changes boundaries.
  std::size_t first = scene_.face_pressures.size();
  for (const StageSpec& s : scene_.stages)
  {
    if (s.section == stage.section)
      return region_digest_->face_load_table(stage.boundaries.face_pressures, first);
    if (s.changes_boundaries)
      first += s.boundaries.face_pressures.size();
  }
  throw std::logic_error("BlockCycle::stage_face_loads: not one of the scene's stages");
}

void BlockCycle::restore_stage(const StageSpec& stage)
{
  stages_begun_.push_back(stage);
  // The loads' state (forces, held velocities) is in the checkpoint; what
  // the materials are is not. The dampers' running state and the time
  // step are the checkpoint's: a rock change makes them anew.
  const Damper damper = system_.solver->damper();
  const std::pair<double, double> steps = system_.solver->time_steps();
  std::optional<DeformableSolver::DampingState> zones;
  std::optional<DeformableSolver::StepState> zone_steps;
  if (system_.zones)
  {
    zones = system_.zones->damping_state();
    zone_steps = system_.zones->step_state();
  }
  // On ranks, the face loads of the blocks each rank holds.
  const std::optional<RigidFaceLoads> table = stage_face_loads(stage);
  restore_changes(scene_, model_, built_model_.get(), system_, stage, share_.get(),
                  table ? &*table : nullptr);
  system_.solver->set_damper(damper);
  system_.solver->set_time_steps(steps);
  if (zones)
  {
    system_.zones->set_damping_state(std::move(*zones));
    system_.zones->set_step_state(*zone_steps);
  }
}

void BlockCycle::make_zone_piece()
{
  zone_piece_ = zone_mesh();
  zone_piece_.zone_block = rank_zones_.zone_global_block;
  zone_writer_ = std::make_unique<ZoneWriter>(zone_piece_, scene_.output.vtu_encoding);
}

void BlockCycle::finish_zone_move()
{
  zones_moved_ = false;
  retired_zones_.reset();
  retired_mesh_.reset();
  system_.mesh = TetMesh(); // the first split's, when it was the one left
                            // What the stages changed of the zones (their materials, boundaries and
  // water), set again on the new split as a restart sets it; the damping's
  // running state and the time step with its masses are the run's.
  DeformableSolver& zones = *system_.zones;
  const DeformableSolver::DampingState damping = zones.damping_state();
  const DeformableSolver::StepState steps = zones.step_state();
  const RigidSolver& solver = *system_.solver;
  const TetMesh& mesh = zone_mesh();
  bool water = has_water(scene_);
  for (const StageSpec& stage : stages_begun_)
  {
    for (const RockMaterialChange& c : stage.rock_materials)
    {
      std::vector<char> chosen(mesh.n_zones(), 0);
      for (unsigned int z = 0; z < mesh.n_zones(); ++z)
      {
        const unsigned int b = mesh.zone_block[z];
        chosen[z] = model_.group_names[model_.group[b]] == c.group && !solver.removed(b);
      }
      zones.change_material(chosen, stage_zone_material(scene_, c), false);
    }
    if (stage.changes_boundaries)
      zones.set_boundaries(stage.boundaries.gridpoint_conditions, stage.boundaries.face_pressures);
    water |= stage.changes_water;
  }
  if (water)
    zones.set_water(solver.water());
  zones.set_damping_state(damping);
  zones.set_step_state(steps);
  share_->set_zone_surfaces(rank_zones_.surfaces);
  make_zone_piece();
}

BlockCycle::~BlockCycle() = default;

void BlockCycle::step()
{
  RigidSolver& solver = *system_.solver;
  solver.step();
  if (share_)
  {
    // The block of the largest force by its global number: the refresh may
    // hand blocks to other ranks and number the rest again.
    const DeformableSolver* zones = system_.zones.get();
    if (zones && zones->unbalanced_ratio() > solver.rigid_unbalanced_ratio())
    {
      // A gridpoint's: every rank knows which (of the whole mesh).
      unbalanced_ = {1.0, rank_zones_.block_of_whole_gridpoint(zones->unbalanced_gridpoint())};
    }
    else
    {
      const unsigned int b = solver.unbalanced_block();
      const bool mine = b < model_.n_blocks() && share_->blocks().owned[b];
      unbalanced_ = {mine ? solver.local_unbalanced_force() : -1.0,
                     mine ? share_->global_of(b) : 0};
    }
    share_->refresh(solver);
    if (zones && share_->migrations() != migrations_seen_)
    {
      // The zones' blocks by their new local numbers.
      migrations_seen_ = share_->migrations();
      rank_zones_.renumber(zone_mesh(), *share_);
    }
    if (zones_moved_)
      finish_zone_move();
  }
}
unsigned long BlockCycle::steps_done() const
{
  return system_.solver->steps_done();
}
double BlockCycle::time() const
{
  return system_.solver->time();
}
double BlockCycle::ratio() const
{
  return system_.solver->unbalanced_ratio();
}

std::vector<std::string> BlockCycle::history_columns() const
{
  std::vector<std::string> columns{"step", "time (s)", "unbalanced ratio"};
  for (const std::string& c : EnergyAccount::column_names())
    columns.push_back(c);
  for (unsigned int b : scene_.solver.history_blocks)
  {
    for (const char* q : {"ux", "uy", "uz", "vx", "vy", "vz"})
      columns.push_back("block " + std::to_string(b) + " " + q + (q[0] == 'u' ? " (m)" : " (m/s)"));
    if (has_water(scene_))
      columns.push_back("block " + std::to_string(b) + " pore pressure (Pa)");
  }
  points_->add_columns(columns);
  return columns;
}

std::vector<double> BlockCycle::history_row()
{
  const RigidSolver& solver = *system_.solver;
  const EnergyAccount e = solver.energy_account();
  std::vector<double> row{double(solver.steps_done()), solver.time(), solver.unbalanced_ratio()};
  e.append_to(row);
  const bool water = has_water(scene_);
  const Vec3 zero = Vec3::Zero();
  for (unsigned int global : scene_.solver.history_blocks)
  {
    // On ranks: the owner's values, zeros elsewhere (summed below).
    const int b =
        share_ ? (share_->owns(global) ? share_->local_of(global) : -1) : static_cast<int>(global);
    for (const std::vector<Vec3>* q : {&solver.displacement, &solver.velocity})
      for (int d = 0; d < 3; ++d)
        row.push_back((b >= 0 ? (*q)[std::size_t(b)] : zero)[d]);
    // At the block's centroid now: the water it stands in.
    if (water)
      row.push_back(b < 0 ? 0.0
                          : pore_pressure(solver.water(), scene_.solver.gravity.norm(),
                                          model_.centroid[std::size_t(b)]));
  }
  if (share_)
  {
    // The energies are the whole model's on every rank (RigidSolver::
    // energy_account); the blocks' columns after them are sums of the
    // ranks' shares (the owner's values and zeros).
    const std::size_t first = 3 + EnergyAccount::column_names().size();
    std::vector<double> shares(row.begin() + first, row.end());
    share_->sum(shares);
    std::copy(shares.begin(), shares.end(), row.begin() + first);
    if (system_.zones)
      add_point_values_on_ranks(row, *system_.zones, *points_, rank_zones_.point_gridpoint,
                                rank_zones_.point_zone, share_->comm());
  }
  else if (system_.zones)
    points_->add_values(row, *system_.zones);
  return row;
}

std::string
BlockCycle::write_pieces(const std::string& name,
                         const std::function<void(const std::string&)>& write_piece) const
{
  const std::string& folder = scene_.output.directory;
  std::vector<std::string> pieces;
  for (int r = 0; r < share_->ranks(); ++r)
    pieces.push_back(name + "_" + std::to_string(r) + ".vtu");
  write_piece(pieces[std::size_t(share_->rank())]);
  if (share_->rank() == 0)
    write_pvtu(folder + "/" + name + ".pvtu", folder + "/" + pieces[0], pieces);
  MPI_Barrier(share_->comm()); // the frame whole before the run goes on
  return name + ".pvtu";
}

void BlockCycle::write_frame(bool diverged)
{
  if (!scene_.output.write_vtu)
    return;
  const RigidSolver& solver = *system_.solver;
  const bool lists = !share_ || share_->rank() == 0; // writes the series
  char name[64];
  std::snprintf(name, sizeof name, "_blocks_%05u", frame_++);
  const std::string blocks = scene_.output.base_name + name;
  std::vector<BlockField> fields{{"displacement", 3, {}}, {"velocity", 3, {}}, {"rotation", 3, {}}};
  for (unsigned int b = 0; b < model_.n_blocks(); ++b)
    for (int d = 0; d < 3; ++d)
    {
      fields[0].values.push_back(solver.displacement[b][d]);
      fields[1].values.push_back(solver.velocity[b][d]);
      fields[2].values.push_back(solver.rotation[b][d]);
    }
  std::string vtu = blocks + ".vtu";
  if (share_)
  {
    // This rank's blocks (not its ghosts), by their numbers in the model.
    std::vector<char> gone = solver.removed_blocks();
    for (std::size_t b = 0; b < gone.size(); ++b)
      gone[b] |= !share_->blocks().owned[b];
    vtu =
        write_pieces(blocks,
                     [&](const std::string& piece)
                     {
                       write_blocks_vtu(scene_.output.directory + "/" + piece, model_, fields,
                                        scene_.output.vtu_encoding, &gone, &share_->blocks().local);
                     });
  }
  else
    write_blocks_vtu(scene_.output.directory + "/" + vtu, model_, fields,
                     scene_.output.vtu_encoding, &solver.removed_blocks());
  if (lists)
    block_series_.add(solver.time(), vtu);
  if (diverged)
  {
    if (system_.zones)
      write_zones(false);
    return;
  }
  std::snprintf(name, sizeof name, "_contacts_%05u", frame_ - 1);
  const std::string contacts = scene_.output.base_name + name;
  std::string contacts_vtu = contacts + ".vtu";
  const ContactSet& cs = solver.contacts();
  if (share_)
  {
    // The sub-contacts this rank counts (of contacts whose first block it owns).
    std::vector<unsigned int> counted;
    for (unsigned int i = 0; i < cs.n_subcontacts(); ++i)
      if (share_->blocks().owned[cs.block_a[cs.sc_contact[i]]])
        counted.push_back(i);
    contacts_vtu =
        write_pieces(contacts,
                     [&](const std::string& piece)
                     {
                       write_contacts_vtu(scene_.output.directory + "/" + piece, cs, model_,
                                          joint_numbers_, scene_.output.vtu_encoding,
                                          &solver.water(), scene_.solver.gravity.norm(), &counted);
                     });
  }
  else
    write_contacts_vtu(scene_.output.directory + "/" + contacts_vtu, cs, model_, joint_numbers_,
                       scene_.output.vtu_encoding, &solver.water(), scene_.solver.gravity.norm());
  if (lists)
    contact_series_.add(solver.time(), contacts_vtu);
  if (system_.zones)
    write_zones(true);
}

void BlockCycle::write_zones(bool with_stress)
{
  if (!share_)
  {
    write_zone_frame(scene_, system_.mesh, *system_.zones, *zone_writer_, zone_series_,
                     zone_frame_++, with_stress);
    return;
  }
  char name[64];
  std::snprintf(name, sizeof name, "_zones_%05u", zone_frame_++);
  const std::string vtu =
      write_pieces(scene_.output.base_name + name,
                   [&](const std::string& piece)
                   {
                     write_zone_file(scene_.output.directory + "/" + piece, zone_piece_,
                                     *system_.zones, *zone_writer_, with_stress);
                   });
  if (share_->rank() == 0)
    zone_series_.add(system_.zones->time(), vtu);
}

void BlockCycle::register_checkpoint(Checkpoint& checkpoint)
{
  for (PvdSeries* s : {&block_series_, &contact_series_, &zone_series_})
    checkpoint.add(*s);
  checkpoint.add(frame_);
  checkpoint.add(zone_frame_);
  if (share_)
  {
    checkpoint.add(*share_);
    checkpoint.add(unbalanced_.first);
    checkpoint.add(unbalanced_.second);
  }
}

void BlockCycle::begin_stage(const StageSpec& stage)
{
  stages_begun_.push_back(stage);
  RigidSolver& solver = *system_.solver;
  // Excavations: the blocks of the groups named, and those whose centroid
  // (as built) lies in a region, which the model was cut along. On ranks
  // each rank removes its blocks so chosen, ghosts too (the same rule
  // keeps them equal to their owners), and counts those it owns.
  const auto owned = [&](unsigned int b) { return !share_ || share_->blocks().owned[b]; };
  const auto global = [&](unsigned int b) { return share_ ? share_->global_of(b) : b; };
  std::vector<unsigned int> gone;
  std::vector<double> gone_volume(share_ ? built_centroid_.size() : 0, 0.0); // by global number
  unsigned long n_gone = 0;
  double volume = 0.0;
  const double on_face = 1e-9 * scene_.brick.diagonal();
  for (unsigned int b = 0; b < model_.n_blocks(); ++b)
  {
    if (solver.removed(b))
      continue;
    bool go = std::find(stage.excavate_groups.begin(), stage.excavate_groups.end(),
                        model_.group_names[model_.group[b]]) != stage.excavate_groups.end();
    for (const ExcavationSpec& e : stage.excavations)
      go |= e.region.contains(built_centroid_[global(b)], on_face);
    if (go)
    {
      gone.push_back(b);
      if (!owned(b))
        continue;
      ++n_gone;
      volume += model_.volume[b];
      if (share_)
        gone_volume[global(b)] = model_.volume[b];
    }
  }
  if (share_)
  {
    // The serial sum, in the order of the blocks' numbers (the others' zeros add nothing).
    n_gone = share_->sum(n_gone);
    share_->sum(gone_volume);
    volume = 0.0;
    for (double v : gone_volume)
      volume += v;
  }
  if (n_gone > 0)
  {
    solver.remove_blocks(gone); // on ranks, on every rank (masses and the step are reduced)
    std::printf("  Excavated:  %lu blocks, %.9g m^3\n", n_gone, volume);
    if (share_) // the work left is checked at once, not at the next hundredth step
      share_->check_balance_soon();
  }
  unsigned long fixed = 0, freed = 0;
  for (unsigned int b = 0; b < model_.n_blocks(); ++b)
  {
    const std::string& g = model_.group_names[model_.group[b]];
    if (std::find(stage.fix_groups.begin(), stage.fix_groups.end(), g) != stage.fix_groups.end() &&
        !solver.fixed[b] && !solver.removed(b))
    {
      solver.set_fixed(b, true);
      fixed += owned(b);
    }
    if (std::find(stage.free_groups.begin(), stage.free_groups.end(), g) !=
            stage.free_groups.end() &&
        solver.fixed[b] && !solver.removed(b))
    {
      solver.set_fixed(b, false);
      freed += owned(b);
    }
  }
  if (share_)
  {
    fixed = share_->sum(fixed);
    freed = share_->sum(freed);
  }
  if (fixed + freed > 0)
    std::printf("  Fixed:      %lu blocks held, %lu let go\n", fixed, freed);
  if (stage.changes_water)
  {
    solver.set_water(stage.water);
    std::printf("  Water:      as '%s / Water' gives it\n", stage.section.c_str());
  }
  else if (solver.water().active() && fixed + freed + n_gone > 0)
    solver.set_water(solver.water()); // on the blocks that move now
  for (const JointMaterialChange& c : stage.joint_materials)
    solver.change_joint_material(c.origin, c.material);
  if (!stage.joint_materials.empty())
    std::printf("  Joints:     %zu joint sets or joints change material\n",
                stage.joint_materials.size());
  for (const GroupContactChange& c : stage.group_contacts)
    solver.change_group_pair_material(model_.group_index(c.a), model_.group_index(c.b), c.material);
  if (!stage.group_contacts.empty())
    std::printf("  Joints:     %zu pairs of groups change contact material\n",
                stage.group_contacts.size());
  change_rock_materials(scene_, model_, system_, stage, true, share_.get());
  if (stage.dynamic != solver.dynamic())
  {
    solver.set_dynamic(stage.dynamic);
    std::printf("  Mode:       %s, time step %.6g s\n", stage.dynamic ? "dynamic" : "static",
                solver.dt());
    SolverSettings now = scene_.solver;
    now.dynamic = stage.dynamic;
    print_dynamic_damping(now, solver.dt(), solver.time_step_without_stiffness_damping(), "  ");
    print_added_mass(now, solver.added_mass(), "  ");
  }
  if (stage.changes_boundaries)
  {
    solver.set_loads(stage.boundaries.loads);
    const std::optional<RigidFaceLoads> table = stage_face_loads(stage);
    apply_boundaries(system_, built_model_.get(), stage.boundaries, share_.get(),
                     table ? &*table : nullptr);
    std::printf("  Boundaries: ");
    for (std::size_t k = 0; k < stage.boundary_changes.size(); ++k)
      std::printf("%s%s", k == 0 ? "" : ", ", stage.boundary_changes[k].c_str());
    std::printf("\n");
  }
  if (stage.reset_displacements)
    solver.reset_displacements();
}

std::pair<double, unsigned int> BlockCycle::largest_displacement() const
{
  // The first block of the largest displacement, as a serial loop finds it.
  // An excavated block is not in the model any more (and on ranks no rank
  // holds it after the next migration).
  const RigidSolver& solver = *system_.solver;
  double largest = 0.0;
  unsigned int at = 0;
  for (unsigned int b = 0; b < model_.n_blocks(); ++b)
    if ((!share_ || share_->blocks().owned[b]) && !solver.removed(b) &&
        solver.displacement[b].norm() > largest)
    {
      largest = solver.displacement[b].norm();
      at = share_ ? share_->global_of(b) : b;
    }
  if (share_)
    return share_->largest(largest, at);
  return {largest, at};
}

std::string BlockCycle::displacement_text() const
{
  const auto [largest, moved_most] = largest_displacement();
  char text[160];
  std::snprintf(text, sizeof text, "%.6g m (block %u)", largest, moved_most);
  std::string s = text;
  if (system_.zones)
  {
    std::snprintf(text, sizeof text, ", gridpoints %.6g m",
                  largest_gridpoint_displacement(*system_.zones));
    s += text;
  }
  return s;
}

void BlockCycle::print_end()
{
  const RigidSolver& solver = *system_.solver;
  const SolverReport r = solver.report();
  const ContactSet& cs = solver.contacts();
  // On ranks, each contact is counted by the owner of its first block.
  const auto counted = [&](unsigned int c)
  { return cs.alive[c] && (!share_ || share_->blocks().owned[cs.block_a[c]]); };
  unsigned long contacts = r.contacts, subcontacts = r.subcontacts;
  if (share_)
  {
    contacts = subcontacts = 0;
    for (unsigned int c = 0; c < cs.n_slots(); ++c)
      contacts += counted(c);
    for (unsigned int i = 0; i < cs.n_subcontacts(); ++i)
      subcontacts += counted(cs.sc_contact[i]);
    contacts = share_->sum(contacts);
    subcontacts = share_->sum(subcontacts);
  }
  std::printf("Steps:        %lu (time %.6g s)\n", r.steps, r.time);
  std::printf("Contacts:     %lu with %lu sub-contacts\n", contacts, subcontacts);
  if (solver.water().active() && share_)
  {
    // The owners' water forces summed in the order of the blocks' numbers,
    // as on one rank (the others' zeros add nothing).
    const WaterLoads& w = solver.water_loads();
    std::vector<double> by_global(3 * built_centroid_.size() + 1, 0.0);
    for (std::size_t k = 0; k < w.blocks().size(); ++k)
      for (int d = 0; d < 3; ++d)
        by_global[3 * solver.water_global()[k] + d] = w.forces()[k][d];
    by_global.back() = w.faces_below();
    share_->sum(by_global);
    Vec3 force = Vec3::Zero();
    for (std::size_t g = 0; g < built_centroid_.size(); ++g)
      force += Vec3(by_global[3 * g], by_global[3 * g + 1], by_global[3 * g + 2]);
    if (system_.zones) // the zones' water after the blocks', as one run adds them
    {
      const auto [faces, zone_force] = system_.zones->whole_water();
      by_global.back() += double(faces);
      force += zone_force;
    }
    std::printf(
        "%s\n",
        water_summary(solver.water(), static_cast<unsigned int>(by_global.back()), force).c_str());
  }
  else if (solver.water().active())
    std::printf("%s\n", solver.water_summary().c_str());
  if (scene_.joint_material_names.size() > 1)
  {
    // Which material the contacts took: the check that the rules say what
    // was meant.
    std::vector<double> count(scene_.joint_material_names.size(), 0.0);
    for (unsigned int c = 0; c < cs.n_slots(); ++c)
      if (counted(c))
        count[cs.material[c]] += 1.0;
    if (share_)
      share_->sum(count); // whole numbers: exact
    std::printf("Joint materials:");
    for (std::size_t k = 0; k < count.size(); ++k)
      std::printf("%s %s %.0f", k == 0 ? "" : ",", scene_.joint_material_names[k].c_str(),
                  count[k]);
    std::printf(" contacts\n");
  }
  std::printf("Unbalanced force ratio: %.3g\n", r.ratio);
  const auto [largest, moved_most] = largest_displacement();
  if (model_.n_blocks() > 0 || share_)
    std::printf("Largest displacement: %.6g m (block %u)\n", largest, moved_most);
  for (unsigned int global : scene_.solver.history_blocks)
  {
    std::vector<double> u(3, 0.0);
    const int b =
        share_ ? (share_->owns(global) ? share_->local_of(global) : -1) : static_cast<int>(global);
    if (b >= 0)
      for (int d = 0; d < 3; ++d)
        u[std::size_t(d)] = solver.displacement[std::size_t(b)][d];
    if (share_)
      share_->sum(u); // the owner's, and zeros
    std::printf("Block %u displacement: %.9g, %.9g, %.9g m\n", global, u[0], u[1], u[2]);
  }
  const double total = r.seconds_detection + r.seconds_planes + r.seconds_forces + r.seconds_motion;
  std::printf(
      "   Time = %.3f s in the cycle: detection %.0f %%, common planes %.0f %%, forces %.0f %%, "
      "motion %.0f %%\n",
      total, 100 * r.seconds_detection / total, 100 * r.seconds_planes / total,
      100 * r.seconds_forces / total, 100 * r.seconds_motion / total);
  if (share_ && system_.zones && share_->zone_moves() > 0) // (rank 0's wall time)
    std::printf("   Time = %.3f s to split the zones again (deformable blocks changed rank)\n",
                zone_move_seconds_);
  if (system_.zones)
    std::printf("Largest gridpoint displacement: %.6g m\n",
                largest_gridpoint_displacement(*system_.zones));
  std::printf("Output:       %s_blocks.pvd, %s_contacts.pvd, %s%s_history.csv\n", prefix_.c_str(),
              prefix_.c_str(), system_.zones ? (prefix_ + "_zones.pvd, ").c_str() : "",
              prefix_.c_str());
  // On standard error: the summary is the serial run's, line for line.
  if (share_ && share_->rank() == 0)
  {
    const RankBalance& b = share_->balance();
    char rebalances[200];
    if (b.off())
      std::snprintf(rebalances, sizeof rebalances, "rebalance off");
    else if (b.rebalances() == 0) // no before and after to give
      std::snprintf(rebalances, sizeof rebalances,
                    "0 rebalances (the ranks' largest work over the mean at the last check: "
                    "%.3f)",
                    b.measured());
    else
      std::snprintf(rebalances, sizeof rebalances,
                    "%lu rebalances (the ranks' largest work over the mean: %.3f before the last "
                    "rebalance, %.3f expected after it, %.3f at the last check)",
                    b.rebalances(), b.before(), b.expected(), b.measured());
    if (b.refused() > 0) // regions that needed a deformable block's surface where it is not held
      std::snprintf(rebalances + std::strlen(rebalances),
                    sizeof rebalances - std::strlen(rebalances), ", %lu new regions refused",
                    b.refused());
    char zones[120] = "";
    if (system_.zones) // deformable blocks that changed rank
      std::snprintf(zones, sizeof zones, "; the zones split again at %lu of the events",
                    share_->zone_moves());
    std::fprintf(stderr,
                 "talus: on %d ranks: %lu migration events (the sum of their steps %lu), %lu "
                 "owner changes, %s%s\n",
                 share_->ranks(), share_->migrations(), share_->event_steps(),
                 share_->owner_changes(), rebalances, zones);
  }
}

std::string BlockCycle::unbalanced_where() const
{
  if (share_)
  {
    // The rank with the largest force names its block, and sends where it is.
    // (A rank with no free block offers none.)
    const auto [force, global] = share_->largest(unbalanced_.first, unbalanced_.second);
    (void)force;
    const int at = share_->owns(global) ? share_->local_of(global) : -1;
    std::vector<double> where(4, 0.0); // centroid and group
    if (at >= 0)
    {
      for (int d = 0; d < 3; ++d)
        where[std::size_t(d)] = model_.centroid[std::size_t(at)][d];
      where[3] = model_.group[std::size_t(at)];
    }
    share_->sum(where);
    char text[200];
    std::snprintf(text, sizeof text, "block %u (group %s, centroid %.4g, %.4g, %.4g m)", global,
                  model_.group_names[std::size_t(where[3])].c_str(), where[0], where[1], where[2]);
    return text;
  }
  const unsigned int b = system_.solver->unbalanced_block();
  const Vec3& c = model_.centroid[b];
  char where[200];
  std::snprintf(where, sizeof where, "block %u (group %s, centroid %.4g, %.4g, %.4g m)", b,
                model_.group_names[model_.group[b]].c_str(), c[0], c[1], c[2]);
  return where;
}

} // namespace talus
