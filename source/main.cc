// talus: three-dimensional distinct element code for jointed rock.
// Usage: talus scene.prm

#include <talus/base/exceptions.h>
#include <talus/io/block_vtu_writer.h>
#include <talus/io/contact_vtu_writer.h>
#include <talus/io/file_output.h>
#include <talus/io/history_file.h>
#include <talus/solver/rigid_solver.h>
#include <talus/io/scene.h>
#include <talus/model/build_blocks.h>

#include <chrono>
#include <filesystem>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <map>

namespace
{

constexpr const char* usage = "usage: talus SCENE.prm\n"
                              "  Builds the block model the parameter file describes, writes it\n"
                              "  for ParaView into the output folder it names, and prints a summary.\n"
                              "  Shipped scenes are in the parameters/ folder.\n";

/// Runs the calculation the scene asks for, with output and histories.
void solve(talus::Scene& scene, talus::BlockModel& model, talus::PvdSeries& series,
           const std::string& prefix)
{
  using namespace talus;
  resolve_group_names(scene, model);
  for (unsigned int b : scene.solver.history_blocks)
    if (b >= model.n_blocks())
      throw InputError(scene.parameter_file + ": entry 'History blocks' in subsection 'Solver': "
                       "block " + std::to_string(b) + " does not exist; allowed: 0 to " +
                       std::to_string(model.n_blocks() - 1));
  RigidSolver solver(model, scene.density, scene.solver);
  std::printf("Time step:    %.6g s (eq. 87, fraction %g)\n", solver.dt(),
              scene.solver.time_step_fraction);

  std::vector<std::string> columns{"step",
                                   "time (s)",
                                   "unbalanced ratio",
                                   "kinetic energy (J)",
                                   "work of gravity (J)",
                                   "joint elastic energy (J)",
                                   "friction dissipation (J)",
                                   "damping dissipation (J)"};
  for (unsigned int b : scene.solver.history_blocks)
    for (const char* q : {"ux", "uy", "uz", "vx", "vy", "vz"})
      columns.push_back("block " + std::to_string(b) + " " + q + (q[0] == 'u' ? " (m)" : " (m/s)"));
  HistoryFile history(prefix + "_history.csv", columns);
  ProgressLine progress(scene.solver.steps);
  unsigned int frame = 0;
  PvdSeries contact_series(prefix + "_contacts.pvd");
  const auto output = [&](unsigned long step, double time) {
    progress.update(step, time);
    if (!scene.output.write_vtu)
      return;
    char name[64];
    std::snprintf(name, sizeof name, "_blocks_%05u.vtu", frame++);
    const std::string vtu = scene.output.base_name + name;
    std::vector<BlockField> fields{{"displacement", 3, {}}, {"velocity", 3, {}}, {"rotation", 3, {}}};
    for (unsigned int b = 0; b < model.n_blocks(); ++b)
      for (int d = 0; d < 3; ++d)
      {
        fields[0].values.push_back(solver.displacement[b][d]);
        fields[1].values.push_back(solver.velocity[b][d]);
        fields[2].values.push_back(solver.rotation[b][d]);
      }
    write_blocks_vtu(scene.output.directory + "/" + vtu, model, fields);
    series.add(time, vtu);
    std::snprintf(name, sizeof name, "_contacts_%05u.vtu", frame - 1);
    const std::string contacts_vtu = scene.output.base_name + name;
    write_contacts_vtu(scene.output.directory + "/" + contacts_vtu, solver.contacts());
    contact_series.add(time, contacts_vtu);
  };
  const auto record = [&](unsigned long step, double time) {
    progress.update(step, time);
    std::vector<double> row{double(step),
                            time,
                            solver.unbalanced_ratio(),
                            solver.kinetic_energy(),
                            solver.gravity_work(),
                            solver.joint_energy(),
                            solver.friction_dissipation(),
                            solver.damping_dissipation()};
    for (unsigned int b : scene.solver.history_blocks)
      for (const Vec3* q : {&solver.displacement[b], &solver.velocity[b]})
        for (int d = 0; d < 3; ++d)
          row.push_back((*q)[d]);
    history.record(row);
  };
  const SolverReport r = solver.run(output, record);
  progress.finish();
  std::printf("Steps:        %lu (time %.6g s)\n", r.steps, r.time);
  std::printf("Contacts:     %u with %u sub-contacts\n", r.contacts, r.subcontacts);
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
  std::printf("   Time = %.3f s in the cycle: detection %.0f %%, common planes %.0f %%, forces %.0f %%, "
              "motion %.0f %%\n",
              total, 100 * r.seconds_detection / total, 100 * r.seconds_planes / total,
              100 * r.seconds_forces / total, 100 * r.seconds_motion / total);
  std::printf("Output:       %s_blocks.pvd, %s_contacts.pvd, %s_history.csv\n", prefix.c_str(),
              prefix.c_str(), prefix.c_str());
}

int run(const std::string& filename)
{
  const auto start = std::chrono::steady_clock::now();
  talus::Scene scene = talus::read_scene(filename);

  // read_scene has checked every value and prepared the output folder.
  const std::string prefix = scene.output.directory + "/" + scene.output.base_name;
  talus::write_file_atomically(prefix + "_used_parameters.prm",
                               [&](std::ostream& out) { out << scene.used_parameters; });

  talus::BuildReport report;
  talus::BlockModel model = talus::build_blocks(scene, report);
  const auto built = std::chrono::steady_clock::now();

  std::printf("talus: scene %s\n", std::filesystem::path(filename).filename().c_str());
  std::printf("Blocks:       %u\n", model.n_blocks());
  std::printf("Faces:        %u\n", model.n_faces());
  std::printf("Vertices:     %u\n", model.n_vertices());
  std::printf("Total volume: %.9g m^3 (brick %.9g m^3)\n", model.total_volume(),
              scene.brick.volume());
  for (std::size_t e = 0; e < scene.excavations.size(); ++e)
    std::printf("Excavated:    %.9g m^3 (%s; region volume %.9g m^3)\n",
                report.excavated_volume[e], scene.excavations[e].description.c_str(),
                scene.excavations[e].region.volume);
  std::printf("Mass:         %.9g kg (density %g kg/m^3)\n", model.total_volume() * scene.density,
              scene.density);
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

  talus::PvdSeries series(prefix + "_blocks.pvd");
  if (scene.solver.steps == 0)
  {
    if (scene.output.write_vtu)
    {
      const std::string vtu = scene.output.base_name + "_blocks_00000.vtu";
      talus::write_blocks_vtu(scene.output.directory + "/" + vtu, model);
      series.add(0.0, vtu);
      std::printf("Output:       %s_blocks.pvd\n", prefix.c_str());
    }
  }
  else
    solve(scene, model, series, prefix);
  const auto done = std::chrono::steady_clock::now();
  // Indented "Time =" lines are ignored when test output is compared.
  std::printf("   Time = %.3f s (blocks %.3f s, output %.3f s)\n",
              std::chrono::duration<double>(done - start).count(),
              std::chrono::duration<double>(built - start).count(),
              std::chrono::duration<double>(done - built).count());
  return 0;
}

} // namespace

int main(int argc, char** argv)
{
  if (argc != 2 || std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0)
  {
    std::fputs(usage, argc == 2 ? stdout : stderr);
    return argc == 2 ? 0 : 1;
  }
  try
  {
    return run(argv[1]);
  }
  catch (const talus::InputError& e)
  {
    std::fprintf(stderr, "talus: error: %s\n", e.what());
  }
  catch (const talus::GeometryError& e)
  {
    std::fprintf(stderr, "talus: error in %s: %s\n", argv[1], e.what());
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "talus: internal error (please report it): %s\n", e.what());
    return 2;
  }
  return 1;
}
