// The digest of the whole model that the run summary, the checks and the
// checkpoints read (ModelDigest) is the same whether it is taken from the
// whole model or one block at a time as the brick is cut (what a rank that
// builds only its region does, issue 24): counts, volume and mass to the
// last bit, groups, centroids, the geometry fingerprint, the blocks that
// hold the history points, which face loads select a rigid face, and the
// table of face loads every rank keeps (compared by the forces it puts on
// the whole model). A nudged vertex changes the fingerprint.

#include <talus/scene/build_blocks.h>
#include <talus/scene/model_digest.h>

#include <cmath>
#include <cstring>

#include "../block_model_checks.h"
#include "../tests.h"

using namespace talus;

namespace
{

bool same_bits(double a, double b)
{
  return std::memcmp(&a, &b, sizeof a) == 0;
}

/// The forces and moments of a face load table on every block of `model`.
std::vector<Vec3> loads_of(const RigidFaceLoads& table, const BlockModel& model)
{
  std::vector<unsigned int> all(model.n_blocks());
  for (unsigned int b = 0; b < model.n_blocks(); ++b)
    all[b] = b;
  RigidFaceLoads here = table.localized(model, all, std::vector<char>(model.n_blocks(), 1));
  std::vector<Vec3> force(model.n_blocks(), Vec3::Zero()), moment = force;
  const std::vector<Vec3> still(model.n_blocks(), Vec3::Zero());
  here.add(model, force, moment, still, still, 0.0);
  force.insert(force.end(), moment.begin(), moment.end());
  return force;
}

} // namespace

int main()
{
  const std::string shipped = std::string(SOURCE_DIR) + "/../../parameters/";
  const std::string tests = std::string(SOURCE_DIR) + "/../";
  for (const std::string& file :
       {shipped + "cavern_staged.prm", shipped + "stability/slope_10000_blocks.prm",
        shipped + "stability/degenerate_contacts.prm", shipped + "verification/staged_stack.prm",
        tests + "parallel/pushed_block_crossing_01.prm",
        tests + "scenes/shaped_boundaries_rigid.prm", tests + "scenes/history_block_points_01.prm"})
  {
    Scene scene = read_scene(file, false);
    BuildReport report;
    const BlockModel whole = build_blocks(scene, report);
    const ModelDigest of_whole = ModelDigest::of(scene, whole);
    ModelDigest streamed(scene, true);
    std::vector<unsigned int> none;
    unsigned int n_blocks = 0;
    BuildReport again;
    build_blocks_where(
        scene, again,
        [&](unsigned int b, const ConvexPolyhedron& block)
        {
          streamed.add(scene_block(scene, block, b), 0);
          return false;
        },
        none, n_blocks);

    const std::string name = file.substr(file.rfind('/') + 1);
    // (The mass to round-off: the compiler may fuse the product and the sum
    // here and not in the digest, or the other way round.)
    const auto counts = [&](const ModelDigest& d)
    {
      double mass = 0.0;
      for (unsigned int b = 0; b < whole.n_blocks(); ++b)
        mass += scene.density_of(whole.group_names[whole.group[b]]) * whole.volume[b];
      bool groups = true;
      for (unsigned int g = 0; g < whole.group_names.size(); ++g)
        groups = groups && d.blocks_in(whole.group_names[g]) ==
                               std::count(whole.group.begin(), whole.group.end(), g);
      return d.n_blocks() == whole.n_blocks() && d.n_faces() == whole.n_faces() &&
             d.n_vertices() == whole.n_vertices() &&
             same_bits(d.total_volume(), whole.total_volume()) &&
             std::abs(d.mass() - mass) <= 1e-14 * mass && groups &&
             talus_test::same_array_bits(d.centroid(), whole.centroid);
    };
    std::printf(
        "%s: %u blocks, %lu faces; counts, sums and centroids: whole %s, streamed %s; "
        "masses alike %s; fingerprints %s\n",
        name.c_str(), of_whole.n_blocks(), of_whole.n_faces(),
        talus_test::verdict(counts(of_whole)), talus_test::verdict(counts(streamed)),
        talus_test::verdict(same_bits(of_whole.mass(), streamed.mass())),
        talus_test::verdict(of_whole.geometry_fingerprint() == streamed.geometry_fingerprint()));

    // One vertex a last bit away: another fingerprint.
    BlockModel nudged = whole;
    nudged.vertex[nudged.n_vertices() / 2][1] =
        std::nextafter(nudged.vertex[nudged.n_vertices() / 2][1], 1e300);
    std::printf("  a nudged vertex changes the fingerprint: %s\n",
                talus_test::verdict(ModelDigest::of(scene, nudged).geometry_fingerprint() !=
                                    of_whole.geometry_fingerprint()));

    Scene a = scene, b = scene;
    of_whole.resolve_history_blocks(a);
    streamed.resolve_history_blocks(b);
    std::printf("  history blocks:");
    for (unsigned int h : b.solver.history_blocks)
      std::printf(" %u", h);
    std::printf(" (%zu from points); the same from the whole model: %s\n",
                scene.history_block_points.size(),
                talus_test::verdict(a.solver.history_blocks == b.solver.history_blocks));

    // Face loads: which select a rigid face, as on the whole model, and the
    // table's forces.
    const std::vector<char> rigid(whole.n_blocks(), 1);
    std::vector<const FacePressure*> loads;
    for (const FacePressure& p : scene.face_pressures)
      loads.push_back(&p);
    for (const StageSpec& stage : scene.stages)
      if (stage.changes_boundaries)
        for (const FacePressure& p : stage.boundaries.face_pressures)
          loads.push_back(&p);
    unsigned int selecting = 0;
    bool alike = true;
    for (std::size_t k = 0; k < loads.size(); ++k)
    {
      const FacePressure* p = loads[k];
      const bool on_whole = !p->quiet && !face_patches_in(whole, rigid, p->region).empty();
      selecting += on_whole;
      alike = alike && streamed.rigid_face_in(k) == on_whole;
    }
    const RigidFaceLoads table = streamed.face_load_table(scene.face_pressures, 0);
    const RigidFaceLoads expected =
        RigidFaceLoads(whole, rigid, scene.face_pressures).relative_to(whole);
    std::printf("  face loads: %zu, %u select a rigid face, as on the whole model: %s; table of "
                "%u parts, forces on the whole model %s\n",
                loads.size(), selecting, talus_test::verdict(alike), table.n_patches(),
                talus_test::verdict(table.n_patches() == expected.n_patches() &&
                                    talus_test::same_array_bits(loads_of(table, whole),
                                                                loads_of(expected, whole))));
  }
}
