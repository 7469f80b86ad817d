// Building only some blocks of a scene (build_blocks_where: the brick cut
// one piece at a time, depth first, keeping what a rank asks for) gives
// each kept block exactly as build_blocks() makes the whole model: same
// number, vertices, faces, face origins, mass properties and group, bit for
// bit, and the same report (cuts, refused slivers, excavated volumes). The
// scenes are shipped ones with dipping joint sets, single and limited
// joints, excavations and stages' excavations, slivers refused by the
// minimum volume, and blocks of very different sizes.

#include <talus/scene/build_blocks.h>

#include <cstring>

#include "../block_model_checks.h"
#include "../tests.h"

using namespace talus;

namespace
{

bool same_report(const BuildReport& a, const BuildReport& b)
{
  return a.cutting.cuts == b.cutting.cuts &&
         a.cutting.skipped_slivers == b.cutting.skipped_slivers &&
         std::memcmp(&a.cutting.smallest_refused, &b.cutting.smallest_refused, sizeof(double)) ==
             0 &&
         a.cutting.smallest_refused_at == b.cutting.smallest_refused_at &&
         talus_test::same_array_bits(a.excavated_volume, b.excavated_volume) &&
         talus_test::same_array_bits(a.stage_excavated_volume, b.stage_excavated_volume) &&
         a.joint_set_cuts == b.joint_set_cuts && a.joint_cuts == b.joint_cuts;
}

} // namespace

int main()
{
  const std::string dir = std::string(SOURCE_DIR) + "/../../parameters/";
  for (const char* file :
       {"cavern_staged.prm", "stability/slope_10000_blocks.prm",
        "stability/degenerate_contacts.prm", "stability/sliver_beside_large_block.prm",
        "stability/spinning_block.prm", "verification/key_block_fall.prm",
        "verification/staged_stack.prm", "verification/sheared_wall.prm"})
  {
    const Scene scene = read_scene(dir + file, false);
    BuildReport whole_report;
    const BlockModel whole = build_blocks(scene, whole_report);
    const double middle = 0.5 * (scene.brick.lo[0] + scene.brick.hi[0]);
    // What a rank might keep: every third block, and those in the lower
    // half in x; then all, then none.
    const std::vector<std::pair<const char*, KeepBlock>> keeps{
        {"a third and the lower half", [middle](unsigned int b, const ConvexPolyhedron& block)
         { return b % 3 == 1 || block.vertex_mean()[0] < middle; }},
        {"all", [](unsigned int, const ConvexPolyhedron&) { return true; }},
        {"none", [](unsigned int, const ConvexPolyhedron&) { return false; }}};
    for (const auto& [name, keep] : keeps)
    {
      BuildReport report;
      std::vector<unsigned int> global;
      unsigned int n_blocks = 0;
      const BlockModel part = build_blocks_where(scene, report, keep, global, n_blocks);
      // The blocks the predicate takes, from the whole model.
      std::vector<unsigned int> expected;
      for (unsigned int b = 0; b < whole.n_blocks(); ++b)
        if (keep(b, whole.polyhedron(b)))
          expected.push_back(b);
      const bool numbers = n_blocks == whole.n_blocks() && global == expected;
      const bool blocks = numbers && talus_test::same_model(part, whole.subset(global));
      std::printf("%s, %s: %u blocks of %u kept; numbers %s, blocks %s, report %s\n", file, name,
                  static_cast<unsigned int>(global.size()), n_blocks, talus_test::verdict(numbers),
                  talus_test::verdict(blocks),
                  talus_test::verdict(same_report(report, whole_report)));
    }
    std::printf("%s: %lu cuts, %lu refused as slivers, %zu excavations, %zu stage cuts\n", file,
                whole_report.cutting.cuts, whole_report.cutting.skipped_slivers,
                whole_report.excavated_volume.size(), whole_report.stage_excavated_volume.size());
  }
}
