// Zone VTU output: a unit cube meshed by mesh_blocks into 5 n^3
// tetrahedra is written as talus writes a zone frame (displacement and
// velocity per gridpoint; stress, principal_stress and plastic_state per
// zone), once as ASCII and once as compressed binary (the default), taking
// turns three times. Per size and encoding it prints the zones written per
// second (the fastest of the runs, wall clock; binary compresses on
// vtu_compression_lanes() threads), the zones per second of processor time
// (all threads; close to the wall-clock rate of one lane on an idle
// machine, less disturbed when the cores are shared), the file size per zone and
// the peak memory the write adds, per zone: the process's peak resident
// set (VmHWM, reset through /proc/self/clear_refs before each write) minus
// its resident set just before.
//
// The fields are made to compress like those of a run: smooth
// displacements and velocities, a gravitational stress with noise in its
// last digits, a third of the zones plastic.
//
// Run from a Release build:
//   cmake --build build --target benchmark_vtu_write
//   build/contrib/benchmarks/benchmark_vtu_write [n ...]
// Default n = 39 59 (296 k and 1.03 M zones). Files go to the working
// folder and are removed.

#include <talus/io/zone_vtu_writer.h>
#include <talus/model/block_model.h>
#include <talus/zone/block_mesher.h>

#include "benchmark_arguments.h"

#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#if __has_include(<talus/io/vtu_encoding.h>)
#include <talus/io/vtu_encoding.h>
#define TALUS_HAS_VTU_ENCODING 1
#endif

namespace
{

/// A field of /proc/self/status in bytes.
double status_bytes(const char* field)
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind(field, 0) == 0)
      return 1024.0 * std::stod(line.substr(std::string(field).size()));
  return 0.0;
}

struct Result
{
  double seconds = 1e300, cpu_seconds = 1e300, peak_bytes = 0.0, file_bytes = 0.0;
};

} // namespace

int main(int argc, char** argv)
{
  using namespace talus;
  std::vector<unsigned long> sizes;
  for (int a = 1; a < argc; ++a)
    sizes.push_back(whole_argument(argv[0], argv[a], "n (5 n^3 zones)", 2, 120));
  if (sizes.empty())
    sizes = {39, 59};
#ifdef TALUS_HAS_VTU_ENCODING
  const std::vector<std::pair<const char*, VtuEncoding>> encodings{{"ascii", VtuEncoding::ascii},
                                                                   {"binary", VtuEncoding::binary}};
#else
  const std::vector<std::pair<const char*, int>> encodings{{"dealii", 0}};
#endif
#ifdef TALUS_HAS_VTU_ENCODING
  std::printf("compression lanes: %u\n", vtu_compression_lanes());
#endif
  std::printf("%9s %9s %8s %12s %12s %12s %12s\n", "zones", "gridpts", "encoding", "zones/s",
              "zones/cpu-s", "file B/zone", "peak B/zone");
  for (const unsigned long n : sizes)
  {
    BlockModel blocks;
    blocks.add_block(ConvexPolyhedron::box(Vec3(0, 0, 0), Vec3(1, 1, 1)), 0);
    MeshReport report;
    const TetMesh mesh = mesh_blocks(blocks, {0}, 1.0 / static_cast<double>(n), report);
    const unsigned int n_zones = mesh.n_zones(), n_points = mesh.n_gridpoints();

    // Fields like a run's: smooth motion, stress with noise in its last
    // digits (a linear congruential sequence, the same every run).
    std::vector<double> x(3 * n_points), u(3 * n_points), v(3 * n_points);
    for (unsigned int g = 0; g < n_points; ++g)
      for (int d = 0; d < 3; ++d)
      {
        const double* p = &mesh.position[3 * g];
        u[3 * g + d] = 1e-3 * (p[0] * p[1] + (d + 1) * p[2] * p[2]);
        v[3 * g + d] = 1e-4 * (p[2] - 0.5 * d * p[0]);
        x[3 * g + d] = p[d] + u[3 * g + d];
      }
    std::vector<double> stress(6 * n_zones), principal(3 * n_zones), state(n_zones);
    unsigned long random = 12345;
    for (unsigned int z = 0; z < n_zones; ++z)
    {
      const double depth = 1.0 - mesh.position[3 * mesh.zone_gridpoint[z][0] + 2];
      for (int c = 0; c < 6; ++c)
      {
        random = random * 6364136223846793005ul + 1442695040888963407ul;
        const double noise = 1.0 + 1e-3 * static_cast<double>(random >> 40) / double(1ul << 24);
        stress[6 * z + c] = (c < 3 ? -2.6e4 * depth : 1e3 * depth) * noise;
      }
      principal_stresses(&stress[6 * z], &principal[3 * z]);
      state[z] = z % 3 == 0 ? 1.0 : 0.0;
    }
    const std::vector<ZoneField> point_fields{{"displacement", 3, u}, {"velocity", 3, v}};
    const std::vector<ZoneField> zone_fields{
        {"stress", 6, stress}, {"principal_stress", 3, principal}, {"plastic_state", 1, state}};

    std::vector<Result> results(encodings.size());
    for (int run = 0; run < 3; ++run)
      for (std::size_t e = 0; e < encodings.size(); ++e)
      {
        const std::string path = std::string("benchmark_vtu_write_") + encodings[e].first + ".vtu";
        malloc_trim(0);
        std::ofstream("/proc/self/clear_refs") << "5"; // VmHWM := VmRSS
        const double before = status_bytes("VmRSS:");
        const auto start = std::chrono::steady_clock::now();
        const std::clock_t cpu_start = std::clock();
        {
#ifdef TALUS_HAS_VTU_ENCODING
          ZoneWriter writer(mesh, encodings[e].second);
#else
          ZoneWriter writer(mesh);
#endif
          writer.write(path, x, point_fields, zone_fields, 1.0);
        }
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const double cpu_seconds = double(std::clock() - cpu_start) / CLOCKS_PER_SEC;
        Result& r = results[e];
        r.seconds = std::min(r.seconds, seconds);
        r.cpu_seconds = std::min(r.cpu_seconds, cpu_seconds);
        r.peak_bytes = std::max(r.peak_bytes, status_bytes("VmHWM:") - before);
        r.file_bytes = static_cast<double>(std::filesystem::file_size(path));
        std::filesystem::remove(path);
      }
    for (std::size_t e = 0; e < encodings.size(); ++e)
      std::printf("%9u %9u %8s %12.3g %12.3g %12.1f %12.1f\n", n_zones, n_points,
                  encodings[e].first, n_zones / results[e].seconds,
                  n_zones / results[e].cpu_seconds, results[e].file_bytes / n_zones,
                  results[e].peak_bytes / n_zones);
    std::fflush(stdout);
  }
  return 0;
}
