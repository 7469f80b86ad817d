// Cost of a 10-node zone-update against a 4-node one: the elastic 10 m cube
// of zone_cycle.cc (static, density scaling, gravity, base held, starting
// from the gravitational stress), meshed into 5 n^3 tetrahedra, run with
// 4-node zones and then, on the same zones made quadratic (make_quadratic),
// with 10-node zones; then both again as Mohr-Coulomb (the material of
// zone_cycle.cc, about half the zones yield).
//
// Per size, model and element it prints zones, gridpoints, zone-updates per
// second of the whole cycle and of the zone stage alone, and for tet10 the
// time per zone-update over that of tet4 in the same run (whole cycle and
// zone stage). Each run is repeated until about 2e7 zone-updates (tet4) or
// 5e6 (tet10) have been timed; the fastest run counts (the other core may
// be busy).
//
// One core; run from a Release build:
//   cmake --build build --target benchmark_tet10_cycle
//   build/contrib/benchmarks/benchmark_tet10_cycle [steps] [n ...]
// Defaults: 30 steps, n = 10 20 30.

#include "benchmark_arguments.h"
#include "gravity_cube.h"

#include <talus/base/parallel_environment.h>
#include <talus/solver/deformable_solver.h>
#include <talus/zone/block_mesher.h>
#include <talus/zone/tet10_mesh.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

using namespace talus;

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  const unsigned long steps =
      argc > 1 ? whole_argument(argv[0], argv[1], "the step count (first argument)", 1, 1000000)
               : 30;
  std::vector<unsigned int> sizes;
  for (int i = 2; i < argc; ++i)
    sizes.push_back(static_cast<unsigned int>(
        whole_argument(argv[0], argv[i], "a mesh size n (5 n^3 zones)", 1, 100)));
  if (sizes.empty())
    sizes = {10, 20, 30};

  const GravityCube cube;
  const double side = cube.side;
  const ZoneMaterial& elastic = cube.elastic;
  const ZoneMaterial& plastic = cube.plastic;
  const SolverSettings& settings = cube.settings;
  const GridpointCondition& base = cube.base;
  const InitialStress& initial = cube.initial;

  std::printf("%-6s %4s %-6s %8s %8s %5s %10s %12s %9s %9s %7s\n", "model", "n", "zone", "zones",
              "gridpts", "runs", "Mzone-u/s", "Mzone-u/s zs", "t/zu rel", "zs rel", "yield%");
  for (unsigned int n : sizes)
  {
    BlockModel blocks;
    blocks.add_block(ConvexPolyhedron::box(Vec3::Zero(), Vec3::Constant(side)), 0);
    MeshReport report;
    const TetMesh linear = mesh_blocks(blocks, {0}, side / n, report);
    TetMesh quadratic = linear;
    make_quadratic(quadratic);
    const unsigned int nz = linear.n_zones();
    for (int mode = 0; mode < 2; ++mode)
    {
      const bool mc = mode == 1;
      double cost4[2] = {0.0, 0.0};
      for (int order = 0; order < 2; ++order)
      {
        const TetMesh& mesh = order == 0 ? linear : quadratic;
        ZoneMaterial material = mc ? plastic : elastic;
        material.element = order == 0 ? ZoneElement::tet4 : ZoneElement::tet10;
        const double budget = order == 0 ? 2e7 : 5e6;
        const unsigned int repeats =
            std::max(1u, static_cast<unsigned int>(budget / (double(nz) * steps)));
        double best = 1e300, best_zones = 1e300, yielding = 0.0;
        for (unsigned int r = 0; r < repeats; ++r)
        {
          DeformableSolver solver(mesh, {material}, std::vector<unsigned int>(nz, 0), settings,
                                  {base}, {}, &initial);
          const auto start = std::chrono::steady_clock::now();
          for (unsigned long k = 0; k < steps; ++k)
            solver.step();
          best = std::min(
              best,
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
          best_zones = std::min(best_zones, solver.seconds_zones());
          unsigned int now = 0;
          for (unsigned char s : solver.plastic_state())
            now += (s & (shear_now | tension_now)) != 0;
          yielding = 100.0 * now / solver.plastic_state().size();
        }
        const double updates = double(nz) * steps;
        std::printf("%-6s %4u %-6s %8u %8u %5u %10.3f %12.3f", mc ? "MC" : "elast", n,
                    order == 0 ? "tet4" : "tet10", nz, mesh.n_gridpoints(), repeats,
                    1e-6 * updates / best, 1e-6 * updates / best_zones);
        if (order == 0)
        {
          cost4[0] = best;
          cost4[1] = best_zones;
          std::printf(" %9s %9s", "1", "1");
        }
        else
          std::printf(" %9.2f %9.2f", best / cost4[0], best_zones / cost4[1]);
        if (mc)
          std::printf(" %7.1f", yielding);
        std::printf("\n");
        std::fflush(stdout);
      }
    }
  }
  std::printf("steps per run: %lu; t/zu rel: time per zone-update over tet4's (whole cycle), zs "
              "rel: the same for the zone stage alone; yield%%: share of stress points at a "
              "yield surface in the last step\n",
              steps);
}
