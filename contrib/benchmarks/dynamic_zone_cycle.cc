// Cost of damping in a dynamic zone step (issue 23): the elastic 10 m cube
// of zone_cycle.cc (rho = 2650, E = 1e10 Pa, nu = 0.25, its base on
// rollers), released unstressed under gravity (so that it sags and rings
// and every term has something to work on), in dynamic mode four ways on
// the same mesh:
//   none     undamped;
//   rayleigh Rayleigh damping, both terms (xi = 0.05 at 10 Hz: the mass
//            term -alpha m v at the gridpoints, the stiffness term's
//            viscous stress beta C d(eps)/dt in the zones);
//   quiet    quiet boundaries (Lysmer-Kuhlemeyer dashpots) on all six faces;
//   both     Rayleigh damping and quiet boundaries.
// for 4-node zones, hexahedral zones of mixed discretization, 10-node zones
// and 4-node zones with nodal mixed discretization (nmd, zones in columns
// as talus meshes them for it). Per element and mode it prints the time per
// zone-step (whole step: zone forces, motion, the account's works) and per
// gridpoint-step, and the cost of each damped mode over the undamped one
// measured in the same run, by the wall clock and in processor time (the
// latter less disturbed when other jobs share the cores). The time step of
// each mode is its own (the stiffness term lowers it); only the cost of a
// step is compared.
//
// Each mode's solver is built once and takes one step untimed; then the
// modes take turns (each one's first run, then each one's second, ...), so
// that a slow spell of the machine falls on every mode alike; the fastest
// run counts. Standard error gets sums of the state each mode reached (to
// compare builds: a faster kernel must give the same numbers).
//
// One core; run from a Release build:
//   cmake --build build --target benchmark_dynamic_zone_cycle
//   build/contrib/benchmarks/benchmark_dynamic_zone_cycle [steps] [runs=N]
//     [tet4=n] [hex=n] [tet10=n] [nmd=n] [element ...]
// Defaults: 20 steps, 5 runs, tet4 and nmd n = 40 (5 n^3 = 320,000 zones),
// hex-mixed n = 32 (10 n^3 = 327,680 tetrahedra), tet10 n = 20 (40,000
// zones). Name elements (tet4, hex, tet10, nmd) to run only those.

#include "benchmark_arguments.h"

#include <talus/base/parallel_environment.h>
#include <talus/solver/deformable_solver.h>
#include <talus/zone/block_mesher.h>
#include <talus/zone/mesh_order.h>
#include <talus/zone/tet10_mesh.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <memory>
#include <string>

using namespace talus;

namespace
{
/// Processor time of this thread (s): less disturbed than the wall clock
/// when other jobs share the cores.
double thread_seconds()
{
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

std::string cpu_model()
{
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0)
    {
      const std::size_t colon = line.find(':');
      return colon == std::string::npos ? line : line.substr(colon + 2);
    }
  return "unknown";
}
} // namespace

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  unsigned long steps = 20;
  unsigned int runs = 5;
  const char* element_name[4] = {"tet4", "hex", "tet10", "nmd"};
  unsigned int size[4] = {40, 32, 20, 40};
  bool run_element[4] = {true, true, true, true};
  bool named = false;
  for (int i = 1; i < argc; ++i)
  {
    const char* eq = std::strchr(argv[i], '=');
    if (i == 1 && argv[i][0] >= '0' && argv[i][0] <= '9')
      steps = whole_argument(argv[0], argv[i], "the step count (first argument)", 1, 100000);
    else if (std::strncmp(argv[i], "runs=", 5) == 0)
      runs = static_cast<unsigned int>(
          whole_argument(argv[0], argv[i] + 5, "runs=N (timed runs per mode)", 1, 100));
    else
    {
      int found = -1;
      for (int e = 0; e < 4; ++e)
        if (eq != nullptr ? std::strncmp(argv[i], element_name[e], eq - argv[i]) == 0 &&
                                std::strlen(element_name[e]) == std::size_t(eq - argv[i])
                          : std::strcmp(argv[i], element_name[e]) == 0)
          found = e;
      if (found < 0)
      {
        std::fprintf(stderr,
                     "%s: argument '%s' is not allowed; allowed: a step count (first), runs=N, "
                     "tet4=n, hex=n, tet10=n, nmd=n, or an element name (tet4, hex, tet10, "
                     "nmd)\n",
                     argv[0], argv[i]);
        return 2;
      }
      if (eq != nullptr)
        size[found] = static_cast<unsigned int>(
            whole_argument(argv[0], eq + 1, "the mesh size n of an element", 1, 200));
      else
      {
        if (!named)
          std::fill(run_element, run_element + 4, false);
        named = true;
        run_element[found] = true;
      }
    }
  }

  const double side = 10.0, density = 2650.0, g = 9.81;
  SolverSettings plain;
  plain.dynamic = true;
  plain.gravity = Vec3(0, 0, -g);
  const double xi = 0.05, omega = 2.0 * M_PI * 10.0;
  GridpointCondition base; // rollers
  base.region = Box{Vec3(-1, -1, -1e-9), Vec3(side + 1, side + 1, 1e-9)};
  base.held[0] = base.held[1] = false;
  FacePressure quiet; // every boundary face
  quiet.region = Box{Vec3::Constant(-1), Vec3::Constant(side + 1)};
  quiet.quiet = true;

  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  std::printf("CPU: %s; %s; %lu steps per run, %u runs per mode (the fastest counts)\n",
              cpu_model().c_str(), date, steps, runs);
  std::printf("%-6s %4s %8s %8s %-9s %10s %10s %8s %10s %8s %10s\n", "zone", "n", "zones",
              "gridpts", "damping", "ns/zone", "ns/gp", "vs none", "cpu ns/z", "cpu vs", "dt (s)");
  const char* mode_name[4] = {"none", "rayleigh", "quiet", "both"};
  for (int e = 0; e < 4; ++e)
  {
    if (!run_element[e])
      continue;
    const unsigned int n = size[e];
    BlockModel blocks;
    blocks.add_block(ConvexPolyhedron::box(Vec3::Zero(), Vec3::Constant(side)), 0);
    MeshReport report;
    ZoneMaterial material;
    material.density = density;
    material.set_young_poisson(1e10, 0.25);
    TetMesh mesh;
    if (e == 1)
    {
      material.element = ZoneElement::hex_mixed;
      mesh = mesh_blocks(blocks, {0}, side / n, report, ZoneElement::hex_mixed);
    }
    else
    {
      mesh = mesh_blocks(blocks, {0}, side / n, report);
      if (e == 2)
      {
        material.element = ZoneElement::tet10;
        make_quadratic(mesh);
      }
      if (e == 3)
      {
        material.nodal_mixed = true;
        order_for_locality(mesh, MeshOrder::columns, 32);
      }
    }
    const unsigned int nz = mesh.n_zones(), ng = mesh.n_gridpoints();
    std::unique_ptr<DeformableSolver> solver[4];
    for (int m = 0; m < 4; ++m)
    {
      SolverSettings s = plain;
      if (m == 1 || m == 3)
      {
        s.rayleigh_alpha = xi * omega;
        s.rayleigh_beta = xi / omega;
      }
      std::vector<FacePressure> pressures;
      if (m >= 2)
        pressures.push_back(quiet);
      solver[m] = std::make_unique<DeformableSolver>(
          mesh, std::vector<ZoneMaterial>{material}, std::vector<unsigned int>(nz, 0), s,
          std::vector<GridpointCondition>{base}, pressures);
      solver[m]->step(); // the first step has no strain (no motion yet)
    }
    double best[4] = {1e300, 1e300, 1e300, 1e300}, best_cpu[4] = {1e300, 1e300, 1e300, 1e300};
    for (unsigned int r = 0; r < runs; ++r)
      for (int m = 0; m < 4; ++m)
      {
        const auto start = std::chrono::steady_clock::now();
        const double cpu_start = thread_seconds();
        for (unsigned long k = 0; k < steps; ++k)
          solver[m]->step();
        best_cpu[m] = std::min(best_cpu[m], thread_seconds() - cpu_start);
        best[m] = std::min(
            best[m],
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      }
    for (int m = 0; m < 4; ++m)
    {
      std::printf("%-6s %4u %8u %8u %-9s %10.2f %10.2f %8.3f %10.2f %8.3f %10.3g\n",
                  element_name[e], n, nz, ng, mode_name[m], 1e9 * best[m] / (double(nz) * steps),
                  1e9 * best[m] / (double(ng) * steps), best[m] / best[0],
                  1e9 * best_cpu[m] / (double(nz) * steps), best_cpu[m] / best_cpu[0],
                  solver[m]->dt());
      if (m >= 2 && solver[m]->quiet_faces() == 0)
        std::printf("  (no quiet faces: the benchmark is wrong)\n");
      // The state reached, to compare builds (a faster kernel must give the
      // same numbers): sums of the magnitudes of the displacements, velocities and stresses.
      double sums[3] = {0.0, 0.0, 0.0};
      for (double u : solver[m]->displacements())
        sums[0] += std::abs(u);
      for (double v : solver[m]->velocities())
        sums[1] += std::abs(v);
      for (double sigma : solver[m]->stress())
        sums[2] += std::abs(sigma);
      std::fprintf(stderr, "%s %s: sums of |u|, |v|, |stress| after %lu steps: %.17g %.17g %.17g\n",
                   element_name[e], mode_name[m], solver[m]->steps_done(), sums[0], sums[1],
                   sums[2]);
    }
    std::fflush(stdout);
  }
  std::printf("ns/zone, ns/gp: wall time per zone-step and per gridpoint-step of the fastest "
              "run; vs none: its time over the undamped step's; cpu ns/z, cpu vs: the same in "
              "processor time, of the run with the least\n");
}
