// Deformable-block cycle throughput: an elastic 10 m cube meshed by
// mesh_blocks into 5 n^3 constant-strain tetrahedra, static mode (local
// damping, density scaling) under gravity with the base held, starting from
// the gravitational stress sigma_zz = -rho g (H - z). The same cube is run
// again as Mohr-Coulomb (c = 40 kPa, phi = 30, psi = 0, sigma_t = 10 kPa:
// the uniaxial strength 2 c sqrt(N_phi) = 139 kPa is reached about halfway
// down, so roughly the lower half of the zones yields).
//
// Per size and model it prints: zones, gridpoints, runs; zone-updates per
// second of the whole cycle; gridpoint-updates per second of the gridpoint
// stage alone; the share of time per stage (zones / gridpoints); the bytes
// per zone of hot data the cycle touches and how much of that is gridpoint
// data; the whole-process memory per zone (VmRSS after setup minus VmRSS
// before meshing, freed heap returned by malloc_trim first); the time per
// zone-update relative to the first size (a linear cost keeps it near 1);
// the zone-updates per second of processor time of the run with the least
// (close to the wall-clock rate on an idle machine, less disturbed when the
// cores are shared);
// for Mohr-Coulomb the share of zones at a yield surface in the last step
// and the share that has ever yielded.
//
// Hot data counted (what zone_forces and move_gridpoints read or write):
//   per zone: the zone table (4 unsigned), stress (6 doubles), plastic
//     state (1 byte, Mohr-Coulomb only);
//   per gridpoint: the PETSc position, velocity, force and inertial mass
//     (4 x 3 doubles), gravity force, force_size, held velocity (3 doubles
//     each) and the held flags (1 byte).
// Not counted: the kernel scratch (one batch of 1024 zones, 152 KB, stays in
// cache), the initial positions of the mesh and the material index per zone
// (not read by the cycle).
//
// Every run takes the same number of steps from the same start (so each size
// sees the same physics); each size and mode runs at least 3 times ("runs=N"
// to change that; one run was too noisy for the 1.3 limit of nodal mixed
// discretization, its ratio moving by up to 0.1 between runs) and small sizes
// repeat the run, from a new solver, until about 4e7 zone-updates have been
// timed. The modes take turns (each mode's first run, then each one's
// second, ...), so that a slow spell of the machine does not fall on one
// mode and skew a ratio. Only the steps are timed;
// the rates and the linearity are those of the fastest run (the other core
// may be busy), the stage shares and "seconds" are over all runs.
//
// One core; run from a Release build:
//   cmake --build build --target benchmark_zone_cycle
//   build/contrib/benchmarks/benchmark_zone_cycle [steps] [n ...] [modes]
//     [generator|hilbert] [columns=N] [ring=N] [runs=N]
// Defaults: 30 steps, n = 20 40 60 80 100, four modes: elastic, mc,
// nmd-elastic, nmd-mc (the last two with nodal mixed discretization; their
// rows end with the cost per zone-update over the plain run of the same
// size and model). Name modes to run only those (one, to profile it).
// Nodal mixed discretization runs on the same cube with its zones in
// columns of 32 cells across (MeshOrder::columns, as talus meshes blocks
// for it); "columns=N" sets the width, "columns=0" runs it on the plain
// zones' mesh. "ring=N" sets DeformableSolver::set_nodal_mixed_ring_limit
// (0: nodal mixed discretization takes the strain increments twice;
// default: the solver's own choice); NMD rows end with the batches of
// scratch kept between its two stages and the share of batches whose
// strain increments were kept.
// "generator" or "hilbert" puts zones and gridpoints in that order instead
// of the mesher's default (slabs, mesh_order.h), to measure what the order
// costs. peakB/z (VmHWM over the run so far) is the meshing peak only while
// the sizes increase.

#include "benchmark_arguments.h"
#include "gravity_cube.h"

#include <talus/base/parallel_environment.h>
#include <talus/solver/deformable_solver.h>
#include <talus/zone/block_mesher.h>
#include <talus/zone/mesh_order.h>

#include <malloc.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <string>

using namespace talus;

namespace
{
/// Resident set size of this process (bytes), after handing freed heap
/// back to the system so that the meshing's temporaries do not count.
double resident_bytes(const char* field = "VmRSS:")
{
  malloc_trim(0);
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind(field, 0) == 0)
      return 1024.0 * std::strtod(line.c_str() + std::strlen(field), nullptr);
  return 0.0;
}

} // namespace

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  const unsigned long steps =
      argc > 1 ? whole_argument(argv[0], argv[1], "the step count (first argument)", 1, 1000000)
               : 30;
  const double budget = 4e7; // zone-updates timed per size and model
  std::vector<unsigned int> sizes;
  // Modes: elastic, Mohr-Coulomb, and both with nodal mixed discretization.
  const char* mode_name[4] = {"elastic", "mc", "nmd-elastic", "nmd-mc"};
  bool run_model[4] = {true, true, true, true};
  bool mode_named = false;
  MeshOrder order = MeshOrder::slabs;
  int ring_limit = -1; // nodal mixed discretization: the solver's own choice
  unsigned int least_runs = 3;
  // Nodal mixed discretization's mesh: in columns of this many cells across
  // (as talus orders it), or (0) the same mesh as the plain zones'.
  unsigned int column_cells = 32;
  for (int i = 2; i < argc; ++i)
    if (std::strcmp(argv[i], "generator") == 0)
      order = MeshOrder::generator;
    else if (std::strncmp(argv[i], "ring=", 5) == 0)
      ring_limit = static_cast<int>(
          whole_argument(argv[0], argv[i] + 5, "ring=N (batches of scratch)", 0, 100000));
    else if (std::strncmp(argv[i], "runs=", 5) == 0)
      least_runs = static_cast<unsigned int>(whole_argument(
          argv[0], argv[i] + 5, "runs=N (runs at least, per size and mode)", 1, 100));
    else if (std::strncmp(argv[i], "columns=", 8) == 0)
      column_cells = static_cast<unsigned int>(whole_argument(
          argv[0], argv[i] + 8, "columns=N (cells across a column, 0: no columns)", 0, 1000));
    else if (std::strcmp(argv[i], "hilbert") == 0)
      order = MeshOrder::hilbert;
    else if (std::isalpha(static_cast<unsigned char>(argv[i][0])))
    {
      // The modes named, and only those.
      if (!mode_named)
        std::fill(run_model, run_model + 4, false);
      mode_named = true;
      bool known = false;
      for (int m = 0; m < 4; ++m)
        if (std::strcmp(argv[i], mode_name[m]) == 0)
          run_model[m] = known = true;
      if (!known)
      {
        std::fprintf(stderr,
                     "%s: argument '%s' is not a mode, an order, columns=N, ring=N or runs=N; "
                     "allowed: elastic, mc, nmd-elastic, nmd-mc, generator, hilbert, columns=N, "
                     "ring=N, runs=N, or a mesh "
                     "size\n",
                     argv[0], argv[i]);
        return 2;
      }
    }
    else
      sizes.push_back(static_cast<unsigned int>(
          whole_argument(argv[0], argv[i], "a mesh size n (5 n^3 zones)", 1, 200)));
  if (sizes.empty())
    sizes = {20, 40, 60, 80, 100};

  const GravityCube cube;
  const double side = cube.side;
  const ZoneMaterial& elastic = cube.elastic;
  const ZoneMaterial& plastic = cube.plastic;
  const SolverSettings& settings = cube.settings;
  const GridpointCondition& base = cube.base;
  const InitialStress& initial = cube.initial;

  std::printf("%-6s %4s %8s %8s %5s %8s %10s %10s %9s %8s %7s %8s %8s %8s %8s %7s %7s\n", "model",
              "n", "zones", "gridpts", "runs", "seconds", "Mzone-u/s", "Mgp-u/s", "zone/gp%",
              "hotB/z", "gp%", "rssB/z", "peakB/z", "t/zu rel", "cpuMz/s", "yield%", "ever%");
  double first_cost[4] = {0.0, 0.0, 0.0, 0.0};
  for (unsigned int n : sizes)
  {
    const double baseline = resident_bytes();
    BlockModel blocks;
    blocks.add_block(ConvexPolyhedron::box(Vec3::Zero(), Vec3::Constant(side)), 0);
    MeshReport report;
    const TetMesh mesh = mesh_blocks(blocks, {0}, side / n, report, ZoneElement::tet4, order);
    // Nodal mixed discretization's zones in columns (as talus meshes them
    // for it), the plain zones in `order`; both meshes stay in memory, so
    // the column mesh's own bytes are taken off every mode's rssB/z.
    TetMesh column_mesh;
    double column_mesh_bytes = 0.0;
    if (column_cells > 0 && (run_model[2] || run_model[3]))
    {
      const double before = resident_bytes();
      column_mesh = mesh;
      order_for_locality(column_mesh, MeshOrder::columns, column_cells);
      column_mesh_bytes = resident_bytes() - before;
    }
    const unsigned int nz = mesh.n_zones(), ng = mesh.n_gridpoints();
    const unsigned int repeats =
        std::max(least_runs, static_cast<unsigned int>(budget / (nz * steps)));
    const std::vector<unsigned int> material_of_zone(nz, 0);

    // The runs of the modes alternate (all modes once, then again), so that
    // a slow spell of the machine falls on every mode alike.
    struct Result
    {
      double best = 1e300, best_cpu = 1e300, best_gridpoints = 1e300, seconds = 0.0,
             seconds_zones = 0.0, seconds_gridpoints = 0.0, rss = 0.0, peak = 0.0, ratio = 0.0;
      std::vector<unsigned char> state;
      double kept_share = 0.0;
      unsigned int ring = 0;
    };
    Result results[4];
    for (unsigned int r = 0; r < repeats; ++r)
      for (int mode = 0; mode < 4; ++mode)
      {
        if (!run_model[mode])
          continue;
        ZoneMaterial material = mode % 2 == 1 ? plastic : elastic;
        material.nodal_mixed = mode >= 2;
        Result& result = results[mode];
        DeformableSolver solver(mode >= 2 && column_cells > 0 ? column_mesh : mesh, {material},
                                material_of_zone, settings, {base}, {}, &initial);
        if (ring_limit >= 0)
          solver.set_nodal_mixed_ring_limit(static_cast<unsigned int>(ring_limit));
        result.kept_share = solver.nodal_mixed_kept_share();
        result.ring = solver.nodal_mixed_ring_batches();
        if (r == 0)
        {
          result.rss = resident_bytes() - baseline - column_mesh_bytes;
          result.peak = resident_bytes("VmHWM:") - baseline;
        }
        const auto start = std::chrono::steady_clock::now();
        const std::clock_t cpu_start = std::clock();
        for (unsigned long k = 0; k < steps; ++k)
          solver.step();
        const double run_seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        result.best = std::min(result.best, run_seconds);
        result.best_cpu =
            std::min(result.best_cpu, double(std::clock() - cpu_start) / CLOCKS_PER_SEC);
        result.seconds += run_seconds;
        result.seconds_zones += solver.seconds_zones();
        result.seconds_gridpoints += solver.seconds_gridpoints();
        result.best_gridpoints = std::min(result.best_gridpoints, solver.seconds_gridpoints());
        result.ratio = solver.unbalanced_ratio();
        result.state = solver.plastic_state();
      }

    double plain_cost[2] = {0.0, 0.0}; // this size, without nodal mixed discretization
    for (int mode = 0; mode < 4; ++mode)
    {
      if (!run_model[mode])
        continue;
      const bool mc = mode % 2 == 1, nmd = mode >= 2;
      const Result& r = results[mode];
      const double updates = double(nz) * steps; // per run
      // Nodal mixed discretization keeps nothing per zone beyond a batch;
      // it adds per gridpoint the zone volumes around it and the average
      // volumetric strain increment, and with Mohr-Coulomb the average
      // plastic pressure.
      const double zone_bytes = sizeof(mesh.zone_gridpoint[0]) + 6 * sizeof(double) + (mc ? 1 : 0);
      const double gridpoint_bytes =
          (4 * 3 + 3 * 3 + (nmd ? (mc ? 3 : 2) : 0)) * sizeof(double) + 1;
      const double hot = zone_bytes + gridpoint_bytes * ng / nz;
      unsigned int yielding = 0, yielded = 0;
      for (unsigned char s : r.state)
      {
        yielding += (s & (shear_now | tension_now)) != 0;
        yielded += (s & (shear_past | tension_past)) != 0;
      }
      const double cost = r.best / updates;
      if (first_cost[mode] == 0.0)
        first_cost[mode] = cost;
      const double stages = r.seconds_zones + r.seconds_gridpoints;
      if (!nmd)
        plain_cost[mc] = cost;
      std::printf("%-6s %4u %8u %8u %5u %8.2f %10.2f %10.2f %4.0f/%-4.0f %8.1f %7.1f %8.0f %8.0f "
                  "%8.2f %8.2f",
                  nmd ? (mc ? "NMD-MC" : "NMD-el") : (mc ? "MC" : "elast"), n, nz, ng, repeats,
                  r.seconds, 1e-6 * updates / r.best, 1e-6 * ng * steps / r.best_gridpoints,
                  100 * r.seconds_zones / stages, 100 * r.seconds_gridpoints / stages, hot,
                  100 * gridpoint_bytes * ng / nz / hot, r.rss / nz, r.peak / nz,
                  cost / first_cost[mode], 1e-6 * updates / r.best_cpu);
      if (mc)
        std::printf(" %7.1f %7.1f", 100.0 * yielding / nz, 100.0 * yielded / nz);
      else
        std::printf(" %7s %7s", "", "");
      if (nmd && plain_cost[mc] > 0.0)
        std::printf("  cost vs plain %.2f", cost / plain_cost[mc]);
      if (nmd)
        std::printf(" (ring of %u batches, strains of %.0f %% of the batches kept)", r.ring,
                    100.0 * r.kept_share);
      std::printf("\n");
      std::fflush(stdout);
      if (!std::isfinite(r.ratio))
        std::printf("  (unbalanced ratio not finite: the run went wrong)\n");
    }
  }
  std::printf("steps per run: %lu; mesh order: %s", steps,
              order == MeshOrder::generator ? "generator"
              : order == MeshOrder::hilbert ? "hilbert"
                                            : "slabs");
  if (column_cells > 0)
    std::printf(", nodal mixed discretization in columns of %u cells", column_cells);
  std::printf("\n");
}
