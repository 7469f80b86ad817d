#include <talus/base/archive.h>
#include <talus/base/exceptions.h>
#include <talus/base/parallel_environment.h>
#include <talus/io/block_vtu_writer.h>
#include <talus/io/contact_vtu_writer.h>
#include <talus/io/factor_of_safety_run.h>
#include <talus/io/history_file.h>
#include <talus/io/scene_checks.h>
#include <talus/io/zone_vtu_writer.h>
#include <talus/scene/build_blocks.h>
#include <talus/scene/factor_of_safety.h>
#include <talus/zone/tet10_mesh.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>

namespace talus
{

void write_mechanism(const Scene& scene, const TrialView& view, const std::string& prefix)
{
  const BlockSystem& system = view.system;
  const BlockModel& model = view.model;
  const RigidSolver& solver = *system.solver;
  // The frames are named after `prefix`, in its folder: a stage's
  // mechanism must not take the name of the run's first frame.
  const std::size_t slash = prefix.rfind('/');
  const std::string folder = slash == std::string::npos ? "." : prefix.substr(0, slash);
  const std::string base = slash == std::string::npos ? prefix : prefix.substr(slash + 1);
  std::vector<BlockField> fields{{"displacement", 3, {}}, {"velocity", 3, {}}, {"rotation", 3, {}}};
  for (unsigned int b = 0; b < model.n_blocks(); ++b)
    for (int d = 0; d < 3; ++d)
    {
      fields[0].values.push_back(solver.displacement[b][d] - view.start_displacement[b][d]);
      fields[1].values.push_back(solver.velocity[b][d]);
      fields[2].values.push_back(solver.rotation[b][d]);
    }
  write_blocks_vtu(folder + "/" + base + "_blocks_00000.vtu", model, fields,
                   scene.output.vtu_encoding);
  PvdSeries(prefix + "_blocks.pvd").add(solver.time(), base + "_blocks_00000.vtu");
  JointNumbers joints;
  for (const std::string& section : scene.joint_set_sections)
    joints.joint_set_number.push_back(std::stoi(section.substr(section.rfind(' ') + 1)));
  for (const std::string& section : scene.joint_plane_sections)
    joints.joint_number.push_back(std::stoi(section.substr(section.rfind(' ') + 1)));
  // (contacts numbered in block-pair order: the trial's slots depend on
  // the layout of the state it started from, a gathered one on ranks)
  write_contacts_vtu(folder + "/" + base + "_contacts_00000.vtu", solver.contacts(), model, joints,
                     scene.output.vtu_encoding, nullptr, 0.0, nullptr, true);
  PvdSeries(prefix + "_contacts.pvd").add(solver.time(), base + "_contacts_00000.vtu");
  if (!system.zones)
    return;
  const DeformableSolver& zones = *system.zones;
  const std::vector<double> x = zones.positions();
  std::vector<double> stress;
  std::vector<unsigned char> state;
  if (system.mesh.quadratic()) // a 10-node zone shows as its eight sub-tetrahedra
    state = tet10_subcell_flags(zones.plastic_state());
  else
    shown_zone_values(system.mesh, x, zones.stress(), zones.plastic_state(), stress, state);
  std::vector<ZoneField> cells{{"plastic_state", 1, {}}};
  cells[0].values.assign(state.begin(), state.end());
  std::vector<double> u = zones.displacements();
  if (view.start_gridpoint_displacement.size() == u.size())
    for (std::size_t i = 0; i < u.size(); ++i)
      u[i] -= view.start_gridpoint_displacement[i];
  ZoneWriter(system.mesh, scene.output.vtu_encoding)
      .write(folder + "/" + base + "_zones_00000.vtu", x,
             {{"displacement", 3, u}, {"velocity", 3, zones.velocities()}}, cells, zones.time());
  PvdSeries(prefix + "_zones.pvd").add(zones.time(), base + "_zones_00000.vtu");
}

int run_factor_of_safety(Scene& scene, BlockModel& model, const std::string& prefix, MPI_Comm comm)
{
  int rank = 0, ranks = 1;
  if (comm != MPI_COMM_NULL)
  {
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &ranks);
  }
  resolve_group_names(scene, model);
  // PETSc and MPI for the zones (talus is serial: this process alone).
  std::unique_ptr<ParallelEnvironment> parallel;
  if (!scene.deformable.groups.empty())
    parallel = ParallelEnvironment::unless_running();
  else
    check_boundary_selections(scene, model, TetMesh());
  const StrengthReductionSettings& f = scene.strength_reduction;
  const SolverSettings& s = scene.solver;
  std::printf("Strength reduction: tan(phi), cohesion and tensile strength of every joint "
              "material%s divided by F; each trial from the initial state, up to %lu steps; "
              "stable when the unbalanced-force ratio falls below %g and the largest "
              "displacement grew by less than %g %% over the last quarter of the steps; "
              "bracket to %g of F\n",
              f.reduce_zone_strength ? " and of the Mohr-Coulomb zones" : "", s.steps,
              s.target_ratio, 100.0 * creep_fraction, f.tolerance);

  std::vector<std::string> columns{"step", "time (s)", "unbalanced ratio",
                                   "largest displacement (m)"};
  for (const std::string& c : EnergyAccount::column_names())
    columns.push_back(c);
  for (unsigned int b : s.history_blocks)
    for (const char* q : {"ux", "uy", "uz", "vx", "vy", "vz"})
      columns.push_back("block " + std::to_string(b) + " " + q + (q[0] == 'u' ? " (m)" : " (m/s)"));
  std::vector<std::vector<double>> rows;          // of the trial running
  bool checked = scene.deformable.groups.empty(); // else at the first trial's start
  TrialHooks hooks;
  hooks.record = [&](const TrialView& view)
  {
    const RigidSolver& solver = *view.system.solver;
    if (!checked) // the boundaries' selections, once the zones exist
    {
      check_boundary_selections(scene, model, view.system.mesh);
      checked = true;
    }
    if (solver.steps_done() == view.start_step)
      rows.clear();
    // Steps, time and displacements since the initial state; the energy
    // account runs on from the start of the initial equilibrium.
    const EnergyAccount e = solver.energy_account();
    std::vector<double> row{double(solver.steps_done() - view.start_step),
                            solver.time() - view.start_time, solver.unbalanced_ratio(),
                            view.largest_displacement()};
    e.append_to(row);
    for (unsigned int b : s.history_blocks)
    {
      const Vec3 u = solver.displacement[b] - view.start_displacement[b];
      for (const Vec3* q : {&u, &solver.velocity[b]})
        for (int d = 0; d < 3; ++d)
          row.push_back((*q)[d]);
    }
    rows.push_back(std::move(row));
  };
  double mechanism_factor = 0.0;
  std::string water_line; // of the last stable trial: the water the model stands in
  const auto write_history = [&](const std::vector<std::vector<double>>& trial_rows)
  {
    HistoryFile history(prefix + "_history.csv", columns);
    for (const std::vector<double>& row : trial_rows)
    {
      bool finite = true;
      for (double v : row)
        finite &= std::isfinite(v);
      if (finite) // a diverged trial's last rows may not be
        history.record(row);
    }
  };
  hooks.finished = [&](const TrialView& view, const StrengthReductionTrial& t)
  {
    if (t.stable && scene.solver.water.active())
      water_line = view.system.solver->water_summary();
    // Each unstable trial replaces the mechanism written before: the last
    // one, nearest the limit, stays.
    if (t.stable)
      return;
    mechanism_factor = t.factor;
    write_history(rows);
    if (scene.output.write_vtu)
      write_mechanism(scene, view, prefix);
  };
  const auto print_trial = [](const StrengthReductionTrial& t)
  { std::printf("%s\n", trial_line(t).c_str()); };
  StrengthReductionResult r;
  if (ranks == 1)
    r = factor_of_safety(scene, model, hooks, print_trial);
  else
  {
    // Rank 0 always runs the round's first trial, which the search takes:
    // it writes as on one rank. Another rank's trial, if the search takes
    // it, comes as its water line (stable) or its history and end state
    // (unstable), from which rank 0 writes what the serial run would.
    std::string payload;
    TrialHooks other;
    other.record = hooks.record;
    other.finished = [&](const TrialView& view, const StrengthReductionTrial& t)
    {
      CheckpointWriter out;
      if (t.stable)
        out.put(scene.solver.water.active() ? view.system.solver->water_summary() : std::string());
      else
      {
        out.put(static_cast<std::uint64_t>(rows.size()));
        for (const std::vector<double>& row : rows)
          out.put(row);
        CheckpointWriter state; // for the mechanism's VTU files
        if (scene.output.write_vtu)
        {
          view.system.solver->save_state(state);
          if (view.system.zones)
            view.system.zones->save_state(state);
        }
        out.put(state.bytes());
      }
      payload = out.bytes();
    };
    std::vector<unsigned int> rounds;
    int stable_by = -1, unstable_by = -1; // the ranks that ran the last of each
    r = factor_of_safety(
        scene, model,
        [&](const StrengthReductionTrials& trials)
        {
          return find_factor_of_safety_on_ranks(
              [&](double factor)
              {
                payload.clear();
                const StrengthReductionTrial t = trials.run(factor, rank == 0 ? hooks : other);
                return RankTrial{t, payload};
              },
              scene.strength_reduction, comm,
              [&](const StrengthReductionTrial& t, int by, const std::string& bytes)
              {
                print_trial(t);
                (t.stable ? stable_by : unstable_by) = by;
                if (rank != 0 || by == 0)
                  return;
                CheckpointReader in(bytes,
                                    "a strength reduction trial from rank " + std::to_string(by));
                if (t.stable)
                {
                  std::string water;
                  in.get(water);
                  if (!water.empty())
                    water_line = water;
                  return;
                }
                mechanism_factor = t.factor;
                std::uint64_t n = 0;
                in.get(n);
                std::vector<std::vector<double>> trial_rows(n);
                for (std::vector<double>& row : trial_rows)
                  in.get(row);
                write_history(trial_rows);
                std::string state;
                in.get(state);
                if (scene.output.write_vtu)
                  trials.show(t.factor, state,
                              [&](const TrialView& view) { write_mechanism(scene, view, prefix); });
              },
              &rounds);
        });
    if (rank == 0) // the search's figures, beside the summary
    {
      std::string per_round;
      for (unsigned int n : rounds)
        per_round += (per_round.empty() ? "" : " ") + std::to_string(n);
      std::fprintf(stderr,
                   "talus: factor of safety on %d ranks: %zu trials in %zu rounds (trials the "
                   "search took per round: %s); the last stable trial ran on rank %d, the last "
                   "unstable one (the mechanism) on rank %d\n",
                   ranks, r.trials.size(), rounds.size(), per_round.c_str(), stable_by,
                   unstable_by);
    }
  }
  if (!r.found)
  {
    const auto line = scene.lines.find("Solver / Mode");
    throw InputError::at(scene.parameter_file, line == scene.lines.end() ? 0 : line->second,
                         "Solver", "Mode", "factor of safety: " + r.failure,
                         r.trials.empty()
                             ? "a model that comes to rest under its loads (every block "
                               "supported, 'Steps' enough to reach 'Target ratio')"
                             : "a model that is stable at some F and fails at a larger one, "
                               "between F = " +
                                   number(f.smallest_factor) + " and " + number(f.largest_factor));
  }
  std::printf("Factor of safety: %.4g (between %.6g and %.6g, %zu trials)\n", r.factor(),
              r.stable_factor, r.unstable_factor, r.trials.size());
  if (!water_line.empty())
    std::printf("%s (the last stable trial)\n", water_line.c_str());
  std::printf(
      "Mechanism:    the last unstable trial (F = %.6g): %s%s_history.csv\n", mechanism_factor,
      scene.output.write_vtu ? (prefix + "_blocks.pvd, " + prefix + "_contacts.pvd, " +
                                (scene.deformable.groups.empty() ? "" : prefix + "_zones.pvd, "))
                                   .c_str()
                             : "",
      prefix.c_str());
  return 0;
}

} // namespace talus
