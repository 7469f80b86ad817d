// Memory and time of the set-up of a rigid model split among ranks (issue
// 24): the settling cubes of benchmark_rigid_ranks (n x n x (n + 1) unit
// cubes, n^2 of them the fixed floor) as a scene, each rank's share made
// either from the whole model every rank builds (build_blocks, its digest,
// then RankShare from the model: what `talus` does on a restart, or for a
// scene with deformable blocks) or from the scene alone (RankShare from the
// scene: each rank cuts the brick piece by piece, twice, takes the whole
// model's digest on the first pass, and keeps its region and the blocks
// near it: what `talus` does for a new run of rigid blocks).
//
//   mpirun -np P benchmark_region_setup n whole|region
//
// One way per run, since a process's peak memory only rises. Prints per
// rank: the set-up's time, the rise of the peak resident memory over the
// set-up (VmHWM), the resident memory held after it (the share), and the
// blocks held; then the peak over the whole model's blocks, and the
// slowest rank's time. Run both ways with the same n to compare.

#include <talus/base/memory.h>
#include <talus/base/parallel_environment.h>
#include <talus/run/rank_share.h>
#include <talus/scene/build_blocks.h>

#include <mpi.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "rank_figures.h"

using namespace talus;
using namespace rank_figures;

int main(int argc, char** argv)
{
  ParallelEnvironment mpi(argc, argv);
  const unsigned int n = argc > 1 ? static_cast<unsigned int>(std::atoi(argv[1])) : 30;
  const bool by_region = argc > 2 && std::strcmp(argv[2], "region") == 0;
  if (n == 0 || argc < 3 || (!by_region && std::strcmp(argv[2], "whole") != 0))
  {
    std::fprintf(stderr, "usage: benchmark_region_setup n whole|region\n");
    return 2;
  }
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);

  Scene scene;
  scene.brick = Box{Vec3::Zero(), Vec3(n, n, n + 1)};
  scene.joint_sets = {{0.0, 0.0, 1.0, Vec3::Zero(), 0, false, {}},
                      {90.0, 0.0, 1.0, Vec3::Zero(), 0, false, {}},
                      {90.0, 90.0, 1.0, Vec3::Zero(), 0, false, {}}};
  GroupSpec floor;
  floor.name = "floor";
  floor.region = Box{Vec3(-1, -1, -1), Vec3(n + 1, n + 1, 1)};
  scene.groups = {floor};
  const double reach = 4.0 * 0.01; // as talus: 4 contact tolerances (m)

  wait_for_all(MPI_COMM_WORLD);
  const double peak_before = peak_memory();
  const auto start = std::chrono::steady_clock::now();
  BuildReport report;
  std::unique_ptr<RankShare> share;
  ModelDigest digest;
  if (by_region)
  {
    digest = ModelDigest(scene, true);
    share = std::make_unique<RankShare>(scene, report, reach, MPI_COMM_WORLD, &digest);
  }
  else
  {
    const BlockModel whole = build_blocks(scene, report);
    digest = ModelDigest::of(scene, whole);
    share = std::make_unique<RankShare>(whole, reach, MPI_COMM_WORLD);
  }
  const double seconds = seconds_since(start);
  const double peak_rise = peak_memory() - peak_before;
  const double held_bytes = resident_bytes();

  const std::vector<double> mine{seconds, peak_rise, held_bytes,
                                 static_cast<double>(share->blocks().local.size()),
                                 static_cast<double>(share->blocks().n_owned())};
  const std::vector<double> all = gather_on_rank_0(mine, MPI_COMM_WORLD);
  if (rank != 0)
    return 0;
  const double blocks = share->n_blocks();
  std::printf("# %s, %s; %d ranks; n = %u: %.0f blocks, set-up %s\n", cpu_model().c_str(),
              date_utc().c_str(), ranks, n, blocks,
              by_region ? "by region (RankShare from the scene)"
                        : "whole (build_blocks, RankShare from the model)");
  std::printf("digest of the whole model: %u blocks, %lu faces, volume %.9g m^3, fingerprint "
              "%016llx\n",
              digest.n_blocks(), digest.n_faces(), digest.total_volume(),
              static_cast<unsigned long long>(digest.geometry_fingerprint()));
  double slowest = 0.0, largest_peak = 0.0;
  for (int r = 0; r < ranks; ++r)
  {
    const double* f = &all[std::size_t(r) * mine.size()];
    std::printf("rank %d: set-up %.2f s, peak resident memory rose %.1f MB (%.0f bytes per block "
                "of the model), resident after %.1f MB; %.0f blocks held, %.0f owned\n",
                r, f[0], f[1] / 1e6, f[1] / blocks, f[2] / 1e6, f[3], f[4]);
    slowest = std::max(slowest, f[0]);
    largest_peak = std::max(largest_peak, f[1]);
  }
  std::printf("slowest rank's set-up %.2f s (%.0f blocks/s); largest rise of peak memory %.1f MB "
              "(%.0f bytes per block of the model)\n",
              slowest, blocks / slowest, largest_peak / 1e6, largest_peak / blocks);
  return 0;
}
