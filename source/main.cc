// talus: three-dimensional distinct element code for jointed rock.
// Usage: talus scene.prm, or talus --restart checkpoint [scene.prm]

#include <talus/base/exceptions.h>
#include <talus/base/memory.h>
#include <talus/base/parallel_environment.h>
#include <talus/io/block_vtu_writer.h>
#include <talus/io/checkpoint.h>
#include <talus/io/contact_vtu_writer.h>
#include <talus/io/file_output.h>
#include <talus/io/history_file.h>
#include <talus/io/scene.h>
#include <talus/io/scene_checks.h>
#include <talus/io/zone_vtu_writer.h>
#include <talus/model/build_blocks.h>
#include <talus/solver/block_system.h>
#include <talus/solver/implicit_check.h>
#include <talus/solver/rigid_solver.h>
#include <talus/zone/block_mesher.h>
#include <talus/zone/tet10_mesh.h>

#include <talus_revision.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <new>

namespace
{

constexpr const char* usage =
    "usage: talus SCENE.prm\n"
    "       talus --check SCENE.prm\n"
    "       talus --restart CHECKPOINT [SCENE.prm]\n"
    "       talus --version\n"
    "  Builds the block model the parameter file describes, writes it\n"
    "  for ParaView into the output folder it names, and prints a summary.\n"
    "  Shipped scenes are in the parameters/ folder.\n"
    "  --check reads, builds and checks the scene (blocks, zones, solvers)\n"
    "  and writes nothing: exit code 0 when it would run, 1 when not.\n"
    "  --restart continues a run from its checkpoint (<Base name>_checkpoint.bin,\n"
    "  written every 'Checkpoint interval' steps and on SIGINT/SIGTERM) with the\n"
    "  parameter file it was written for (or SCENE.prm, the same file moved).\n";

/// The checkpoint to continue from (talus --restart), or empty.
std::string restart_from;

/// Restores a run from `restart_from` (when restarting) and says so.
void restore_run(talus::Checkpoint& checkpoint)
{
  if (restart_from.empty())
    return;
  const unsigned long step = checkpoint.restore(restart_from);
  std::printf("Restarted:    from %s at step %lu\n",
              std::filesystem::path(restart_from).filename().c_str(), step);
}

/// Writes the zones of deformable blocks at their current state as frame
/// `frame` of the zone series.
/// After a divergence (`with_stress` false) non-finite stresses are written
/// as 0.
void write_zone_frame(const talus::Scene& scene, const talus::TetMesh& mesh,
                      const talus::DeformableSolver& solver, talus::ZoneWriter& writer,
                      talus::PvdSeries& series, unsigned int frame, bool with_stress = true)
{
  using namespace talus;
  char file[64];
  std::snprintf(file, sizeof file, "_zones_%05u.vtu", frame);
  const std::string vtu = scene.output.base_name + file;
  // One cell per shown tetrahedron: a hexahedral zone shows its averaged
  // stress on its first overlay; a 10-node zone is eight sub-tetrahedra
  // with the Gauss-point stresses and states carried over (tet10_mesh.h).
  const std::vector<double> x = solver.positions();
  std::vector<double> stress;
  std::vector<unsigned char> state;
  if (mesh.quadratic())
  {
    stress = tet10_subcell_values(solver.stress(), 6);
    state = tet10_subcell_flags(solver.plastic_state());
  }
  else
    shown_zone_values(mesh, x, solver.stress(), solver.plastic_state(), stress, state);
  // After a divergence the stresses may hold the non-finite values found:
  // those are written as 0, so that the frame keeps the fields of the others.
  if (!with_stress)
    for (double& s : stress)
      s = std::isfinite(s) ? s : 0.0;
  std::vector<ZoneField> cells{
      {"stress", 6, stress}, {"principal_stress", 3, {}}, {"plastic_state", 1, {}}};
  cells[1].values.resize(3 * state.size());
  for (std::size_t c = 0; c < state.size(); ++c)
  {
    principal_stresses(&stress[6 * c], &cells[1].values[3 * c]);
    cells[2].values.push_back(state[c]);
  }
  writer.write(scene.output.directory + "/" + vtu, x,
               {{"displacement", 3, solver.displacements()}, {"velocity", 3, solver.velocities()}},
               cells, solver.time());
  series.add(solver.time(), vtu);
}

/// History columns of deformable blocks at chosen points: the nearest
/// gridpoint's displacement and velocity, the nearest zone's stress.
struct PointHistory
{
  std::vector<unsigned int> gridpoint, zone;

  PointHistory(const talus::TetMesh& mesh, const std::vector<talus::Vec3>& points)
  {
    using talus::Vec3;
    for (const Vec3& p : points)
    {
      unsigned int best_g = 0, best_z = 0;
      double dg = 1e300, dz = 1e300;
      for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
      {
        const double d =
            (Vec3(mesh.position[3 * g], mesh.position[3 * g + 1], mesh.position[3 * g + 2]) - p)
                .squaredNorm();
        if (d < dg)
        {
          dg = d;
          best_g = g;
        }
      }
      for (unsigned int z = 0; z < mesh.n_zones(); ++z)
      {
        Vec3 c = Vec3::Zero();
        for (unsigned int g : mesh.zone_gridpoint[z])
          c +=
              0.25 * Vec3(mesh.position[3 * g], mesh.position[3 * g + 1], mesh.position[3 * g + 2]);
        if ((c - p).squaredNorm() < dz)
        {
          dz = (c - p).squaredNorm();
          best_z = z;
        }
      }
      gridpoint.push_back(best_g);
      zone.push_back(best_z);
    }
  }

  void add_columns(std::vector<std::string>& columns) const
  {
    for (std::size_t k = 0; k < gridpoint.size(); ++k)
    {
      const std::string at = "point " + std::to_string(k) + " ";
      for (const char* q : {"ux (m)", "uy (m)", "uz (m)", "vx (m/s)", "vy (m/s)", "vz (m/s)",
                            "sxx (Pa)", "syy (Pa)", "szz (Pa)", "sxy (Pa)", "syz (Pa)", "szx (Pa)"})
        columns.push_back(at + q);
    }
  }

  void add_values(std::vector<double>& row, const talus::DeformableSolver& zones) const
  {
    if (gridpoint.empty())
      return;
    const std::vector<double> u = zones.displacements(), v = zones.velocities();
    for (std::size_t k = 0; k < gridpoint.size(); ++k)
    {
      for (const std::vector<double>* q : {&u, &v})
        for (int d = 0; d < 3; ++d)
          row.push_back((*q)[3 * gridpoint[k] + d]);
      // The zone's mean over its stress points (Gauss points of 10-node zones).
      const unsigned int p = zones.stress_points_per_zone();
      for (int c = 0; c < 6; ++c)
      {
        double sum = 0.0;
        for (unsigned int q = 0; q < p; ++q)
          sum += zones.stress()[6 * (p * zone[k] + q) + c];
        row.push_back(sum / p);
      }
    }
  }
};

/// Solves the static elastic problem of a deformable run implicitly, the
/// explicit kernels' own discrete problem, and prints how far the explicit
/// answer is from it: at the history points (or the gridpoint of largest
/// displacement) and the largest difference anywhere.
void implicit_check(const talus::Scene& scene, talus::DeformableSolver& solver)
{
  using namespace talus;
  const auto refuse = [](const std::string& why)
  { std::printf("Implicit check: not made (%s)\n", why.c_str()); };
  if (scene.solver.dynamic)
    return refuse("the run is dynamic");
  if (scene.deformable.material.model != ZoneModel::elastic)
    return refuse("the zones are not elastic");
  if (scene.has_initial_stress)
    return refuse("the zones have an initial stress");
  for (const GridpointCondition& c : scene.gridpoint_conditions)
    if (c.velocity.norm() > 0.0 || c.velocity_gradient.norm() > 0.0)
      return refuse("a boundary moves at a velocity");
  ImplicitCheck check;
  try
  {
    check = check_implicitly(solver, scene.solver.history_points);
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

/// How a run ended: its unbalanced-force ratio, and where the force that
/// sets it acts (for the warning of a run that did not settle).
struct RunEnd
{
  double ratio = 0.0;
  std::string where;
};

/// The largest displacement of a gridpoint (m).
double largest_gridpoint_displacement(const talus::DeformableSolver& solver)
{
  const std::vector<double> u = solver.displacements();
  double largest = 0.0;
  for (std::size_t g = 0; g < u.size() / 3; ++g)
    largest = std::max(largest, std::sqrt(u[3 * g] * u[3 * g] + u[3 * g + 1] * u[3 * g + 1] +
                                          u[3 * g + 2] * u[3 * g + 2]));
  return largest;
}

/// How the zones' edge length was asked for, for the summary.
std::string edge_length_text(const talus::EdgeLengthField& f)
{
  using talus::number;
  if (!f.graded())
    return "edge length " + number(f.coarse) + " m";
  return "edge length " + number(f.fine) + " m at the fine region, growing to " + number(f.coarse) +
         " m at " + number(f.distance) + " m from it";
}

/// The summary's lines on the zones' shapes: the radius ratio (1 for a
/// regular tetrahedron), where the poor zones are, and the gridpoint that
/// sets the stable step of eq. 84 with its worst zone.
void print_mesh_quality(const talus::MeshReport& r, const talus::TetMesh& mesh,
                        const talus::DeformableSolver& zones, const talus::BlockModel& model)
{
  using namespace talus;
  if (r.zones == 0)
    return;
  std::printf("Quality:      radius ratio min %.2g (a zone of block %u), 1 %% %.2g, median %.2g; "
              "%u zones below 0.1",
              r.quality_min, r.worst_block, r.quality_1, r.quality_median, r.poor_zones);
  if (!r.poor_blocks.empty())
  {
    std::printf(" in block");
    for (std::size_t i = 0; i < r.poor_blocks.size(); ++i)
      std::printf("%s %u (%u)", i == 0 ? "" : ",", r.poor_blocks[i].first, r.poor_blocks[i].second);
  }
  std::printf("\n");
  const unsigned int g = zones.time_step_gridpoint();
  double worst = 2.0, height = 1e300;
  const auto P = [&](unsigned int i)
  { return Vec3(mesh.position[3 * i], mesh.position[3 * i + 1], mesh.position[3 * i + 2]); };
  for (const auto& t : mesh.zone_gridpoint)
    if (std::find(t.begin(), t.end(), g) != t.end())
    {
      worst = std::min(worst, radius_ratio(P(t[0]), P(t[1]), P(t[2]), P(t[3])));
      const double v =
          std::abs((P(t[1]) - P(t[0])).dot((P(t[2]) - P(t[0])).cross(P(t[3]) - P(t[0]))));
      for (int k = 0; k < 4; ++k)
      {
        const Vec3 a = P(t[(k + 1) % 4]), b = P(t[(k + 2) % 4]), c = P(t[(k + 3) % 4]);
        height = std::min(height, v / (b - a).cross(c - a).norm());
      }
    }
  // The block's own shape: an edge or a thickness much below the zone size
  // forces thin zones, whatever the mesher does.
  const unsigned int b = mesh.gridpoint_block[g];
  double shortest = 1e300, thickness = 1e300;
  for (unsigned int f = model.face_start[b]; f < model.face_start[b + 1]; ++f)
  {
    const unsigned int first = model.face_loop_start[f], n = model.face_loop_start[f + 1] - first;
    for (unsigned int k = 0; k < n; ++k)
      shortest = std::min(shortest, (model.vertex[model.face_vertex[first + k]] -
                                     model.vertex[model.face_vertex[first + (k + 1) % n]])
                                        .norm());
    double across = 0.0;
    for (unsigned int v = model.vertex_start[b]; v < model.vertex_start[b + 1]; ++v)
      across = std::max(across, -model.face_normal[f].dot(model.vertex[v] -
                                                         model.vertex[model.face_vertex[first]]));
    thickness = std::min(thickness, across);
  }
  std::printf("Step set by:  the gridpoint at (%.4g, %.4g, %.4g) m of block %u (eq. 84): its "
              "zones' worst radius ratio %.2g, smallest height %.3g m; the block's shortest edge "
              "%.3g m, thickness %.3g m\n",
              P(g).x(), P(g).y(), P(g).z(), b, worst, height, shortest, thickness);
}

/// The summary's line on the zones about to be meshed: how many and how much
/// memory, estimated before meshing (after the checks, which refuse a scene
/// that does not fit).
void print_zone_estimate(const talus::Scene& scene, const talus::BlockModel& model)
{
  const talus::ZoneEstimate e = talus::estimate_zones(scene, model);
  if (e.blocks == 0 || e.zones == 0.0)
    return;
  std::printf("Meshing:      about %.3g %s in %zu deformable block%s, about %s of memory\n",
              e.zones, e.quadratic ? "10-node zones" : "zones", e.blocks, e.blocks == 1 ? "" : "s",
              talus::memory_text(e.bytes).c_str());
  std::fflush(stdout);
}

/// The summary's line on nodal mixed discretization, when some zones have
/// it.
void print_nodal_mixed(const talus::DeformableSolver& solver)
{
  if (const unsigned int mixed = solver.nodal_mixed_zones(); mixed > 0)
    std::printf("Nodal mixed:  %u of %u zones (eqs. 68-76)\n", mixed, solver.mesh().n_zones());
}

/// The zones of a scene of one deformable block: meshed, or read from its
/// mesh file (and then ordered and made quadratic as the scene asks).
talus::TetMesh single_block_zones(const talus::Scene& scene, const talus::BlockModel& model,
                                  talus::MeshReport& report)
{
  using namespace talus;
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

/// PETSc and MPI for the zones of a scene with deformable blocks (none
/// without): talus is serial, so they are started for this process alone.
std::unique_ptr<talus::ParallelEnvironment> zone_environment(const talus::Scene& scene)
{
  if (scene.deformable.groups.empty())
    return nullptr;
  int argc = 1;
  char name[] = "talus";
  char* args[] = {name, nullptr};
  char** argv = args;
  return std::make_unique<talus::ParallelEnvironment>(argc, argv);
}

/// Runs a scene of deformable blocks: meshes them, then the explicit zone
/// cycle with output and histories; returns the unbalanced-force ratio
/// reached.
RunEnd solve_deformable(talus::Scene& scene, talus::BlockModel& model, const std::string& prefix)
{
  using namespace talus;
  MeshReport mesh_report;
  print_zone_estimate(scene, model);
  TetMesh mesh = single_block_zones(scene, model, mesh_report);
  const bool from_file = !scene.deformable.mesh_file.empty();
  check_boundary_selections(scene, model, mesh);
  std::printf(
      "Zones:        %u %s, %u gridpoints, %u boundary faces (%s; largest edge %.4g m, "
      "smallest height %.4g m), zone volume %.9g m^3\n",
      mesh_report.zones, mesh.quadratic() ? "10-node tetrahedra" : "tetrahedra",
      mesh_report.gridpoints, mesh_report.boundary_faces,
      from_file ? ("from " + std::filesystem::path(scene.deformable.mesh_file).filename().string())
                      .c_str()
                : edge_length_text(scene.deformable.edge_length).c_str(),
      mesh_report.largest_edge, mesh_report.smallest_height, mesh_report.zone_volume);
  if (mesh_report.hexes > 0)
    std::printf("Hexahedra:    %u (mixed discretization: the tetrahedra are their two overlays of "
                "five)\n",
                mesh_report.hexes);
  const std::unique_ptr<ParallelEnvironment> parallel = zone_environment(scene);
  ZoneMaterials materials = zone_materials(scene, model, mesh);
  DeformableSolver solver(mesh, std::move(materials.materials), std::move(materials.of_zone),
                          scene.solver, scene.gridpoint_conditions, scene.face_pressures,
                          scene.has_initial_stress ? &scene.initial_stress : nullptr);
  print_mesh_quality(mesh_report, mesh, solver, model);
  print_nodal_mixed(solver);
  std::printf("Time step:    %.6g s (eq. 84%s)\n", solver.dt(),
              !scene.solver.dynamic && scene.solver.density_scaling ? ", density scaling: unit step"
                                                                    : "");

  PvdSeries series(prefix + "_zones.pvd");
  ZoneWriter zone_writer(mesh, scene.output.vtu_encoding);
  const PointHistory points(mesh, scene.solver.history_points);
  std::vector<std::string> columns{"step", "time (s)", "unbalanced ratio",
                                   "largest displacement (m)"};
  points.add_columns(columns);
  for (const ReactionReport& r : scene.reactions)
    for (const char* q : {" reaction x (N)", " reaction y (N)", " reaction z (N)"})
      columns.push_back(r.name + q);
  // The energy account (see EnergyAccount), last so that the columns
  // before keep their places.
  for (const char* q : {"kinetic energy (J)", "work of gravity (J)", "work of boundaries (J)",
                        "zone elastic energy (J)", "plastic dissipation (J)",
                        "damping dissipation (J)", "energy balance error (J)"})
    columns.push_back(q);
  Checkpoint checkpoint(scene, model, nullptr, &solver, restart_from);
  HistoryFile history(prefix + "_history.csv", columns, 100, restart_from.empty());
  ProgressLine progress(scene.solver.steps);
  // A static run may stop at the target ratio only once every boundary
  // velocity with an end time has ended (s).
  double moving_until = 0.0;
  for (const GridpointCondition& c : scene.gridpoint_conditions)
    if (std::isfinite(c.velocity_until))
      moving_until = std::max(moving_until, c.velocity_until);
  unsigned int frame = 0;
  unsigned long last_output = 0;
  checkpoint.add(history);
  checkpoint.add(series);
  checkpoint.add(frame);
  checkpoint.add(last_output);
  restore_run(checkpoint);
  const auto output = [&]()
  {
    if (scene.output.write_vtu)
      write_zone_frame(scene, mesh, solver, zone_writer, series, frame++);
  };
  // One history row at the solver's current step; the last row is kept so
  // that the run's end is recorded once.
  unsigned long last_row = solver.steps_done();
  const auto record = [&]()
  {
    std::vector<double> row{double(solver.steps_done()), solver.time(), solver.unbalanced_ratio(),
                            largest_gridpoint_displacement(solver)};
    points.add_values(row, solver);
    for (const ReactionReport& r : scene.reactions)
    {
      const Vec3 f = -solver.support_force(r.region, r.held);
      row.insert(row.end(), {f[0], f[1], f[2]});
    }
    EnergyAccount e;
    solver.add_energy(e);
    row.insert(row.end(), {e.kinetic, e.gravity_work, e.boundary_work, e.zone_elastic, e.plastic,
                           e.damping, e.error()});
    history.record(row);
    last_row = solver.steps_done();
  };
  if (restart_from.empty())
  {
    output();
    record();
  }
  while (solver.steps_done() < scene.solver.steps)
  {
    try
    {
      solver.step();
    }
    catch (const DivergenceError&)
    {
      // The last good state: nothing moved after the fault was found.
      if (scene.output.write_vtu)
        write_zone_frame(scene, mesh, solver, zone_writer, series, frame++, false);
      throw;
    }
    const unsigned long n = solver.steps_done();
    if (n % scene.solver.history_interval == 0)
      record();
    progress.update(n, solver.time(), solver.unbalanced_ratio());
    if (scene.solver.output_interval > 0 && n - last_output >= scene.solver.output_interval)
    {
      output();
      last_output = n;
    }
    if (!scene.solver.dynamic && scene.solver.target_ratio > 0.0 && n >= 20 &&
        solver.time() >= moving_until && solver.unbalanced_ratio() < scene.solver.target_ratio)
      break;
    checkpoint.after_step(n);
  }
  progress.finish();
  if (last_row != solver.steps_done())
    record();
  if (last_output != solver.steps_done())
    output();
  std::printf("Steps:        %lu (time %.6g s)\n", solver.steps_done(), solver.time());
  if (scene.solver.water.active())
    std::printf("%s\n",
                water_summary(scene.solver.water, solver.water_faces_below(), solver.water_force())
                    .c_str());
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
  for (unsigned int z = 0; z < mesh.n_zones(); ++z)
  {
    bool any = false;
    for (unsigned int q = 0; q < per_zone; ++q)
      any |= solver.plastic_state()[per_zone * z + q] != 0;
    yielding += any;
  }
  if (scene.deformable.material.model == ZoneModel::mohr_coulomb)
    std::printf("Plastic zones: %u of %u\n", yielding, mesh.n_zones());
  for (const ReactionReport& r : scene.reactions)
  {
    const Vec3 f = -solver.support_force(r.region, r.held);
    std::printf("Reaction of %s on the body: %.9g, %.9g, %.9g N\n", r.name.c_str(), f[0], f[1],
                f[2]);
  }
  if (scene.deformable.implicit_check)
    implicit_check(scene, solver);
  std::printf("Output:       %s_zones.pvd, %s_history.csv\n", prefix.c_str(), prefix.c_str());
  const unsigned int g = solver.unbalanced_gridpoint();
  const std::vector<double> x = solver.positions();
  char where[160];
  std::snprintf(where, sizeof where, "gridpoint %u at %.4g, %.4g, %.4g m", g, x[3 * g],
                x[3 * g + 1], x[3 * g + 2]);
  return {solver.unbalanced_ratio(), where};
}

/// Runs the calculation the scene asks for, with output and histories;
/// returns the unbalanced-force ratio reached and where it acts.
RunEnd solve(talus::Scene& scene, talus::BlockModel& model, talus::PvdSeries& series,
             const std::string& prefix)
{
  using namespace talus;
  resolve_group_names(scene, model);
  // Deformable blocks among rigid ones: their zones, and their surfaces as
  // their shapes for the contacts.
  const std::unique_ptr<ParallelEnvironment> parallel = zone_environment(scene);
  print_zone_estimate(scene, model);
  const auto meshing = std::chrono::steady_clock::now();
  BlockSystem system = build_block_system(scene, model);
  const double meshing_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - meshing).count();
  check_boundary_selections(scene, model, system.mesh);
  RigidSolver& solver = *system.solver;
  const TetMesh& mesh = system.mesh;
  DeformableSolver* zones = system.zones.get();
  if (zones)
    std::printf("Zones:        %u tetrahedra in %u deformable blocks, %u gridpoints (%s)\n",
                system.mesh_report.zones, system.mesh_report.blocks, system.mesh_report.gridpoints,
                edge_length_text(scene.deformable.edge_length).c_str());
  if (zones)
    // Indented "Time =" lines are ignored when test output is compared.
    std::printf("   Time = %.3f s to mesh and set up the zones (%.3g zones/s); peak memory %s\n",
                meshing_seconds, system.mesh_report.zones / meshing_seconds,
                memory_text(peak_memory()).c_str());
  if (zones && system.mesh_report.hexes > 0)
    std::printf("Hexahedra:    %u (mixed discretization: the tetrahedra are their two overlays of "
                "five)\n",
                system.mesh_report.hexes);
  if (zones)
  {
    print_mesh_quality(system.mesh_report, mesh, *zones, model);
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
  PvdSeries zone_series(prefix + "_zones.pvd");
  std::unique_ptr<ZoneWriter> zone_writer;
  if (zones)
    zone_writer = std::make_unique<ZoneWriter>(mesh, scene.output.vtu_encoding);
  unsigned int zone_frame = 0;

  std::vector<std::string> columns{"step",
                                   "time (s)",
                                   "unbalanced ratio",
                                   "kinetic energy (J)",
                                   "work of gravity (J)",
                                   "joint elastic energy (J)",
                                   "friction dissipation (J)",
                                   "damping dissipation (J)",
                                   "work of boundaries (J)",
                                   "zone elastic energy (J)",
                                   "plastic dissipation (J)",
                                   "energy balance error (J)"};
  for (unsigned int b : scene.solver.history_blocks)
    for (const char* q : {"ux", "uy", "uz", "vx", "vy", "vz"})
      columns.push_back("block " + std::to_string(b) + " " + q + (q[0] == 'u' ? " (m)" : " (m/s)"));
  const PointHistory points(mesh, zones ? scene.solver.history_points : std::vector<Vec3>{});
  if (!zones && !scene.solver.history_points.empty())
    std::printf("Warning: 'History points' follow deformable blocks; this scene has none\n");
  points.add_columns(columns);
  Checkpoint checkpoint(scene, model, &solver, zones, restart_from);
  HistoryFile history(prefix + "_history.csv", columns, 100, restart_from.empty());
  ProgressLine progress(scene.solver.steps);
  unsigned int frame = 0;
  PvdSeries contact_series(prefix + "_contacts.pvd");
  // 'Joint set N' and 'Joint N' as N, for the contacts' joint_set and joint.
  JointNumbers joint_numbers;
  for (const std::string& section : scene.joint_set_sections)
    joint_numbers.joint_set_number.push_back(std::stoi(section.substr(section.rfind(' ') + 1)));
  for (const std::string& section : scene.joint_plane_sections)
    joint_numbers.joint_number.push_back(std::stoi(section.substr(section.rfind(' ') + 1)));
  checkpoint.add(history);
  for (PvdSeries* s : {&series, &contact_series, &zone_series})
    checkpoint.add(*s);
  checkpoint.add(frame);
  checkpoint.add(zone_frame);
  restore_run(checkpoint);
  bool diverged = false; // then forces and stresses may not be finite: motion only
  const auto output = [&](unsigned long step, double time)
  {
    progress.update(step, time, solver.unbalanced_ratio());
    if (!scene.output.write_vtu)
      return;
    char name[64];
    std::snprintf(name, sizeof name, "_blocks_%05u.vtu", frame++);
    const std::string vtu = scene.output.base_name + name;
    std::vector<BlockField> fields{
        {"displacement", 3, {}}, {"velocity", 3, {}}, {"rotation", 3, {}}};
    for (unsigned int b = 0; b < model.n_blocks(); ++b)
      for (int d = 0; d < 3; ++d)
      {
        fields[0].values.push_back(solver.displacement[b][d]);
        fields[1].values.push_back(solver.velocity[b][d]);
        fields[2].values.push_back(solver.rotation[b][d]);
      }
    write_blocks_vtu(scene.output.directory + "/" + vtu, model, fields, scene.output.vtu_encoding);
    series.add(time, vtu);
    if (diverged)
    {
      if (zones)
        write_zone_frame(scene, mesh, *zones, *zone_writer, zone_series, zone_frame++, false);
      return;
    }
    std::snprintf(name, sizeof name, "_contacts_%05u.vtu", frame - 1);
    const std::string contacts_vtu = scene.output.base_name + name;
    write_contacts_vtu(scene.output.directory + "/" + contacts_vtu, solver.contacts(), model,
                       joint_numbers, scene.output.vtu_encoding, &scene.solver.water,
                       scene.solver.gravity.norm());
    contact_series.add(time, contacts_vtu);
    if (zones)
      write_zone_frame(scene, mesh, *zones, *zone_writer, zone_series, zone_frame++);
  };
  const auto record = [&](unsigned long step, double time)
  {
    progress.update(step, time, solver.unbalanced_ratio());
    const EnergyAccount e = solver.energy_account();
    std::vector<double> row{double(step),   time,           solver.unbalanced_ratio(),
                            e.kinetic,      e.gravity_work, e.joint_elastic,
                            e.friction,     e.damping,      e.boundary_work,
                            e.zone_elastic, e.plastic,      e.error()};
    for (unsigned int b : scene.solver.history_blocks)
      for (const Vec3* q : {&solver.displacement[b], &solver.velocity[b]})
        for (int d = 0; d < 3; ++d)
          row.push_back((*q)[d]);
    if (zones)
      points.add_values(row, *zones);
    history.record(row);
  };
  SolverReport r;
  try
  {
    r = solver.run(output, record, [&](unsigned long step) { checkpoint.after_step(step); });
  }
  catch (const DivergenceError&)
  {
    // The last good state: nothing moved after the fault was found.
    diverged = true;
    output(solver.steps_done(), solver.time());
    progress.finish();
    throw;
  }
  progress.finish();
  std::printf("Steps:        %lu (time %.6g s)\n", r.steps, r.time);
  std::printf("Contacts:     %u with %u sub-contacts\n", r.contacts, r.subcontacts);
  if (scene.solver.water.active())
    std::printf("%s\n", solver.water_summary().c_str());
  if (scene.joint_material_names.size() > 1)
  {
    // Which material the contacts took: the check that the rules say what
    // was meant.
    std::vector<unsigned int> count(scene.joint_material_names.size(), 0);
    const ContactSet& cs = solver.contacts();
    for (unsigned int c = 0; c < cs.n_slots(); ++c)
      if (cs.alive[c])
        ++count[cs.material[c]];
    std::printf("Joint materials:");
    for (std::size_t k = 0; k < count.size(); ++k)
      std::printf("%s %s %u", k == 0 ? "" : ",", scene.joint_material_names[k].c_str(), count[k]);
    std::printf(" contacts\n");
  }
  std::printf("Unbalanced force ratio: %.3g\n", r.ratio);
  unsigned int moved_most = 0;
  for (unsigned int b = 0; b < model.n_blocks(); ++b)
    if (solver.displacement[b].norm() > solver.displacement[moved_most].norm())
      moved_most = b;
  if (model.n_blocks() > 0)
    std::printf("Largest displacement: %.6g m (block %u)\n", solver.displacement[moved_most].norm(),
                moved_most);
  for (unsigned int b : scene.solver.history_blocks)
    std::printf("Block %u displacement: %.9g, %.9g, %.9g m\n", b, solver.displacement[b][0],
                solver.displacement[b][1], solver.displacement[b][2]);
  const double total = r.seconds_detection + r.seconds_planes + r.seconds_forces + r.seconds_motion;
  std::printf(
      "   Time = %.3f s in the cycle: detection %.0f %%, common planes %.0f %%, forces %.0f %%, "
      "motion %.0f %%\n",
      total, 100 * r.seconds_detection / total, 100 * r.seconds_planes / total,
      100 * r.seconds_forces / total, 100 * r.seconds_motion / total);
  if (zones)
    std::printf("Largest gridpoint displacement: %.6g m\n", largest_gridpoint_displacement(*zones));
  std::printf("Output:       %s_blocks.pvd, %s_contacts.pvd, %s%s_history.csv\n", prefix.c_str(),
              prefix.c_str(), zones ? (prefix + "_zones.pvd, ").c_str() : "", prefix.c_str());
  const unsigned int b = solver.unbalanced_block();
  const Vec3& c = model.centroid[b];
  char where[200];
  std::snprintf(where, sizeof where, "block %u (group %s, centroid %.4g, %.4g, %.4g m)", b,
                model.group_names[model.group[b]].c_str(), c[0], c[1], c[2]);
  return {r.ratio, where};
}

/// The summary's lines on the history blocks: which block each is (so that
/// an id can be checked, and a point's block known), and a warning for a
/// fixed one, whose history holds only zeros.
void print_history_blocks(const talus::Scene& scene, const talus::BlockModel& model)
{
  for (unsigned int b : scene.solver.history_blocks)
  {
    const std::string& group = model.group_names[model.group[b]];
    const talus::Vec3& c = model.centroid[b];
    std::printf("History block %u: group %s, centroid %.6g, %.6g, %.6g m\n", b, group.c_str(), c[0],
                c[1], c[2]);
    if (std::find(scene.fixed_groups.begin(), scene.fixed_groups.end(), group) !=
        scene.fixed_groups.end())
      std::printf("Warning: history block %u is in the fixed group %s: its displacement and "
                  "velocity stay zero\n",
                  b, group.c_str());
  }
}

/// Exit code of a static run that stopped at its step limit above its
/// target ratio: scripts must be able to tell it from an equilibrium.
constexpr int exit_not_in_equilibrium = 4;

/// Warns, and returns exit_not_in_equilibrium, when a static run with a
/// target ratio ended above it; 0 otherwise.
int static_run_end(const talus::Scene& scene, const RunEnd& end)
{
  const talus::SolverSettings& s = scene.solver;
  if (s.dynamic || s.target_ratio <= 0.0 || end.ratio < s.target_ratio)
    return 0;
  std::printf("Warning: the run stopped at its step limit ('Steps' = %lu) with the unbalanced "
              "force ratio at %.3g, above 'Target ratio' = %g: the model is not in equilibrium "
              "(exit code %d); the largest unbalanced force is on %s; raise 'Steps', or set "
              "'Target ratio' = 0 to run a fixed number of steps\n",
              s.steps, end.ratio, s.target_ratio, exit_not_in_equilibrium, end.where.c_str());
  return exit_not_in_equilibrium;
}

/// `talus --check`: builds what a run would build before its first step
/// (the zones and the solvers, whose checks refuse an unstable time step
/// and the like) and prints what it found; writes nothing.
void check_calculation(talus::Scene& scene, talus::BlockModel& model)
{
  using namespace talus;
  if (scene.solver.steps == 0)
    return;
  const std::unique_ptr<ParallelEnvironment> parallel = zone_environment(scene);
  if (!scene.deformable.groups.empty() && model.n_blocks() == 1)
  {
    MeshReport report;
    const TetMesh mesh = single_block_zones(scene, model, report);
    check_boundary_selections(scene, model, mesh);
    ZoneMaterials materials = zone_materials(scene, model, mesh);
    const DeformableSolver solver(mesh, std::move(materials.materials),
                                  std::move(materials.of_zone), scene.solver,
                                  scene.gridpoint_conditions, scene.face_pressures,
                                  scene.has_initial_stress ? &scene.initial_stress : nullptr);
    std::printf("Zones:        %u, %u gridpoints\n", report.zones, report.gridpoints);
    std::printf("Time step:    %.6g s\n", solver.dt());
    return;
  }
  resolve_group_names(scene, model);
  const BlockSystem system = build_block_system(scene, model);
  check_boundary_selections(scene, model, system.mesh);
  if (system.zones)
    std::printf("Zones:        %u in %u deformable blocks, %u gridpoints\n",
                system.mesh_report.zones, system.mesh_report.blocks, system.mesh_report.gridpoints);
  std::printf("Time step:    %.6g s\n", system.solver->dt());
}

/// Runs the scene of `filename`; with `check_only`, reads, builds and checks
/// it and writes nothing.
int run(const std::string& filename, bool check_only = false)
{
  const auto start = std::chrono::steady_clock::now();
  // A restart writes into the checkpoint's folder, prepared there; a check
  // prepares nothing.
  talus::Scene scene = talus::read_scene(filename, restart_from.empty() && !check_only);
  if (!restart_from.empty())
    talus::continue_in_checkpoint_folder(restart_from, scene);

  // read_scene has checked every value and prepared the output folder;
  // what needs the blocks is checked before anything is written.
  talus::BuildReport report;
  talus::BlockModel model = talus::build_blocks(scene, report);
  talus::check_built_model(scene, model, report);
  talus::resolve_history_blocks(scene, model);
  if (check_only)
  {
    std::printf("talus: scene %s\n", std::filesystem::path(filename).filename().c_str());
    std::printf("Blocks:       %u\n", model.n_blocks());
    print_zone_estimate(scene, model);
    check_calculation(scene, model);
    std::printf("Check:        no problem found; nothing was written\n");
    return 0;
  }
  const std::string prefix = scene.output.directory + "/" + scene.output.base_name;
  talus::write_file_atomically(prefix + "_used_parameters.prm",
                               [&](std::ostream& out) { out << scene.used_parameters; });
  const auto built = std::chrono::steady_clock::now();

  std::printf("talus: scene %s\n", std::filesystem::path(filename).filename().c_str());
  std::printf("Blocks:       %u\n", model.n_blocks());
  std::printf("Faces:        %u\n", model.n_faces());
  std::printf("Vertices:     %u\n", model.n_vertices());
  std::printf("Total volume: %.9g m^3 (brick %.9g m^3)\n", model.total_volume(),
              scene.brick.volume());
  for (std::size_t e = 0; e < scene.excavations.size(); ++e)
    std::printf("Excavated:    %.9g m^3 (%s; region volume %.9g m^3)\n", report.excavated_volume[e],
                scene.excavations[e].description.c_str(), scene.excavations[e].region.volume);
  if (scene.rock_materials.empty())
    std::printf("Mass:         %.9g kg (density %g kg/m^3)\n", model.total_volume() * scene.density,
                scene.density);
  else
  {
    double mass = 0.0;
    for (unsigned int b = 0; b < model.n_blocks(); ++b)
      mass += scene.density_of(model.group_names[model.group[b]]) * model.volume[b];
    std::printf("Mass:         %.9g kg (density %g kg/m^3; rock materials:", mass, scene.density);
    for (const talus::RockMaterialSpec& r : scene.rock_materials)
      std::printf(" %s %g", r.name.c_str(), r.density);
    std::printf(")\n");
  }
  std::map<unsigned int, unsigned int> per_group;
  for (unsigned int g : model.group)
    ++per_group[g];
  for (const auto& [g, count] : per_group)
    std::printf("Group %-8s %u blocks\n", model.group_names[g].c_str(), count);
  std::printf("Cuts:         %lu\n", report.cutting.cuts);
  if (report.cutting.skipped_slivers > 0)
    std::printf("Warning: %lu cuts were not made because a piece would have been smaller than "
                "the minimum block volume %g m^3 (smallest %.3g m^3 near %.4g, %.4g, %.4g)\n",
                report.cutting.skipped_slivers, scene.cutting.minimum_volume,
                report.cutting.smallest_refused, report.cutting.smallest_refused_at[0],
                report.cutting.smallest_refused_at[1], report.cutting.smallest_refused_at[2]);

  print_history_blocks(scene, model);

  talus::PvdSeries series(prefix + "_blocks.pvd");
  if (scene.solver.steps == 0 && scene.output.write_vtu)
  {
    const std::string vtu = scene.output.base_name + "_blocks_00000.vtu";
    talus::write_blocks_vtu(scene.output.directory + "/" + vtu, model, {},
                            scene.output.vtu_encoding);
    series.add(0.0, vtu);
    std::printf("Output:       %s_blocks.pvd\n", prefix.c_str());
  }
  int exit_code = 0;
  if (scene.solver.steps > 0)
  {
    const RunEnd end = !scene.deformable.groups.empty() && model.n_blocks() == 1
                           ? solve_deformable(scene, model, prefix)
                           : solve(scene, model, series, prefix);
    exit_code = static_run_end(scene, end);
  }
  const auto done = std::chrono::steady_clock::now();
  // Indented "Time =" lines are ignored when test output is compared.
  std::printf("   Time = %.3f s (blocks %.3f s, then the calculation and output %.3f s)\n",
              std::chrono::duration<double>(done - start).count(),
              std::chrono::duration<double>(built - start).count(),
              std::chrono::duration<double>(done - built).count());
  return exit_code;
}

} // namespace

int main(int argc, char** argv)
{
  // Each summary line reaches a redirected standard output as it is
  // printed, not at the end of the run.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  if (argc == 2 && std::strcmp(argv[1], "--version") == 0)
  {
    std::printf("talus %s (git %s)\n", TALUS_VERSION, TALUS_GIT_REVISION);
    return 0;
  }
  const bool check = argc == 3 && std::strcmp(argv[1], "--check") == 0;
  const bool restart = (argc == 3 || argc == 4) && std::strcmp(argv[1], "--restart") == 0;
  if ((argc != 2 && !restart && !check) || std::strcmp(argv[1], "--help") == 0 ||
      std::strcmp(argv[1], "-h") == 0)
  {
    std::fputs(usage, argc == 2 ? stdout : stderr);
    return argc == 2 ? 0 : 1;
  }
  std::string scene_file = check ? argv[2] : argv[1];
  try
  {
    if (check)
      return run(scene_file, true);
    if (restart)
    {
      restart_from = argv[2];
      // The parameter file may be named (a moved project); else the checkpoint's.
      scene_file =
          argc == 4 ? std::string(argv[3]) : talus::checkpoint_parameter_file(restart_from);
    }
    const int code = run(scene_file);
    // A summary that could not be written (a full disk) is a failed run.
    if (std::fflush(stdout) != 0 || std::ferror(stdout))
    {
      std::fprintf(stderr, "talus: error: standard output could not be written (%s)\n",
                   std::strerror(errno));
      return 1;
    }
    return code;
  }
  catch (const talus::RunInterrupted& e)
  {
    std::fflush(stdout); // the summary so far, then the message
    std::fprintf(stderr, "talus: %s\n", e.what());
    return e.exit_code();
  }
  catch (const talus::InputError& e)
  {
    std::fflush(stdout); // the summary so far, then the message
    std::fprintf(stderr, "talus: error: %s\n", e.what());
  }
  catch (const talus::DivergenceError& e)
  {
    std::fflush(stdout); // the summary so far, then the message
    std::fprintf(stderr,
                 "talus: error in %s: %s (the state of the last good step is written to the "
                 "output folder)\n",
                 scene_file.c_str(), e.what());
    return 3;
  }
  catch (const talus::GeometryError& e)
  {
    std::fflush(stdout); // the summary so far, then the message
    std::fprintf(stderr, "talus: error in %s: %s\n", scene_file.c_str(), e.what());
  }
  catch (const std::bad_alloc&)
  {
    // The estimates of scene_checks.h let the model start; it needed more.
    std::fflush(stdout); // the summary so far, then the message
    std::fprintf(stderr,
                 "talus: error in %s: out of memory (this machine has %s left); make the model "
                 "smaller: a larger 'Edge length' or 'Spacing', fewer deformable groups\n",
                 scene_file.c_str(), talus::memory_text(talus::available_memory()).c_str());
  }
  catch (const std::exception& e)
  {
    std::fflush(stdout); // the summary so far, then the message
    std::fprintf(stderr, "talus: internal error (please report it): %s\n", e.what());
    return 2;
  }
  return 1;
}
