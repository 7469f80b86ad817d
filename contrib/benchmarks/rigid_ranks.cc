// Strong scaling of the rigid engine split among ranks (issue 24): the
// settling scene of rigid_settling.cc (n x n x n unit cubes on a fixed
// floor layer, static with local damping), first whole on rank 0 alone
// while the other ranks wait, then split among all ranks by a CellPartition
// with RankShare's layers of ghosts refreshed after every step (GhostExchange),
// each contact across ranks computed by one rank (SubContactExchange), and
// owners that follow the blocks (BlockMigration's check after every step);
// then split again with those contacts computed on both sides, for the
// ratio; then, for each further round, whole and split (computed once)
// again from the start. A shared host slows one run and not the next by
// up to a third, so the speed-up is given round by round, as their median
// and as the best whole run's time over the best split run's (the runs
// least disturbed). Prints the rates, the blocks each rank holds and the
// exchange volume per step.
//   cmake --build build --target benchmark_rigid_ranks
//   mpirun -np 2 build/contrib/benchmarks/benchmark_rigid_ranks [n] [steps] [rounds]

#include "benchmark_arguments.h"
#include "rank_figures.h"
#include "settling_cubes.h"

#include <talus/base/memory.h>
#include <talus/base/parallel_environment.h>
#include <talus/contact/block_decomposition.h>
#include <talus/geometry/block_generator.h>
#include <talus/model/block_model.h>
#include <talus/run/rank_share.h>
#include <talus/solver/block_migration.h>
#include <talus/solver/ghost_exchange.h>
#include <talus/solver/rigid_solver.h>
#include <talus/solver/subcontact_exchange.h>

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <string>
#include <vector>

using namespace talus;

using rank_figures::cpu_model;
using rank_figures::seconds_since;
using rank_figures::wait_for_all;

int main(int argc, char** argv)
{
  ParallelEnvironment mpi(argc, argv);
  const MPI_Comm comm = MPI_COMM_WORLD;
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  const unsigned int n =
      argc > 1 ? whole_argument(argv[0], argv[1], "the cubes per side (first argument)", 2, 100)
               : 30;
  const unsigned long steps =
      argc > 2 ? whole_argument(argv[0], argv[2], "the step count (second argument)", 1, 1000000)
               : 200;
  const unsigned long rounds =
      argc > 3 ? whole_argument(argv[0], argv[3], "the rounds (third argument)", 1, 20) : 3;

  SolverSettings s;
  // Every rank builds the whole block model (as talus's set-up does on
  // ranks): its bytes per block, the rise of the resident memory.
  const double resident_before_model = rank_figures::resident_bytes();
  BlockModel model = settling_cubes(n, steps, s);
  const double model_bytes_per_block =
      (rank_figures::resident_bytes() - resident_before_model) / double(model.n_blocks());

  // 1. Whole, on rank 0 alone. What the first whole run ends with is kept
  // for the comparisons (its model and solver are freed before the split);
  // every later whole run must end there too, bit for bit.
  struct EndState
  {
    std::vector<Vec3> centroid, velocity, spin;
    unsigned int subcontacts = 0;
    unsigned long planes = 0; ///< common planes computed in the steps
  } whole;
  // Blocks of a whole run that do not end as the first whole run.
  const auto differing_from_whole = [&](const BlockModel& m, const RigidSolver& solver)
  {
    unsigned long differing = 0;
    for (unsigned int b = 0; b < m.n_blocks(); ++b)
      differing += m.centroid[b] != whole.centroid[b] || solver.velocity[b] != whole.velocity[b] ||
                   solver.spin[b] != whole.spin[b];
    return differing;
  };
  unsigned long rounds_differ = 0; // blocks, over the further rounds, whole and split
  const auto whole_alone = [&]()
  {
    double seconds = 0.0;
    if (rank == 0)
    {
      BlockModel whole_model = model;
      RigidSolver whole_solver(whole_model, 2650.0, s);
      const unsigned long planes_before = whole_solver.contacts().planes_computed();
      const auto start = std::chrono::steady_clock::now();
      for (unsigned long k = 0; k < steps; ++k)
        whole_solver.step();
      seconds = seconds_since(start);
      if (whole.centroid.empty())
        whole = {whole_model.centroid, whole_solver.velocity, whole_solver.spin,
                 whole_solver.contacts().n_subcontacts(),
                 whole_solver.contacts().planes_computed() - planes_before};
      else
        rounds_differ += differing_from_whole(whole_model, whole_solver);
    }
    wait_for_all(comm);
    return seconds;
  };
  std::vector<double> whole_times{whole_alone()};

  // 2. Split among the ranks.
  Box domain{Vec3::Zero(), Vec3(n, n, n + 1)};
  const CellPartition partition(domain, domain.lo, Vec3::Ones(), model.centroid,
                                std::vector<double>(model.n_blocks(), 1.0),
                                static_cast<unsigned int>(ranks));
  const double reach = 4.0 * s.contact.tolerance;
  const double memory_before = peak_memory(); // bytes: with the whole model built
  const unsigned int layers = RankShare::ghost_layers;
  RankBlocks mine =
      decompose_blocks(model, partition, static_cast<unsigned int>(rank), reach, layers);
  BlockModel local = model.subset(mine.local);
  RigidSolver solver(local, 2650.0, s);
  std::vector<char> ghost(mine.local.size());
  for (std::size_t i = 0; i < ghost.size(); ++i)
    ghost[i] = !mine.owned[i];
  solver.split_among_ranks(ghost, reductions_over(comm));
  GhostExchange exchange(mine, comm);
  SubContactExchange shared(mine, comm);
  solver.share_subcontacts(&shared);
  BlockMigration migration(solver, mine, partition, reach, layers, comm);
  const unsigned long planes_before = solver.contacts().planes_computed();
  MPI_Barrier(comm);
  const auto start = std::chrono::steady_clock::now();
  double exchange_seconds = 0.0; // in GhostExchange::refresh, this rank
  for (unsigned long k = 0; k < steps; ++k)
  {
    solver.step();
    const auto refresh_start = std::chrono::steady_clock::now();
    exchange.refresh(solver);
    exchange_seconds += seconds_since(refresh_start);
    migration.update(solver, mine);
  }
  const double mine_seconds = seconds_since(start);
  const std::size_t subcontacts_sent = shared.sent(), subcontacts_taken = shared.received();
  unsigned long planes = solver.contacts().planes_computed() - planes_before, planes_all = 0;
  MPI_Reduce(&planes, &planes_all, 1, MPI_UNSIGNED_LONG, MPI_SUM, 0, comm);

  // The split run must be the whole run: every owned block's centroid,
  // velocity and spin, gathered on rank 0 and compared bit for bit (this
  // is what a run on oversubscribed ranks checks).
  std::vector<double> state;
  for (std::size_t i = 0; i < mine.local.size(); ++i)
    if (mine.owned[i])
    {
      state.push_back(mine.local[i]);
      for (const Vec3* v : {&local.centroid[i], &solver.velocity[i], &solver.spin[i]})
        state.insert(state.end(), v->data(), v->data() + 3);
    }
  const std::vector<double> all_state = rank_figures::gather_on_rank_0(state, comm);
  unsigned long differ = 0, compared = 0;
  if (rank == 0)
    for (std::size_t k = 0; k < all_state.size(); k += 10, ++compared)
    {
      const unsigned int b = static_cast<unsigned int>(all_state[k]);
      const double serial[9] = {whole.centroid[b].x(), whole.centroid[b].y(), whole.centroid[b].z(),
                                whole.velocity[b].x(), whole.velocity[b].y(), whole.velocity[b].z(),
                                whole.spin[b].x(),     whole.spin[b].y(),     whole.spin[b].z()};
      differ += std::memcmp(serial, &all_state[k + 1], sizeof serial) != 0;
    }
  // The rise of the peak resident memory of a rank that never ran the whole
  // model (rank 1) with its share (blocks, solver, contacts, exchange), per
  // block it holds (ghosts included).
  double memory_per_block =
      rank == 1 ? (peak_memory() - memory_before) / double(mine.local.size()) : 0.0;
  MPI_Allreduce(MPI_IN_PLACE, &memory_per_block, 1, MPI_DOUBLE, MPI_MAX, comm);

  // 3. The same split with the contacts across ranks computed on both
  // sides (no SubContactExchange), then once more computed once, so that
  // the order of the runs shows: the times, and the same answer.
  // The machine's ceiling for this work at this moment: every rank runs the
  // whole model at once, sharing nothing; P times the whole run's time
  // alone over the slowest of these is what P cores give at all (a
  // shared host gives less than P when both cores work). Rank 0's run
  // must end where its first whole run did, bit for bit.
  unsigned long at_once_differ = 0;
  const auto whole_at_once = [&]()
  {
    BlockModel copy = model;
    RigidSolver copy_solver(copy, 2650.0, s);
    const double slowest = rank_figures::slowest_steps(copy_solver, steps, comm);
    if (rank == 0)
      at_once_differ += differing_from_whole(copy, copy_solver);
    return slowest;
  };
  std::vector<double> at_once_times{whole_at_once()};

  const auto split_again =
      [&](bool once, double& seconds, unsigned long& differing, unsigned long& planes_again)
  {
    RankBlocks mine_again =
        decompose_blocks(model, partition, static_cast<unsigned int>(rank), reach, layers);
    BlockModel local_again = model.subset(mine_again.local);
    RigidSolver again(local_again, 2650.0, s);
    again.split_among_ranks(ghost, reductions_over(comm));
    GhostExchange exchange_again(mine_again, comm);
    SubContactExchange shared_again(mine_again, comm);
    if (once)
      again.share_subcontacts(&shared_again);
    BlockMigration migration_again(again, mine_again, partition, reach, layers, comm);
    const unsigned long planes_at_start = again.contacts().planes_computed();
    MPI_Barrier(comm);
    const auto again_start = std::chrono::steady_clock::now();
    for (unsigned long k = 0; k < steps; ++k)
    {
      again.step();
      exchange_again.refresh(again);
      migration_again.update(again, mine_again);
    }
    const double again_seconds = seconds_since(again_start);
    MPI_Reduce(&again_seconds, &seconds, 1, MPI_DOUBLE, MPI_MAX, 0, comm);
    // Where each rank's time went (waits included in the phase they end).
    const SolverReport report = again.report();
    const unsigned long planes_here = again.contacts().planes_computed() - planes_at_start;
    std::fprintf(stderr,
                 "rank %d, split computed %s: %.3f s; search %.3f, planes %.3f, forces %.3f, "
                 "motion %.3f; %lu common planes computed; %u contacts, %u sub-contacts held; "
                 "waited %.3f s for the sub-contacts' state, %.3f s for their layout\n",
                 rank, once ? "once" : "on both sides", again_seconds, report.seconds_detection,
                 report.seconds_planes, report.seconds_forces, report.seconds_motion, planes_here,
                 again.contacts().n_contacts(), again.contacts().n_subcontacts(),
                 shared_again.seconds_waiting_for_state(),
                 shared_again.seconds_waiting_for_layout());
    MPI_Reduce(&planes_here, &planes_again, 1, MPI_UNSIGNED_LONG, MPI_SUM, 0, comm);
    differing = 0;
    if (mine_again.local == mine.local)
      for (std::size_t i = 0; i < mine.local.size(); ++i)
        differing += mine.owned[i] &&
                     (local_again.centroid[i] != local.centroid[i] ||
                      again.velocity[i] != solver.velocity[i] || again.spin[i] != solver.spin[i]);
    else
      differing = mine.local.size();
    MPI_Allreduce(MPI_IN_PLACE, &differing, 1, MPI_UNSIGNED_LONG, MPI_SUM, comm);
  };
  // Every round ends with the split computed on both sides.
  std::vector<double> both_times;
  unsigned long both_differ = 0, both_planes = 0;
  const auto split_both_sides = [&]()
  {
    double seconds = 0.0;
    unsigned long differing = 0;
    split_again(false, seconds, differing, both_planes);
    both_times.push_back(seconds);
    both_differ += differing;
  };
  split_both_sides();

  // 4. The further rounds: whole again on rank 0 (which must end where the
  // first whole run did, bit for bit), then split again, computed once.
  std::vector<double> split_times;
  for (unsigned long r = 1; r < rounds; ++r)
  {
    whole_times.push_back(whole_alone());
    double seconds = 0.0;
    unsigned long differing = 0, planes_again = 0;
    split_again(true, seconds, differing, planes_again);
    split_times.push_back(seconds);
    rounds_differ += differing;
    at_once_times.push_back(whole_at_once());
    split_both_sides();
  }

  // This machine's MPI between ranks 0 and 1, for the exchange model.
  const rank_figures::MpiFigures mpi_figures = rank_figures::measure_mpi(comm);
  const double latency = mpi_figures.latency, bandwidth = mpi_figures.bandwidth,
               allreduce = mpi_figures.allreduce;
  // The cost of one migration event, forced: the boxes gathered, the
  // ghosts chosen again, the blocks traded.
  MPI_Barrier(comm);
  const auto event_start = std::chrono::steady_clock::now();
  const RankBlocks at_start = mine;
  migration.migrate(solver, mine);
  const double event_seconds = seconds_since(event_start);
  // The cubes settle far less than the reach: the event, which knows only
  // the boxes near this rank's region, must choose what the whole model
  // gave at the start.
  int same = at_start.local == mine.local && at_start.owned == mine.owned &&
             at_start.send == mine.send && at_start.receive == mine.receive;
  MPI_Allreduce(MPI_IN_PLACE, &same, 1, MPI_INT, MPI_LAND, comm);
  double first_split_seconds = 0.0;
  MPI_Reduce(&mine_seconds, &first_split_seconds, 1, MPI_DOUBLE, MPI_MAX, 0, comm);
  split_times.insert(split_times.begin(), first_split_seconds);
  // The least disturbed runs: the best whole and the best split time.
  const double best_whole = *std::min_element(whole_times.begin(), whole_times.end());
  const double split_seconds = *std::min_element(split_times.begin(), split_times.end());
  // Per round (rank 0's times alone are whole): the speed-up, the ceiling,
  // and the speed-up's share of the ceiling; their medians.
  std::vector<double> speed_ups, ceilings, shares, once_over_both;
  if (rank == 0)
    for (std::size_t r = 0; r < rounds; ++r)
    {
      once_over_both.push_back(split_times[r] / both_times[r]);
      speed_ups.push_back(whole_times[r] / split_times[r]);
      ceilings.push_back(ranks * whole_times[r] / at_once_times[r]);
      shares.push_back(speed_ups.back() / ceilings.back());
    }
  const double median_speed_up = rank_figures::median(speed_ups);
  std::fprintf(stderr, "rank %d: %u owned, %zu held, %.0f doubles sent per step, %.3f s\n", rank,
               mine.n_owned(), mine.local.size(), double(exchange.sent()), mine_seconds);
  long held = static_cast<long>(mine.local.size()), held_all = 0;
  double sent = static_cast<double>(exchange.sent() + subcontacts_sent) * 8.0, sent_all = 0.0;
  double sent_subcontacts = static_cast<double>(subcontacts_sent) * 8.0, sent_subcontacts_all = 0.0;
  unsigned long taken = subcontacts_taken, taken_all = 0;
  unsigned long held_subcontacts = solver.contacts().n_subcontacts(), held_subcontacts_all = 0;
  MPI_Reduce(&held_subcontacts, &held_subcontacts_all, 1, MPI_UNSIGNED_LONG, MPI_SUM, 0, comm);
  MPI_Reduce(&held, &held_all, 1, MPI_LONG, MPI_SUM, 0, comm);
  MPI_Reduce(&sent, &sent_all, 1, MPI_DOUBLE, MPI_SUM, 0, comm);
  MPI_Reduce(&sent_subcontacts, &sent_subcontacts_all, 1, MPI_DOUBLE, MPI_SUM, 0, comm);
  MPI_Reduce(&taken, &taken_all, 1, MPI_UNSIGNED_LONG, MPI_SUM, 0, comm);
  double exchange_all = 0.0;
  MPI_Reduce(&exchange_seconds, &exchange_all, 1, MPI_DOUBLE, MPI_MAX, 0, comm);
  if (rank == 0)
  {
    std::printf("%s, %s; %d ranks\n", cpu_model().c_str(), rank_figures::date_utc().c_str(), ranks);
    std::printf("n = %u: %u blocks, %lu steps\n", n, model.n_blocks(), steps);
    std::printf("split run against the whole run: %lu of %lu blocks (%s) differ in centroid, "
                "velocity or spin, bit for bit\n",
                differ, compared, compared == model.n_blocks() ? "all" : "NOT ALL");
    const double block_steps = double(model.n_blocks()) * steps;
    for (std::size_t r = 0; r < rounds; ++r)
      std::printf("round %zu: whole on one rank %.3f s (%.0f block-cycles/s), split on %d ranks, "
                  "each contact across ranks computed once, %.3f s (%.0f); speed-up %.2f; the "
                  "whole model on every rank at once %.3f s: ceiling %.2f\n",
                  r + 1, whole_times[r], block_steps / whole_times[r], ranks, split_times[r],
                  block_steps / split_times[r], whole_times[r] / split_times[r], at_once_times[r],
                  ranks * whole_times[r] / at_once_times[r]);
    std::printf("speed-up: %.2f, the best whole run (%.3f s, %.0f block-cycles/s) over the best "
                "split run (%.3f s, %.0f); median of the %lu rounds %.2f\n",
                best_whole / split_seconds, best_whole, block_steps / best_whole, split_seconds,
                block_steps / split_seconds, rounds, median_speed_up);
    std::printf("ceiling (median of the rounds): %.2f; the speed-up over the ceiling (median of "
                "the rounds): %.2f\n",
                rank_figures::median(ceilings), rank_figures::median(shares));
    for (std::size_t r = 0; r < rounds; ++r)
      std::printf("round %zu: split with the contacts across ranks computed on both sides "
                  "%.3f s (speed-up %.2f); computed once took %.3f times that\n",
                  r + 1, both_times[r], whole_times[r] / both_times[r], once_over_both[r]);
    std::printf("computed once over computed on both sides, median of the rounds: %.3f\n",
                rank_figures::median(once_over_both));
    std::printf("the split runs on both sides and the later split runs against round 1's, the "
                "later whole runs against round 1's and rank 0's runs at once against it: %lu, "
                "%lu and %lu blocks differ, bit for bit\n",
                both_differ, rounds_differ, at_once_differ);
    std::printf("sub-contacts computed a step: %lu on all ranks (%lu held, %lu of them taken "
                "from another rank), %u on one rank: %.4f times one rank's work (computed on "
                "both sides: %.4f)\n",
                held_subcontacts_all - taken_all, held_subcontacts_all, taken_all,
                whole.subcontacts, double(held_subcontacts_all - taken_all) / whole.subcontacts,
                double(held_subcontacts_all) / whole.subcontacts);
    std::printf("common planes computed in the steps: %lu on all ranks, %lu on one rank: %.4f "
                "times one rank's work (computed on both sides: %.4f)\n",
                planes_all, whole.planes, double(planes_all) / whole.planes,
                double(both_planes) / whole.planes);
    std::printf("blocks held %.3f times the model (ghosts); exchange %.0f bytes per step in "
                "all (%.0f of them sub-contacts' state, %lu sub-contacts taken), %.0f bytes "
                "per block-step\n",
                double(held_all) / model.n_blocks(), sent_all, sent_subcontacts_all, taken_all,
                sent_all / model.n_blocks());
    std::printf("migration events %lu, blocks that changed owner %lu; one event forced "
                "after the steps took %.3f s on rank 0 and chose %s\n",
                migration.events() - 1, migration.owner_changes(), event_seconds,
                same ? "the blocks and lists of the start" : "OTHER BLOCKS OR LISTS (wrong)");
    if (ranks < 2)
      return 0;
    std::printf("exchange: %.1f %% of round 1's split run's time (the slowest rank in "
                "GhostExchange)\n",
                100.0 * exchange_all / first_split_seconds);
    std::printf("MPI between ranks 0 and 1: latency %.2f us, bandwidth %.2f GB/s, one "
                "MPI_Allreduce %.2f us\n",
                1e6 * latency, 1e-9 * bandwidth, 1e6 * allreduce);
    std::printf("memory per block held (rank 1: the rise of its peak resident memory with its "
                "share, ghosts included): %.0f bytes\n",
                memory_per_block);
    std::printf("the whole block model every rank builds at set-up: %.0f bytes per block\n",
                model_bytes_per_block);

    // The exchange model: P ranks, each a cube of m = N / P blocks of side
    // L = m^(1/3) (in block sizes). A rank holds (L + 2 g)^3 blocks (g
    // layers of ghosts on every side). It moves its m at the whole run's
    // rate (t per block-step) and pays, per ghost it holds, what a ghost
    // cost here: the split run's time beyond its owned blocks' share of the
    // whole run's, less the ghosts' exchange, over the ghosts (the
    // sub-contacts' exchange is in it). It sends each of its blocks
    // within g layers of a face to that neighbour ((L + 2 g)^3 - L^3 in all)
    // at the measured bytes per ghost, to 26 neighbours (latency each), and
    // takes part in 5 reductions of log2 P latencies each.
    const double t_block = best_whole / (double(model.n_blocks()) * steps);
    const double ghosts_here = double(held_all - model.n_blocks());
    const double bytes_per_ghost = ghosts_here > 0.0 ? sent_all / ghosts_here : 0.0;
    const double t_ghost =
        ghosts_here > 0.0 ? std::max(0.0, (ranks * (split_seconds - exchange_all) - best_whole) /
                                              (ghosts_here * steps))
                          : 0.0;
    std::printf("model inputs: %.3g s per block-step (whole run), %.3g s per ghost-step, %.0f "
                "bytes per ghost sent\n",
                t_block, t_ghost, bytes_per_ghost);
    for (const double total : {1e7})
      for (const double p : {64.0, 1000.0})
      {
        const double m = total / p, side = std::cbrt(m);
        const double held_blocks = std::pow(side + 2.0 * layers, 3);
        const double compute = m * t_block + (held_blocks - m) * t_ghost;
        const double sent_bytes = (held_blocks - m) * bytes_per_ghost;
        const double talk = 26.0 * latency + sent_bytes / bandwidth + 5.0 * std::log2(p) * latency;
        const double efficiency = m * t_block / (compute + talk);
        std::printf("predicted: %.0f blocks on %.0f ranks: %.0f blocks a rank, held %.2f times; "
                    "%.3g s computing and %.3g s exchanging a step; efficiency %.0f %%\n",
                    total, p, m, held_blocks / m, compute, talk, 100.0 * efficiency);
      }
  }
}
