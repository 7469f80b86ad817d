// talus: three-dimensional distinct element code for jointed rock.
// Usage: talus scene.prm

#include <talus/base/exceptions.h>
#include <talus/io/block_vtu_writer.h>
#include <talus/io/file_output.h>
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

int run(const std::string& filename)
{
  const auto start = std::chrono::steady_clock::now();
  talus::Scene scene = talus::read_scene(filename);

  // read_scene has checked every value and prepared the output folder.
  const std::string prefix = scene.output.directory + "/" + scene.output.base_name;
  talus::write_file_atomically(prefix + "_used_parameters.prm",
                               [&](std::ostream& out) { out << scene.used_parameters; });

  talus::BuildReport report;
  const talus::BlockModel model = talus::build_blocks(scene, report);
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

  if (scene.output.write_vtu)
  {
    const std::string vtu = scene.output.base_name + "_blocks_00000.vtu";
    talus::write_blocks_vtu(scene.output.directory + "/" + vtu, model);
    talus::PvdSeries series(prefix + "_blocks.pvd");
    series.add(0.0, vtu);
    std::printf("Output:       %s_blocks.pvd\n", prefix.c_str());
  }
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
