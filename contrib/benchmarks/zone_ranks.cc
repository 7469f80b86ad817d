// Strong scaling of the zone cycle split among ranks (issue 24): the
// elastic 10 m cube of zone_cycle.cc (5 n^3 constant-strain tetrahedra,
// static with local damping and density scaling, under gravity from the
// gravitational stress, base held), first whole on rank 0 alone while the
// other ranks wait, then split among all ranks.
//
// The split: each gridpoint belongs to the rank whose region of a
// CellPartition (balanced by the zones around the gridpoints) holds it;
// each rank holds every zone with a gridpoint of its own, in the mesh's
// zone order, and the other gridpoints of those zones as ghosts
// (GridpointShare). It moves its own gridpoints; PETSc's ghost update
// brings the ghosts' positions and velocities after every step. The zones
// of a cut are computed on both sides: that is what keeps every owned
// gridpoint's force sum in the one run's order, so the split run must equal
// the whole run bit for bit, which the benchmark checks (every gridpoint's
// position, gathered on rank 0).
//
// It runs in rounds, as benchmark_rigid_ranks does: whole on rank 0 alone
// (the others sleeping between polls), split, then whole on every rank at
// once, sharing nothing, for the machine's ceiling for this work at that
// moment (P times the time alone over the slowest at once). Every later
// run must end as the first of its kind, bit for bit.
//
// Prints each round's rates, speed-up and ceiling, the best whole time
// over the best split time and the medians, the zones held over the
// model's, the exchange per step, the memory per zone held, this machine's
// MPI, and a model of 100 million zones on 64 and 1,000 ranks from those
// figures.
//   cmake --build build --target benchmark_zone_ranks
//   mpirun -np 2 build/contrib/benchmarks/benchmark_zone_ranks [n] [steps] [rounds]
// Defaults: n = 59 (1,026,895 zones), 100 steps, 3 rounds.

#include "benchmark_arguments.h"
#include "gravity_cube.h"
#include "rank_figures.h"

#include <talus/base/memory.h>
#include <talus/base/parallel_environment.h>
#include <talus/solver/deformable_solver.h>
#include <talus/solver/mesh_share.h>
#include <talus/zone/block_mesher.h>
#include <talus/zone/gridpoint_share.h>

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <memory>
#include <vector>

using namespace talus;
using rank_figures::seconds_since;

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  const MPI_Comm comm = MPI_COMM_WORLD;
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  const unsigned int n =
      argc > 1 ? whole_argument(argv[0], argv[1], "the cells per side (first argument)", 2, 200)
               : 59;
  const unsigned long steps =
      argc > 2 ? whole_argument(argv[0], argv[2], "the step count (second argument)", 1, 100000)
               : 100;
  const unsigned long rounds =
      argc > 3 ? whole_argument(argv[0], argv[3], "the rounds (third argument)", 1, 20) : 3;

  const GravityCube cube;
  const double side = cube.side;
  const ZoneMaterial& elastic = cube.elastic;
  const SolverSettings& settings = cube.settings;
  const GridpointCondition& base = cube.base;
  const InitialStress& initial = cube.initial;

  // Every rank meshes the cube (the mesher is deterministic).
  BlockModel blocks;
  blocks.add_block(ConvexPolyhedron::box(Vec3::Zero(), Vec3::Constant(side)), 0);
  MeshReport report;
  const double resident_before_mesh = rank_figures::resident_bytes();
  const TetMesh mesh = mesh_blocks(blocks, {0}, side / n, report, ZoneElement::tet4);
  const double mesh_bytes_per_zone =
      (rank_figures::resident_bytes() - resident_before_mesh) / double(mesh.n_zones());
  const unsigned int nz = mesh.n_zones(), ng = mesh.n_gridpoints();

  // 1. Whole, on rank 0 alone; the first run's positions are kept for the
  // comparisons, every later one must end there too.
  std::vector<double> whole_x;
  unsigned long later_differ = 0; // later runs that did not end as the first of their kind
  const auto whole_alone = [&]()
  {
    double seconds = 0.0;
    if (rank == 0)
    {
      DeformableSolver solver(mesh, {elastic}, std::vector<unsigned int>(nz, 0), settings, {base},
                              {}, &initial);
      const auto start = std::chrono::steady_clock::now();
      for (unsigned long k = 0; k < steps; ++k)
        solver.step();
      seconds = seconds_since(start);
      if (whole_x.empty())
        whole_x = solver.positions();
      else
        later_differ += solver.positions() != whole_x ? 1 : 0;
    }
    rank_figures::wait_for_all(comm);
    return seconds;
  };
  std::vector<double> whole_times{whole_alone()};

  // 2. Split among the ranks: owners from a partition of the gridpoints
  // weighed by their zones, on cells of a tenth of the side.
  const std::vector<unsigned int> owner = gridpoint_owners(
      mesh, Box{Vec3::Zero(), Vec3::Constant(side)}, side / n, static_cast<unsigned int>(ranks));
  const double memory_before = rank_figures::resident_bytes();
  const MeshShare mine = share_mesh(mesh, owner, static_cast<unsigned int>(rank),
                                    static_cast<unsigned int>(ranks), comm);
  const unsigned int held_zones = mine.mesh.n_zones();
  DeformableSolver solver(mine.mesh, {elastic}, std::vector<unsigned int>(held_zones, 0), settings,
                          {base}, {}, &initial, &mine.share);
  MPI_Barrier(comm);
  const auto start = std::chrono::steady_clock::now();
  for (unsigned long k = 0; k < steps; ++k)
    solver.step();
  const double mine_seconds = seconds_since(start);
  const double memory_per_zone =
      rank == 1 ? (rank_figures::resident_bytes() - memory_before) / double(held_zones) : 0.0;

  // The machine's ceiling for this work now: the whole model on every rank
  // at once. Rank 0's run must end as its first whole run.
  const auto whole_at_once = [&]()
  {
    DeformableSolver copy(mesh, {elastic}, std::vector<unsigned int>(nz, 0), settings, {base}, {},
                          &initial);
    const double slowest = rank_figures::slowest_steps(copy, steps, comm);
    if (rank == 0)
      later_differ += copy.positions() != whole_x ? 1 : 0;
    return slowest;
  };
  // A later split run, from the start on the same share: it must end as
  // the first split run, bit for bit.
  const std::vector<double> first_split_x = solver.positions();
  const auto split_again = [&]()
  {
    DeformableSolver again(mine.mesh, {elastic}, std::vector<unsigned int>(held_zones, 0), settings,
                           {base}, {}, &initial, &mine.share);
    const double slowest = rank_figures::slowest_steps(again, steps, comm);
    unsigned long differing = again.positions() != first_split_x ? 1 : 0;
    MPI_Allreduce(MPI_IN_PLACE, &differing, 1, MPI_UNSIGNED_LONG, MPI_SUM, comm);
    later_differ += rank == 0 ? differing : 0;
    return slowest;
  };

  // The split run must be the whole run: own gridpoints' positions on rank 0.
  const std::vector<double> x = solver.positions();
  std::vector<double> state;
  for (unsigned int i = 0; i < mine.share.n_owned; ++i)
  {
    state.push_back(mine.gridpoint[i]);
    state.insert(state.end(), &x[3 * i], &x[3 * i] + 3);
  }
  const std::vector<double> all_state = rank_figures::gather_on_rank_0(state, comm);

  double first_split_seconds = 0.0, memory = 0.0;
  MPI_Allreduce(&mine_seconds, &first_split_seconds, 1, MPI_DOUBLE, MPI_MAX, comm);
  std::vector<double> split_times{first_split_seconds}, at_once_times{whole_at_once()};
  for (unsigned long r = 1; r < rounds; ++r)
  {
    whole_times.push_back(whole_alone());
    split_times.push_back(split_again());
    at_once_times.push_back(whole_at_once());
  }
  const double best_whole = *std::min_element(whole_times.begin(), whole_times.end());
  const double split_seconds = *std::min_element(split_times.begin(), split_times.end());
  MPI_Allreduce(&memory_per_zone, &memory, 1, MPI_DOUBLE, MPI_MAX, comm);
  long held[2] = {long(held_zones), long(mine.mesh.n_gridpoints() - mine.share.n_owned)},
       held_all[2] = {0, 0};
  MPI_Reduce(held, held_all, 2, MPI_LONG, MPI_SUM, 0, comm);
  const rank_figures::MpiFigures mpi = rank_figures::measure_mpi(comm);
  if (rank != 0)
    return 0;

  unsigned long differ = 0, compared = 0;
  for (std::size_t k = 0; k < all_state.size(); k += 4, ++compared)
    differ += std::memcmp(&whole_x[3 * std::size_t(all_state[k])], &all_state[k + 1],
                          3 * sizeof(double)) != 0;
  std::printf("%s, %s; %d ranks\n", rank_figures::cpu_model().c_str(),
              rank_figures::date_utc().c_str(), ranks);
  std::printf("n = %u: %u zones, %u gridpoints, %lu steps\n", n, nz, ng, steps);
  std::printf("split run against the whole run: %lu of %lu gridpoints (%s) differ in position, "
              "bit for bit\n",
              differ, compared, compared == ng ? "all" : "NOT ALL");
  const double zone_steps = double(nz) * steps;
  std::vector<double> speed_ups, ceilings, shares;
  for (std::size_t r = 0; r < rounds; ++r)
  {
    speed_ups.push_back(whole_times[r] / split_times[r]);
    ceilings.push_back(ranks * whole_times[r] / at_once_times[r]);
    shares.push_back(speed_ups.back() / ceilings.back());
    std::printf("round %zu: whole on one rank %.3f s (%.3g zone-cycles/s), split on %d ranks "
                "%.3f s (%.3g); speed-up %.2f; the whole model on every rank at once %.3f s: "
                "ceiling %.2f\n",
                r + 1, whole_times[r], zone_steps / whole_times[r], ranks, split_times[r],
                zone_steps / split_times[r], speed_ups.back(), at_once_times[r], ceilings.back());
  }
  std::printf("speed-up: %.2f, the best whole run (%.3f s, %.3g zone-cycles/s) over the best "
              "split run (%.3f s, %.3g); median of the %lu rounds %.2f\n",
              best_whole / split_seconds, best_whole, zone_steps / best_whole, split_seconds,
              zone_steps / split_seconds, rounds, rank_figures::median(speed_ups));
  std::printf("ceiling (median of the rounds): %.2f; the speed-up over the ceiling (median of "
              "the rounds): %.2f\n",
              rank_figures::median(ceilings), rank_figures::median(shares));
  std::printf("later runs (whole, split, at once) that did not end as the first of their kind, "
              "bit for bit: %lu\n",
              later_differ);
  const double ghost_gridpoints = double(held_all[1]);
  const double exchange_bytes = ghost_gridpoints * 6 * sizeof(double); // positions, velocities
  std::printf("zones held %.4f times the model's (the zones of the cuts on both sides); ghost "
              "gridpoints %.0f, exchange %.0f bytes per step in all\n",
              double(held_all[0]) / nz, ghost_gridpoints, exchange_bytes);
  if (ranks > 1)
    std::printf("MPI between ranks 0 and 1: latency %.2f us, bandwidth %.2f GB/s, one "
                "MPI_Allreduce %.2f us\n",
                1e6 * mpi.latency, 1e-9 * mpi.bandwidth, 1e6 * mpi.allreduce);
  if (ranks > 1)
    std::printf("memory per zone held (rank 1: the rise of its resident memory with its share "
                "and its solver, ghosts included): %.0f bytes\n",
                memory);
  std::printf("the whole mesh every rank builds at set-up (TetMesh): %.0f bytes per zone\n",
              mesh_bytes_per_zone);

  // The model: P ranks, each a cube of m = Z / P zones, L = (m / 5)^(1/3)
  // cells on a side. Zones held: 5 (L + 2 t)^3, with t the depth of the
  // zones a cut adds on each side, measured here (the extra zones per cut
  // over 5 n^2; one cut per pair of ranks when split in two); each held
  // zone costs as much as one in the whole run. Ghost gridpoints: (L + 2
  // t)^3 - L^3 in gridpoint layers, 48 bytes each per step, to 26
  // neighbours (latency each), with 2 reductions of log2 P latencies.
  if (ranks == 2)
  {
    const double t_zone = best_whole / (double(nz) * steps);
    const double depth = (double(held_all[0]) - nz) / (2.0 * 5.0 * n * n);
    const double ghost_depth = ghost_gridpoints / (2.0 * (n + 1.0) * (n + 1.0));
    std::printf("model inputs: %.3g s per zone-step (whole run); a cut adds %.2f cells of zones "
                "and %.2f layers of ghost gridpoints on each side\n",
                t_zone, depth, ghost_depth);
    for (const double p : {64.0, 1000.0})
    {
      const double total = 1e8, m = total / p, cells = std::cbrt(m / 5.0);
      const double held_zones_rank = 5.0 * std::pow(cells + 2.0 * depth, 3);
      const double compute = held_zones_rank * t_zone;
      const double ghosts = std::pow(cells + 1.0 + 2.0 * ghost_depth, 3) - std::pow(cells + 1.0, 3);
      const double talk =
          26.0 * mpi.latency + ghosts * 48.0 / mpi.bandwidth + 2.0 * std::log2(p) * mpi.latency;
      std::printf("predicted: %.0f zones on %.0f ranks: %.0f zones a rank, held %.3f times; %.3g "
                  "s computing and %.3g s exchanging a step; efficiency %.0f %%\n",
                  total, p, m, held_zones_rank / m, compute, talk,
                  100.0 * m * t_zone / (compute + talk));
    }
  }
  return 0;
}
