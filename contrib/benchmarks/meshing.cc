// Meshing convex jointed blocks into tetrahedral zones: talus's meshers
// (zone/convex_block_mesher, gmsh's C++ API; zone/lattice_block_mesher,
// CGAL's Delaunay triangulation of lattice points) and, for comparison, CGAL's 3D
// mesh generator Mesh_3 (cgal_block_mesher.cc, benchmark only) on the same
// blocks. A brick is cut by three oblique joint sets 3 m apart into about 10,
// 100 and 1,000 blocks (rock around an excavation), meshed at a target edge
// length h; each row runs in a child process of its own so that its memory
// peak is its own. Per row and mesher it prints:
//   zones/s     zones made per second of the child's CPU time (one core),
//               then per second of wall-clock time (lower when the machine
//               is shared): the whole mesh_convex_blocks call (or Mesh_3
//               block by block), the statistics not included;
//   us/zone     the same as time per zone, for linearity across rows;
//   count/band  zones over regular_tetrahedra_in(V, h) summed over blocks,
//               and the share of the blocks at least h thick (least width
//               across a face) whose own count is within 0.5-2x of it;
//   quality     normalised radius ratio (radius_ratio): least, 1st
//               percentile, median, and the zones below 0.1;
//   B/zone      the rise of the peak resident memory (VmHWM, reset through
//               /proc/self/clear_refs) while meshing, over the zones; gmsh's
//               start-up (gmsh::initialize) is not in it but printed apart;
//   vol err     largest |sum of zone volumes - block volume| / block volume,
//               and how many blocks miss by more than 1e-9.
// Run:
//   cmake --build build --target benchmark_meshing && build/contrib/benchmarks/benchmark_meshing
// Arguments (all optional): rows (10, 100, 1000: h = 0.5 m; 1000c: the 1,000
// blocks at h = 0.75 m; 1000x: at h = 1.5 m; 100f: the 100 blocks at
// h = 0.25 m, eight times the zones per block), meshers (gmsh, cgal,
// lattice: zone/lattice_block_mesher, as mesh_blocks with Mesher = lattice),
// runs=N (each row and mesher N times, taking turns; the fastest is shown,
// all on standard error), batch=N (blocks per gmsh model; 1 as mesh_blocks),
// and gmsh options as Name=value (e.g. Mesh.Algorithm3D=1, Mesh.Optimize=0),
// set once gmsh is started; cgal-scale=x (CGAL's sizes for x h); detail (one
// line per block on standard error). Without rows or meshers: gmsh and
// lattice on every row and CGAL on 10 and 100 (CGAL on 1000 takes
// about two CPU minutes: `benchmark_meshing 1000 cgal`).

#include "benchmark_arguments.h"
#include "cgal_block_mesher.h"

#include <talus/geometry/block_generator.h>
#include <talus/model/block_model.h>
#include <talus/zone/convex_block_mesher.h>
#include <talus/zone/lattice_block_mesher.h>

#include <gmsh.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <exception>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <utility>
#include <vector>

namespace
{
using namespace talus;

struct Row
{
  const char* name;
  double side; // m, the brick's edge
  double h;    // m, target zone edge length
};

// Sides chosen so that the three joint sets 3 m apart make about 10, 100 and
// 1,000 blocks (blocks of ~20 m^3: ~1,300 zones each at h = 0.5 m).
const Row rows[] = {{"10", 3.7, 0.5},
                    {"100", 10.0, 0.5},
                    {"1000", 26.2, 0.5},
                    {"1000c", 26.2, 0.75},
                    {"1000x", 26.2, 1.5},
                    {"100f", 10.0, 0.25}};

BlockModel jointed_model(double side)
{
  BlockGenerator generator(ConvexPolyhedron::box(Vec3::Zero(), Vec3::Constant(side)), {});
  // One sub-horizontal set and two steep ones crossing it, as in
  // block_generation.cc, at a spacing typical of rock around an excavation.
  generator.cut_joint_set({10.0, 30.0, 3.0, Vec3::Constant(1.5), 0, false, {}});
  generator.cut_joint_set({80.0, 120.0, 3.0, Vec3::Constant(1.5), 0, false, {}});
  generator.cut_joint_set({75.0, 220.0, 3.0, Vec3::Constant(1.5), 0, false, {}});
  BlockModel model;
  for (const ConvexPolyhedron& b : generator.blocks())
    model.add_block(b, 0);
  return model;
}

/// The block's least width across one of its faces.
double thickness(const BlockModel& m, unsigned int b)
{
  double least = INFINITY;
  for (unsigned int f = m.face_start[b]; f < m.face_start[b + 1]; ++f)
  {
    const Vec3& n = m.face_normal[f];
    const double on_face = n.dot(m.vertex[m.face_vertex[m.face_loop_start[f]]]);
    double deepest = on_face;
    for (unsigned int v = m.vertex_start[b]; v < m.vertex_start[b + 1]; ++v)
      deepest = std::min(deepest, n.dot(m.vertex[v]));
    least = std::min(least, on_face - deepest);
  }
  return least;
}

/// The block's shortest edge.
double shortest_edge(const BlockModel& m, unsigned int b)
{
  double least = INFINITY;
  for (unsigned int f = m.face_start[b]; f < m.face_start[b + 1]; ++f)
  {
    const unsigned int first = m.face_loop_start[f], n = m.face_loop_start[f + 1] - first;
    for (unsigned int k = 0; k < n; ++k)
      least = std::min(
          least, (m.vertex[m.face_vertex[first + k]] - m.vertex[m.face_vertex[first + (k + 1) % n]])
                     .norm());
  }
  return least;
}

/// A field of /proc/self/status in bytes (VmRSS, VmHWM).
double status_bytes(const char* field)
{
  FILE* f = std::fopen("/proc/self/status", "r");
  char line[256];
  double kb = 0.0;
  const std::size_t n = std::strlen(field);
  while (f != nullptr && std::fgets(line, sizeof line, f) != nullptr)
    if (std::strncmp(line, field, n) == 0 && line[n] == ':')
      kb = std::atof(line + n + 1);
  if (f != nullptr)
    std::fclose(f);
  return kb * 1024.0;
}

/// Sets the peak resident size back to the current one (Linux >= 4.0).
bool reset_peak_memory()
{
  FILE* f = std::fopen("/proc/self/clear_refs", "w");
  if (f == nullptr)
    return false;
  const bool ok = std::fputs("5", f) >= 0;
  return std::fclose(f) == 0 && ok;
}

double cpu_seconds()
{
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

/// What one child measured (sent through a pipe, so plain data).
struct Result
{
  bool ok = false;
  char why[200] = "";
  unsigned int blocks = 0, failed_blocks = 0, thick_blocks = 0, thick_in_band = 0;
  unsigned int thick2_blocks = 0, thick2_in_band = 0; // at least 2h thick
  double zones = 0, band = 0, cpu = 0, wall = 0;
  double q_min = 0, q_1 = 0, q_median = 0, below_01 = 0;
  double below_01_thick = 0, q_min_thick = 1; // in blocks at least h thick
  double peak_rise = 0, start_up = 0, volume_error = 0;
  unsigned int volume_off = 0; // blocks whose zones miss its volume by more than 1e-9
  unsigned int by_gmsh = 0;    // lattice rows: blocks the lattice mesher left to gmsh
  bool peak_reset = false;
};

struct Settings
{
  bool detail = false;     // one line per block on standard error
  double cgal_scale = 1.0; // CGAL's sizes for h times this
  std::size_t batch = 1; // as mesh_blocks does
  std::vector<std::pair<std::string, double>> gmsh_options;
};

Result measure(const Row& row, const std::string& mesher, const Settings& settings)
{
  Result r;
  const BlockModel model = jointed_model(row.side);
  r.blocks = model.n_blocks();
  std::vector<unsigned int> all(model.n_blocks());
  for (unsigned int b = 0; b < model.n_blocks(); ++b)
    all[b] = b;

  const double rss_model = status_bytes("VmRSS");
  std::vector<BlockTetrahedra> meshes;
  std::vector<bool> meshed(model.n_blocks(), true);
  double cpu0 = 0, cpu1 = 0;
  std::chrono::steady_clock::time_point wall0, wall1;
  try
  {
    if (mesher == "gmsh")
    {
      GmshSession session; // alive through the meshing, so options stay
      for (const auto& [name, value] : settings.gmsh_options)
        gmsh::option::setNumber(name, value);
      r.start_up = status_bytes("VmRSS") - rss_model;
      r.peak_reset = reset_peak_memory();
      wall0 = std::chrono::steady_clock::now();
      cpu0 = cpu_seconds();
      meshes = mesh_convex_blocks(
          model, all, [h = row.h](const Vec3&) { return h; }, settings.batch);
      cpu1 = cpu_seconds();
      wall1 = std::chrono::steady_clock::now();
      r.peak_rise = status_bytes("VmHWM") - rss_model - r.start_up;
    }
    else if (mesher == "lattice")
    {
      // As mesh_blocks does with Mesher = lattice: blocks the lattice mesher
      // fails on go to gmsh (counted apart).
      r.peak_reset = reset_peak_memory();
      wall0 = std::chrono::steady_clock::now();
      cpu0 = cpu_seconds();
      unsigned int by_lattice = 0;
      meshes = mesh_convex_blocks_with(
          model, all, [h = row.h](const Vec3&) { return h; }, ConvexMesher::lattice, &by_lattice);
      cpu1 = cpu_seconds();
      wall1 = std::chrono::steady_clock::now();
      r.peak_rise = status_bytes("VmHWM") - rss_model;
      r.by_gmsh = model.n_blocks() - by_lattice;
    }
    else
    {
      const CgalCriteria criteria = cgal_criteria_for(row.h * settings.cgal_scale);
      r.peak_reset = reset_peak_memory();
      wall0 = std::chrono::steady_clock::now();
      cpu0 = cpu_seconds();
      for (unsigned int b = 0; b < model.n_blocks(); ++b)
      {
        try
        {
          meshes.push_back(cgal_mesh_convex_block(model, b, criteria));
        }
        catch (const std::exception& e)
        {
          meshes.emplace_back();
          meshed[b] = false;
          if (r.failed_blocks++ == 0)
            std::snprintf(r.why, sizeof r.why, "%s", e.what());
        }
      }
      cpu1 = cpu_seconds();
      wall1 = std::chrono::steady_clock::now();
      r.peak_rise = status_bytes("VmHWM") - rss_model;
    }
  }
  catch (const std::exception& e)
  {
    std::snprintf(r.why, sizeof r.why, "%s", e.what());
    return r;
  }
  r.cpu = cpu1 - cpu0;
  r.wall = std::chrono::duration<double>(wall1 - wall0).count();

  std::vector<double> quality;
  for (unsigned int b = 0; b < model.n_blocks(); ++b)
  {
    if (!meshed[b])
      continue;
    const BlockTetrahedra& t = meshes[b];
    const double count = t.tet.size(), band = regular_tetrahedra_in(model.volume[b], row.h);
    r.zones += count;
    r.band += band;
    const bool in_band = count >= 0.5 * band && count <= 2.0 * band;
    const double thick = thickness(model, b);
    if (thick >= row.h)
    {
      ++r.thick_blocks;
      r.thick_in_band += in_band;
    }
    if (thick >= 2.0 * row.h)
    {
      ++r.thick2_blocks;
      r.thick2_in_band += in_band;
    }
    double volume = 0, worst = 1;
    unsigned int poor = 0;
    for (const auto& z : t.tet)
    {
      const Vec3 &a = t.point[z[0]], &b1 = t.point[z[1]], &c = t.point[z[2]], &d = t.point[z[3]];
      quality.push_back(radius_ratio(a, b1, c, d));
      worst = std::min(worst, quality.back());
      poor += quality.back() < 0.1;
      volume += (b1 - a).dot((c - a).cross(d - a)) / 6.0;
    }
    if (thick >= row.h)
    {
      r.below_01_thick += poor;
      r.q_min_thick = std::min(r.q_min_thick, worst);
    }
    const double volume_error = std::abs(volume - model.volume[b]) / model.volume[b];
    r.volume_error = std::max(r.volume_error, volume_error);
    r.volume_off += volume_error > 1e-9;
    if (settings.detail)
      std::fprintf(
          stderr,
          "%s %s block %u: V %.4g m^3 thick %.3g m edge >= %.2g m faces %u zones %.0f band %.0f "
          "ratio %.2f q min %.3f < 0.1: %u vol err %.1e\n",
          mesher.c_str(), row.name, b, model.volume[b], thick, shortest_edge(model, b),
          model.face_start[b + 1] - model.face_start[b], count, band, count / band, worst, poor,
          std::abs(volume - model.volume[b]) / model.volume[b]);
  }
  std::sort(quality.begin(), quality.end());
  if (!quality.empty())
  {
    r.q_min = quality.front();
    r.q_1 = quality[quality.size() / 100];
    r.q_median = quality[quality.size() / 2];
    r.below_01 = std::lower_bound(quality.begin(), quality.end(), 0.1) - quality.begin();
  }
  r.ok = true;
  return r;
}

/// Runs measure() in a child process: a fresh memory peak, and a crash in a
/// mesher is a failed row rather than the end of the benchmark.
Result measure_in_child(const Row& row, const std::string& mesher, const Settings& settings)
{
  int fd[2];
  Result r;
  if (pipe(fd) != 0)
  {
    std::snprintf(r.why, sizeof r.why, "no pipe");
    return r;
  }
  std::fflush(nullptr);
  const pid_t child = fork();
  if (child == 0)
  {
    close(fd[0]);
    const Result mine = measure(row, mesher, settings);
    const bool sent = write(fd[1], &mine, sizeof mine) == static_cast<ssize_t>(sizeof mine);
    std::fflush(nullptr);
    _exit(sent ? 0 : 1);
  }
  close(fd[1]);
  const bool received = child > 0 && read(fd[0], &r, sizeof r) == static_cast<ssize_t>(sizeof r);
  close(fd[0]);
  int status = 0;
  if (child > 0)
    waitpid(child, &status, 0);
  if (!received)
  {
    r = Result();
    std::snprintf(r.why, sizeof r.why, "the child died (status %d)", status);
  }
  return r;
}

std::string thousands(double x)
{
  std::string digits = std::to_string(static_cast<long long>(std::llround(x)));
  for (int i = static_cast<int>(digits.size()) - 3; i > 0; i -= 3)
    digits.insert(static_cast<std::size_t>(i), ",");
  return digits;
}
} // namespace

int main(int argc, char** argv)
{
  std::vector<const Row*> chosen_rows;
  std::vector<std::string> meshers;
  Settings settings;
  unsigned long runs = 1;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    const auto eq = a.find('=');
    const Row* row = nullptr;
    for (const Row& r : rows)
      if (a == r.name)
        row = &r;
    if (row != nullptr)
      chosen_rows.push_back(row);
    else if (a == "gmsh" || a == "cgal" || a == "lattice")
      meshers.push_back(a);
    else if (a == "detail")
      settings.detail = true;
    else if (a.rfind("cgal-scale=", 0) == 0)
    {
      char* end = nullptr;
      settings.cgal_scale = std::strtod(argv[i] + 11, &end);
      if (end == argv[i] + 11 || *end != '\0' || !(settings.cgal_scale > 0.0))
      {
        std::fprintf(stderr, "%s: argument '%s': cgal-scale must be a positive number\n", argv[0],
                     argv[i]);
        return 2;
      }
    }
    else if (a.rfind("runs=", 0) == 0)
      runs = whole_argument(argv[0], argv[i] + 5, "runs", 1, 100);
    else if (a.rfind("batch=", 0) == 0)
      settings.batch = whole_argument(argv[0], argv[i] + 6, "batch", 1, 1000000);
    else if (eq != std::string::npos && a.find('.') < eq)
    {
      char* end = nullptr;
      const double value = std::strtod(a.c_str() + eq + 1, &end);
      if (end == a.c_str() + eq + 1 || *end != '\0')
      {
        std::fprintf(stderr, "%s: argument '%s': a gmsh option's value must be a number\n", argv[0],
                     argv[i]);
        return 2;
      }
      settings.gmsh_options.emplace_back(a.substr(0, eq), value);
    }
    else
    {
      std::fprintf(
          stderr,
          "%s: argument '%s': allowed are rows 10 100 1000 1000c 1000x 100f, meshers "
          "gmsh cgal lattice, runs=N, batch=N, cgal-scale=x, detail and gmsh options Name=value\n",
          argv[0], argv[i]);
      return 2;
    }
  }
  // What runs: every chosen mesher on every chosen row; by default gmsh on
  // every row and CGAL on the rows it finishes in a minute or so.
  std::vector<std::pair<const Row*, std::string>> jobs;
  if (chosen_rows.empty() && meshers.empty())
  {
    for (const Row& r : rows)
      jobs.emplace_back(&r, "gmsh");
    for (const Row& r : rows)
      jobs.emplace_back(&r, "lattice");
    for (const char* name : {"10", "100"})
      for (const Row& r : rows)
        if (std::strcmp(r.name, name) == 0)
          jobs.emplace_back(&r, "cgal");
  }
  else
  {
    if (chosen_rows.empty())
      for (const Row& r : rows)
        chosen_rows.push_back(&r);
    if (meshers.empty())
      meshers = {"gmsh"};
    for (const std::string& m : meshers)
      for (const Row* r : chosen_rows)
        jobs.emplace_back(r, m);
  }

  std::vector<std::vector<Result>> results(jobs.size());
  for (unsigned long run = 0; run < runs; ++run)
    for (std::size_t j = 0; j < jobs.size(); ++j)
    {
      const Result r = measure_in_child(*jobs[j].first, jobs[j].second, settings);
      std::fprintf(stderr, "run %lu %s %-5s: %s zones %.0f cpu %.3f s wall %.3f s%s%s\n", run + 1,
                   jobs[j].second.c_str(), jobs[j].first->name, r.ok ? "ok" : "FAILED", r.zones,
                   r.cpu, r.wall, r.why[0] ? " - " : "", r.why);
      results[j].push_back(r);
    }

  std::printf(
      "| mesher | row | h (m) | blocks | zones | zones/s (CPU; wall) | us/zone | count/band "
      "| in band: blocks >= h / >= 2h thick | quality min / 1 %% / median | zones < 0.1 (in blocks "
      ">= h thick: number, least) | B/zone "
      "(start-up MB) | vol err (blocks > 1e-9) |\n");
  std::printf("|---|---|---:|---:|---:|---|---:|---:|---|---|---:|---|---:|\n");
  for (std::size_t j = 0; j < jobs.size(); ++j)
  {
    const std::vector<Result>& all = results[j];
    const Result* best = nullptr;
    for (const Result& r : all)
      if (r.ok && (best == nullptr || r.cpu < best->cpu))
        best = &r;
    if (best == nullptr)
    {
      std::printf("| %s | %s | %.2f | | | failed: %s | | | | | | | |\n", jobs[j].second.c_str(),
                  jobs[j].first->name, jobs[j].first->h, all.front().why);
      continue;
    }
    const Result& r = *best;
    std::string rates = thousands(r.zones / r.cpu);
    for (const Result& o : all)
      if (o.ok && &o != best)
        rates += ", " + thousands(o.zones / o.cpu);
    rates += "; " + thousands(r.zones / r.wall);
    std::string blocks = thousands(r.blocks);
    if (r.failed_blocks > 0)
      blocks += " (" + std::to_string(r.failed_blocks) + " failed)";
    if (r.by_gmsh > 0)
      blocks += " (" + std::to_string(r.by_gmsh) + " by gmsh)";
    std::printf("| %s | %s | %.2f | %s | %s | %s | %.1f | %.2f | %u of %u / %u of %u | %.3f / %.3f "
                "/ %.3f | "
                "%.0f (%.0f, %.3f) | %.0f%s (%.0f) | %.0e (%u) |\n",
                jobs[j].second.c_str(), jobs[j].first->name, jobs[j].first->h, blocks.c_str(),
                thousands(r.zones).c_str(), rates.c_str(), 1e6 * r.cpu / r.zones, r.zones / r.band,
                r.thick_in_band, r.thick_blocks, r.thick2_in_band, r.thick2_blocks, r.q_min, r.q_1,
                r.q_median, r.below_01, r.below_01_thick, r.q_min_thick, r.peak_rise / r.zones,
                r.peak_reset ? "" : "*", r.start_up / 1048576.0, r.volume_error, r.volume_off);
  }
  std::printf("\nzones/s: the fastest of the runs first, then the others, then the fastest "
              "run's wall-clock rate.%s\n",
              settings.gmsh_options.empty() && settings.batch == 1 ? ""
                                                                    : " (gmsh options changed)");
  return 0;
}
