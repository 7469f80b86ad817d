// The convex block mesher gives a block the same mesh every time it is
// asked the same question: the blocks of a unit cube cut by three oblique
// joints (h = 0.25 m), meshed in one batch, then again after a cube was
// meshed in between, must get the same gridpoints (bit for bit) and zones;
// and so must each block meshed by itself (mesh_convex_block), twice. A
// deformable run's answer must not depend on what the process meshed
// before (a restart or a rerun meshes again). How many blocks mesh
// differently alone than in a batch goes to standard error: gmsh's
// tolerances follow the size of the whole model it meshes, so the batching
// may change a mesh, though not from one run to the next.

#include <talus/geometry/block_generator.h>
#include <talus/model/block_model.h>
#include <talus/zone/convex_block_mesher.h>

#include <cstdio>
#include <numeric>

#include "../tests.h"

using namespace talus;

namespace
{
bool same(const BlockTetrahedra& a, const BlockTetrahedra& b)
{
  return a.point == b.point && a.tet == b.tet;
}
} // namespace

int main()
{
  const double h = 0.25;
  const EdgeLengthAt size = [h](const Vec3&) { return h; };
  BlockGenerator generator(ConvexPolyhedron::box(Vec3::Zero(), Vec3::Ones()), {});
  generator.cut_plane(Plane::through(Vec3(0.5, 0.45, 0.55), normal_from_dip(35.0, 60.0)));
  generator.cut_plane(Plane::through(Vec3(0.4, 0.6, 0.5), normal_from_dip(70.0, 150.0)));
  generator.cut_plane(Plane::through(Vec3(0.55, 0.5, 0.4), normal_from_dip(80.0, 250.0)));
  BlockModel model;
  for (const ConvexPolyhedron& b : generator.blocks())
    model.add_block(b, 0);
  std::vector<unsigned int> all(model.n_blocks());
  std::iota(all.begin(), all.end(), 0u);
  BlockModel cube;
  cube.add_block(ConvexPolyhedron::box(Vec3::Zero(), Vec3::Ones()), 0);

  const std::vector<BlockTetrahedra> batch = mesh_convex_blocks(model, all, size);
  std::vector<BlockTetrahedra> alone;
  for (unsigned int b : all)
    alone.push_back(mesh_convex_block(model, b, size));
  mesh_convex_block(cube, 0, size);
  const std::vector<BlockTetrahedra> batch_again = mesh_convex_blocks(model, all, size);
  unsigned int differ_batch = 0, differ_alone = 0, batch_not_alone = 0;
  for (unsigned int b : all)
  {
    const BlockTetrahedra alone_again = mesh_convex_block(model, b, size);
    differ_batch += !same(batch[b], batch_again[b]);
    differ_alone += !same(alone[b], alone_again);
    batch_not_alone += !same(batch[b], alone[b]);
    std::fprintf(stderr, "block %u: zones in a batch %zu then %zu, alone %zu then %zu\n", b,
                 batch[b].tet.size(), batch_again[b].tet.size(), alone[b].tet.size(),
                 alone_again.tet.size());
  }
  std::printf("%u blocks, each meshed twice in a batch and twice alone:\n", model.n_blocks());
  std::printf("  the same meshes in the batch the second time: %s\n",
              talus_test::verdict(differ_batch == 0));
  std::printf("  the same meshes alone the second time: %s\n",
              talus_test::verdict(differ_alone == 0));
  std::fprintf(stderr,
               "blocks whose mesh differs: second batch %u, second time alone %u; alone and in "
               "the batch %u\n",
               differ_batch, differ_alone, batch_not_alone);
}
