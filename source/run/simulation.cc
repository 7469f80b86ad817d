#include <talus/base/exceptions.h>
#include <talus/base/memory.h>
#include <talus/base/wall_clock.h>
#include <talus/io/checkpoint.h>
#include <talus/io/factor_of_safety_run.h>
#include <talus/io/file_output.h>
#include <talus/io/history_file.h>
#include <talus/io/rank_checkpoint.h>
#include <talus/io/scene_checks.h>
#include <talus/run/block_cycle.h>
#include <talus/run/body_cycle.h>
#include <talus/run/rank_share.h>
#include <talus/run/simulation.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>

namespace talus
{

namespace
{
/// Whether the scene is one deformable body alone (no contacts to find).
bool body_alone(const Scene& scene, const BlockModel& model)
{
  return !scene.deformable.groups.empty() && model.n_blocks() == 1;
}

/// Warns, and returns exit_not_in_equilibrium, when a static stage with a
/// target ratio ended above it; 0 otherwise.
int static_stage_end(const StageSpec& stage, const RunEnd& end, bool staged)
{
  if (stage.dynamic || stage.target_ratio <= 0.0 || end.ratio < stage.target_ratio)
    return 0;
  const std::string where = staged ? "'" + stage.section + "' stopped at its step limit ('Steps'"
                                   : "the run stopped at its step limit ('Steps'";
  std::printf("Warning: %s = %lu) with the unbalanced force ratio at %.3g, above 'Target ratio' "
              "= %g: the model is not in equilibrium (exit code %d); the largest unbalanced "
              "force is on %s; raise 'Steps', or set 'Target ratio' = 0 to run a fixed number "
              "of steps\n",
              where.c_str(), stage.steps, end.ratio, stage.target_ratio, exit_not_in_equilibrium,
              end.where.c_str());
  return exit_not_in_equilibrium;
}
} // namespace

Simulation::Simulation(const std::string& parameter_file, std::string restart_from, bool check_only)
    : start_(std::chrono::steady_clock::now()), parameter_file_(parameter_file),
      restart_from_(std::move(restart_from)), check_only_(check_only)
{
  // A restart writes into the checkpoint's folder, prepared there; a check
  // prepares nothing.
  // On several MPI ranks (mpirun), rank 0 prepares the output folder once
  // the scene is known to run on ranks.
  const int ranks = world_ranks();
  scene_ = read_scene(parameter_file_, restart_from_.empty() && !check_only_ && ranks == 1);
  if (!restart_from_.empty())
    continue_in_checkpoint_folder(restart_from_, scene_);
  if (ranks > 1)
  {
    check_runs_on_ranks(scene_, ranks);
    if (!check_only_)
      agree_on_input_errors(
          [&]()
          {
            if (world_rank() == 0)
              try
              {
                prepare_output_directory(scene_.output.directory);
              }
              catch (const InputError& e)
              {
                throw scene_error(scene_, "Output", "Directory", e.what(),
                                  "a folder that can be created and written");
              }
          });
  }
  // read_scene has checked every value and prepared the output folder;
  // what needs the blocks is checked before anything is written.
  if (ranks > 1 && !check_only_ && builds_by_region(scene_))
  {
    by_region_ = true;
    digest_ = ModelDigest(scene_, true);
    model_ = scene_groups(scene_);
    // A restart: each rank takes the blocks it held at its checkpoint.
    std::optional<RankBlocks> saved;
    if (!restart_from_.empty()) // (a file one rank refuses stops them all)
      agree_on_input_errors([&]() { saved = read_rank_blocks(restart_from_); });
    share_ = std::make_unique<RankShare>(
        scene_, report_, contact_reach(scene_), MPI_COMM_WORLD, &digest_,
        [&]() { check_built_model(scene_, digest_, report_, nullptr); }, saved ? &*saved : nullptr);
  }
  else
  {
    model_ = build_blocks(scene_, report_);
    digest_ = ModelDigest::of(scene_, model_);
    check_built_model(scene_, digest_, report_, &model_);
  }
  digest_.resolve_history_blocks(scene_);
  prefix_ = scene_.output.directory + "/" + scene_.output.base_name;
}

Simulation::Simulation(Scene scene)
    : start_(std::chrono::steady_clock::now()), parameter_file_(scene.parameter_file),
      check_only_(false), scene_(std::move(scene))
{
  model_ = build_blocks(scene_, report_);
  digest_ = ModelDigest::of(scene_, model_);
  check_built_model(scene_, digest_, report_, &model_);
  digest_.resolve_history_blocks(scene_);
  prefix_ = scene_.output.directory + "/" + scene_.output.base_name;
}

Simulation::~Simulation() = default;

void Simulation::print_model() const
{
  const Scene& scene = scene_;
  const ModelDigest& model = digest_;
  std::printf("talus: scene %s\n", std::filesystem::path(parameter_file_).filename().c_str());
  std::printf("Blocks:       %u\n", model.n_blocks());
  std::printf("Faces:        %lu\n", model.n_faces());
  std::printf("Vertices:     %lu\n", model.n_vertices());
  std::printf("Total volume: %.9g m^3 (brick %.9g m^3)\n", model.total_volume(),
              scene.brick.volume());
  for (std::size_t e = 0; e < scene.excavations.size(); ++e)
    std::printf("Excavated:    %.9g m^3 (%s; region volume %.9g m^3)\n",
                report_.excavated_volume[e], scene.excavations[e].description.c_str(),
                scene.excavations[e].region.volume);
  std::size_t k = 0;
  for (const StageSpec& stage : scene.stages)
    for (const ExcavationSpec& e : stage.excavations)
      if (k < report_.stage_excavated_volume.size())
        std::printf("To excavate:  %.9g m^3 (%s; region volume %.9g m^3)\n",
                    report_.stage_excavated_volume[k++], e.description.c_str(), e.region.volume);
  if (scene.rock_materials.empty())
    std::printf("Mass:         %.9g kg (density %g kg/m^3)\n", model.total_volume() * scene.density,
                scene.density);
  else
  {
    std::printf("Mass:         %.9g kg (density %g kg/m^3; rock materials:", model.mass(),
                scene.density);
    for (const RockMaterialSpec& r : scene.rock_materials)
      std::printf(" %s %g", r.name.c_str(), r.density);
    std::printf(")\n");
  }
  // In the order the model numbers its groups.
  for (const std::string& group : model_.group_names)
    if (const unsigned int count = model.blocks_in(group); count > 0)
      std::printf("Group %-8s %u blocks\n", group.c_str(), count);
  std::printf("Cuts:         %lu\n", report_.cutting.cuts);
  if (report_.cutting.skipped_slivers > 0)
    std::printf("Warning: %lu cuts were not made because a piece would have been smaller than "
                "the minimum block volume %g m^3 (smallest %.3g m^3 near %.4g, %.4g, %.4g)\n",
                report_.cutting.skipped_slivers, scene.cutting.minimum_volume,
                report_.cutting.smallest_refused, report_.cutting.smallest_refused_at[0],
                report_.cutting.smallest_refused_at[1], report_.cutting.smallest_refused_at[2]);
  print_history_blocks(scene, model);
}

void Simulation::check_calculation()
{
  std::printf("talus: scene %s\n", std::filesystem::path(parameter_file_).filename().c_str());
  std::printf("Blocks:       %u\n", model_.n_blocks());
  print_zone_estimate(scene_, model_);
  if (steps_to_run(scene_) == 0)
    return;
  // What the first step needs: the zones and the solvers, whose checks
  // refuse an unstable time step and the like.
  std::unique_ptr<ParallelEnvironment> parallel;
  if (!scene_.deformable.groups.empty())
    parallel = ParallelEnvironment::unless_running();
  if (body_alone(scene_, model_))
  {
    MeshReport report;
    const TetMesh mesh = BodyCycle::zones_of(scene_, model_, report);
    check_boundary_selections(scene_, model_, mesh);
    ZoneMaterials materials = zone_materials(scene_, model_, mesh);
    const DeformableSolver solver(mesh, std::move(materials.materials),
                                  std::move(materials.of_zone), scene_.solver,
                                  scene_.gridpoint_conditions, scene_.face_pressures,
                                  scene_.has_initial_stress ? &scene_.initial_stress : nullptr);
    std::printf("Zones:        %u, %u gridpoints\n", report.zones, report.gridpoints);
    std::printf("Time step:    %.6g s\n", solver.dt());
    return;
  }
  resolve_group_names(scene_, model_);
  const BlockSystem system = build_block_system(scene_, model_);
  check_boundary_selections(scene_, model_, system.mesh);
  if (system.zones)
    std::printf("Zones:        %u in %u deformable blocks, %u gridpoints\n",
                system.mesh_report.zones, system.mesh_report.blocks, system.mesh_report.gridpoints);
  std::printf("Time step:    %.6g s\n", system.solver->dt());
}

int Simulation::run()
{
  // From the constructor: the blocks are built there.
  const auto start = start_;
  if (check_only_)
  {
    // The cycles print what they build (zones, time step); nothing is written.
    check_calculation();
    std::printf("Check:        no problem found; nothing was written\n");
    return 0;
  }
  // On ranks, rank 0 writes the files of the whole run; each rank its pieces.
  const bool writes = world_rank() == 0;
  if (writes)
    write_file_atomically(prefix_ + "_used_parameters.prm",
                          [&](std::ostream& out) { out << scene_.used_parameters; });
  print_model();
  if (scene_.strength_reduction.enabled)
  {
    const int code = run_factor_of_safety(scene_, model_, prefix_,
                                          world_ranks() > 1 ? MPI_COMM_WORLD : MPI_COMM_NULL);
    std::printf("   Time = %.3f s (blocks and the search)\n", seconds_since(start));
    return code;
  }
  // Copied again once the cycle has resolved the group names of their loads.
  std::vector<StageSpec> stages = stages_to_run(scene_);
  const unsigned long total_steps = steps_to_run(scene_);
  if (total_steps == 0)
  {
    // The model only.
    if (scene_.output.write_vtu && writes)
    {
      PvdSeries series(prefix_ + "_blocks.pvd");
      const std::string vtu = scene_.output.base_name + "_blocks_00000.vtu";
      write_blocks_vtu(scene_.output.directory + "/" + vtu, model_, {}, scene_.output.vtu_encoding);
      series.add(0.0, vtu);
      std::printf("Output:       %s_blocks.pvd\n", prefix_.c_str());
    }
    std::printf("   Time = %.3f s (blocks and output)\n", seconds_since(start));
    return 0;
  }
  const double built_seconds = seconds_since(start);

  std::unique_ptr<Cycle> cycle;
  agree_on_input_errors(
      [&]()
      {
        if (body_alone(scene_, model_))
          cycle = std::make_unique<BodyCycle>(scene_, model_, prefix_);
        else
        {
          const ModelDigest* by_region = share_ ? &digest_ : nullptr;
          cycle = std::make_unique<BlockCycle>(scene_, model_, prefix_, restart_from_,
                                               std::move(share_), by_region);
        }
      });
  stages = stages_to_run(scene_);
  const bool staged = !scene_.stages.empty();
  std::vector<std::string> columns = cycle->history_columns();
  // Input motions: the factor f(t) (or its integral) of each boundary and
  // load of the file's top level that varies in time.
  std::vector<const TimeFunction*> inputs;
  for (std::size_t l = 0; l < scene_.solver.loads.size(); ++l)
    if (scene_.solver.loads[l].motion.varies())
    {
      columns.push_back(scene_.load_sections[l] + " input");
      inputs.push_back(&scene_.solver.loads[l].motion);
    }
  for (std::size_t c = 0; c < scene_.gridpoint_conditions.size(); ++c)
    if (scene_.gridpoint_conditions[c].motion.varies())
    {
      columns.push_back(scene_.gridpoint_condition_sections[c] + " input");
      inputs.push_back(&scene_.gridpoint_conditions[c].motion);
    }
  for (std::size_t p = 0; p < scene_.face_pressures.size(); ++p)
    if (scene_.face_pressures[p].motion.varies())
    {
      columns.push_back(scene_.face_pressure_sections[p] + " input");
      inputs.push_back(&scene_.face_pressures[p].motion);
    }
  if (staged)
    columns.push_back("stage");
  // Checkpoints (on ranks, one file per rank: io/rank_checkpoint.h);
  // rank 0: the history and the progress line.
  std::unique_ptr<Checkpoint> checkpoints = std::make_unique<Checkpoint>(
      scene_, digest_.geometry_fingerprint(), cycle->rigid(), cycle->zones(), restart_from_);
  std::unique_ptr<HistoryFile> history;
  if (writes)
    history = std::make_unique<HistoryFile>(prefix_ + "_history.csv", columns, 100,
                                            restart_from_.empty());
  std::ostream quiet(nullptr); // the other ranks' progress: nowhere
  ProgressLine progress(total_steps, writes ? std::cerr : quiet, writes ? -1.0 : 1e300);
  // The loop's place: the stage (0-based), the step it began at, the steps
  // of the last history row and output frame.
  unsigned int stage_index = 0, stage_begun = 0, stages_done = 0;
  unsigned long stage_start = 0, last_row = 0, last_output = 0;
  double stage_start_time = 0.0; // s
  if (checkpoints)
  {
    Checkpoint& checkpoint = *checkpoints;
    if (history)
      checkpoint.add(*history);
    cycle->register_checkpoint(checkpoint);
    checkpoint.add(stage_index);
    checkpoint.add(stage_begun);
    checkpoint.add(stage_start);
    checkpoint.add(last_row);
    checkpoint.add(last_output);
    checkpoint.add(stage_start_time);
    checkpoint.add(stages_done);
    checkpoint.set_stages_begun(&stage_begun);
  }
  if (!restart_from_.empty())
  {
    // On ranks: a rank's file that does not fit its share stops every rank.
    unsigned long step = 0;
    agree_on_input_errors([&]() { step = checkpoints->restore(restart_from_); });
    // What the stages begun changed that a checkpoint does not hold (the
    // boundaries, the rock materials), set again in their order.
    for (unsigned int k = 0; k < stage_begun; ++k)
      cycle->restore_stage(stages[k]);
    std::printf("Restarted:    from %s at step %lu\n",
                std::filesystem::path(restart_from_).filename().c_str(), step);
  }
  const auto record = [&]()
  {
    std::vector<double> row = cycle->history_row();
    for (const TimeFunction* input : inputs)
      row.push_back(input->scale(cycle->time()));
    if (staged)
      row.push_back(stage_index + 1);
    if (history)
      history->record(row);
    last_row = cycle->steps_done();
  };
  const auto output = [&]()
  {
    cycle->write_frame(false);
    last_output = cycle->steps_done();
  };
  int exit_code = 0;
  bool end_time_reached = false;
  for (; stage_index < stages.size() && !end_time_reached; ++stage_index)
  {
    if (stages_done > stage_index)
      continue; // done before the checkpoint this run restarted from
    const StageSpec& stage = stages[stage_index];
    if (stage_begun <= stage_index)
    {
      // A new stage (a restart inside one has begun it already).
      if (staged)
        std::printf("Stage %u:      %s (%s)\n", stage_index + 1, stage.name.c_str(),
                    stage.section.c_str());
      cycle->begin_stage(stage);
      stage_begun = stage_index + 1;
      stage_start = cycle->steps_done();
      stage_start_time = cycle->time();
      if (stage_index == 0 && restart_from_.empty())
      {
        output();
        record();
      }
    }
    try
    {
      if (stage.factor_of_safety && stage_begun == stage_index + 1 &&
          cycle->steps_done() == stage_start)
        cycle->factor_of_safety(stages, stage_index); // on copies: the model stays
      while (!stage.factor_of_safety && cycle->steps_done() - stage_start < stage.steps)
      {
        cycle->step();
        const unsigned long n = cycle->steps_done();
        if (n % scene_.solver.history_interval == 0)
          record();
        progress.update(n, cycle->time(), cycle->ratio());
        if (scene_.solver.output_interval > 0 && n - last_output >= scene_.solver.output_interval)
          output();
        if (!stage.dynamic && stage.target_ratio > 0.0 && cycle->may_stop(n - stage_start) &&
            cycle->ratio() < stage.target_ratio)
          break;
        // Half a step of slack: the step that reaches the limit ends it.
        if (stage.time_limit > 0.0 &&
            cycle->time() - stage_start_time > stage.time_limit - 0.5 * cycle->dt())
          break;
        // 'Solver / End time': the whole run's model time, likewise.
        if (scene_.solver.end_time > 0.0 &&
            cycle->time() > scene_.solver.end_time - 0.5 * cycle->dt())
        {
          end_time_reached = true;
          break;
        }
        if (checkpoints)
          checkpoints->after_step(n);
      }
    }
    catch (const DivergenceError&)
    {
      // The last good state: nothing moved after the fault was found. On
      // ranks only the rank that found it knows: it stops them all.
      if (world_ranks() == 1)
        cycle->write_frame(true);
      progress.finish();
      throw;
    }
    if (last_row != cycle->steps_done())
      record();
    if (last_output != cycle->steps_done())
      output();
    progress.finish();
    if (end_time_reached)
      std::printf("End time:     %g s reached\n", scene_.solver.end_time);
    const RunEnd end{cycle->ratio(), cycle->unbalanced_where()};
    if (staged)
      std::printf("  Steps:      %lu (to step %lu, time %.6g s), unbalanced force ratio %.3g; "
                  "largest displacement %s\n",
                  cycle->steps_done() - stage_start, cycle->steps_done(), cycle->time(), end.ratio,
                  cycle->displacement_text().c_str());
    else
      cycle->print_end();
    if (!stage.factor_of_safety && static_stage_end(stage, end, staged) != 0)
      exit_code = exit_not_in_equilibrium;
    if (staged)
    {
      // A checkpoint at each stage's end: a restart from it begins the next
      // stage, or one appended to the file after the run has finished.
      stages_done = stage_index + 1;
      if (checkpoints)
        checkpoints->write(cycle->steps_done());
    }
  }
  if (staged)
    cycle->print_end();
  // Indented "Time =" lines are ignored when test output is compared.
  // (On ranks, the largest rank's peak memory: collective.)
  double peak = peak_memory();
  if (world_ranks() > 1)
    MPI_Allreduce(MPI_IN_PLACE, &peak, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  std::printf(
      "   Time = %.3f s (scene and blocks %.3f s, then the calculation and output %.3f s); peak "
      "memory %s%s%s\n",
      seconds_since(start), built_seconds, seconds_since(start) - built_seconds,
      memory_text(peak).c_str(), world_ranks() > 1 ? " (the largest rank's)" : "",
      by_region_ ? "; each rank built the blocks of its region only" : "");
  return exit_code;
}

} // namespace talus
