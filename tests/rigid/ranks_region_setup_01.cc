// A rank's share of a scene's rigid blocks built from the scene alone, each
// rank cutting the brick one piece at a time and keeping only the blocks of
// its region and near it (RankShare from a Scene), is the share that the
// whole model gives (RankShare from a BlockModel, as every rank built it
// until now): the same number of blocks in the model, the same blocks held
// in the same global order, owned or ghosts alike, the same lists of blocks
// sent and received, and every held block's vertices, faces, face origins,
// mass properties and group, bit for bit; and the same cutting report.
// Each rank's blocks held and owned are on standard error.
//
// The scenes are shipped ones: a staged cavern, a slope of 11,134 blocks
// with refused slivers, contacts on shared edges and corners, a sliver
// beside a large block, a wedge on a base far larger than its blocks, a
// benched slope.

#include <talus/base/parallel_environment.h>
#include <talus/run/rank_share.h>
#include <talus/scene/build_blocks.h>

#include <mpi.h>

#include <cstring>

#include "../block_model_checks.h"
#include "../tests.h"

using namespace talus;

namespace
{

bool same_lists(const std::vector<std::pair<unsigned int, std::vector<unsigned int>>>& a,
                const std::vector<std::pair<unsigned int, std::vector<unsigned int>>>& b)
{
  return a == b;
}

/// Whether every rank's `holds`.
bool on_every_rank(bool holds)
{
  int all = holds ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  return all == 1;
}

} // namespace

int main(int argc, char** argv)
{
  ParallelEnvironment mpi(argc, argv);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  const std::string dir = std::string(SOURCE_DIR) + "/../../parameters/";
  for (const char* file :
       {"cavern_staged.prm", "stability/slope_10000_blocks.prm",
        "stability/degenerate_contacts.prm", "stability/sliver_beside_large_block.prm",
        "verification/wedge.prm", "benched_slope.prm"})
  {
    const Scene scene = read_scene(dir + file, false);
    const double reach = 4.0 * scene.solver.contact.tolerance;
    BuildReport whole_report, report;
    const BlockModel whole = build_blocks(scene, whole_report);
    const RankShare from_model(whole, reach, MPI_COMM_WORLD);
    const RankShare from_scene(scene, report, reach, MPI_COMM_WORLD);
    const RankBlocks &a = from_model.blocks(), &b = from_scene.blocks();
    const bool count = from_scene.n_blocks() == whole.n_blocks();
    const bool held = a.local == b.local && a.owned == b.owned;
    const bool lists = same_lists(a.send, b.send) && same_lists(a.receive, b.receive);
    const bool blocks = held && talus_test::same_model(from_model.local(), from_scene.local());
    const bool cuts =
        report.cutting.cuts == whole_report.cutting.cuts &&
        report.cutting.skipped_slivers == whole_report.cutting.skipped_slivers &&
        talus_test::same_array_bits(report.excavated_volume, whole_report.excavated_volume) &&
        talus_test::same_array_bits(report.stage_excavated_volume,
                                    whole_report.stage_excavated_volume);
    unsigned long owned = a.n_owned(), total_owned = 0;
    MPI_Reduce(&owned, &total_owned, 1, MPI_UNSIGNED_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
    const bool all_owned = on_every_rank(rank != 0 || total_owned == whole.n_blocks());
    const bool c = on_every_rank(count), h = on_every_rank(held), l = on_every_rank(lists),
               k = on_every_rank(blocks), r = on_every_rank(cuts);
    std::fprintf(stderr, "%s, rank %d: %u of %u blocks held (%u owned)\n", file, rank,
                 static_cast<unsigned int>(b.local.size()), whole.n_blocks(), b.n_owned());
    if (rank == 0)
      std::printf("%s on %d ranks: %u blocks; count %s, each block owned once %s, blocks held %s, "
                  "lists sent and received %s, held blocks bit for bit %s, cutting report %s\n",
                  file, ranks, whole.n_blocks(), talus_test::verdict(c),
                  talus_test::verdict(all_owned), talus_test::verdict(h), talus_test::verdict(l),
                  talus_test::verdict(k), talus_test::verdict(r));
  }
}
