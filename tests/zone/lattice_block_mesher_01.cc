// The lattice Delaunay mesher (mesh_convex_block_by_lattice) on a unit
// cube, the cube cut by one and by three oblique joints (every block), at
// h = 0.25 m; a thin slab (0.02 m between two parallel joints, h = 0.25 m);
// and a block of 24 faces (a turned cube with its edges and six corners cut
// off, h = 0.3 m). The checks of convex_block_mesher_checks.h, as for gmsh
// in convex_block_mesher_01 and _02: positive zones, volumes summing to the
// block's to 1e-12, the mesh's surface on the block's faces with their areas
// to 1e-12, 0.5-2x the regular-tetrahedra count for blocks at least 2h wide,
// at most one interior gridpoint in blocks less than 1.2h wide (interior
// lattice points stay 0.6h from every face), the median radius ratio at
// least 0.6, zones below 0.1 only where the block's shape forces them. Then:
//  - every block meshed twice gives the same mesh, bit for bit;
//  - mesh_convex_blocks_with `automatic` meshes a block by the lattice when
//    the edge length is uniform, by gmsh when it varies by more than 25 %
//    over the block.
// Verdicts on standard output; counts and qualities on standard error.

#include <talus/geometry/block_generator.h>
#include <talus/model/block_model.h>
#include <talus/zone/lattice_block_mesher.h>

#include <Eigen/Geometry>

#include <cstdio>
#include <numeric>
#include <string>

#include "../tests.h"
#include "convex_block_mesher_checks.h"

using namespace talus;

namespace
{
BlockModel model_of(const BlockGenerator& generator)
{
  BlockModel model;
  for (const ConvexPolyhedron& b : generator.blocks())
    model.add_block(b, 0);
  return model;
}

/// Meshes blocks `which` by the lattice, checks them, and meshes them again
/// to compare; returns whether every second mesh equals the first.
bool mesh_and_check(const std::string& name, const BlockModel& model,
                    const std::vector<unsigned int>& which, double h)
{
  const EdgeLengthAt size = [h](const Vec3&) { return h; };
  std::vector<BlockTetrahedra> meshes;
  for (unsigned int b : which)
    meshes.push_back(mesh_convex_block_by_lattice(model, b, size));
  talus_test::report_meshes(name, model, meshes, which, h, 1.2);
  bool same = true;
  for (std::size_t i = 0; i < which.size(); ++i)
  {
    const BlockTetrahedra again = mesh_convex_block_by_lattice(model, which[i], size);
    same = same && again.tet == meshes[i].tet && again.point.size() == meshes[i].point.size();
    for (std::size_t g = 0; same && g < again.point.size(); ++g)
      same = again.point[g] == meshes[i].point[g];
  }
  return same;
}

std::vector<unsigned int> all_of(const BlockModel& model)
{
  std::vector<unsigned int> all(model.n_blocks());
  std::iota(all.begin(), all.end(), 0u);
  return all;
}
} // namespace

int main()
{
  bool same = true;
  const double h = 0.25;
  const ConvexPolyhedron cube = ConvexPolyhedron::box(Vec3::Zero(), Vec3::Ones());
  {
    BlockModel model;
    model.add_block(cube, 0);
    same = mesh_and_check("unit cube", model, {0}, h) && same;
  }
  {
    BlockGenerator generator(cube, {});
    generator.cut_plane(Plane::through(Vec3(0.5, 0.45, 0.55), normal_from_dip(35.0, 60.0)));
    const BlockModel model = model_of(generator);
    same = mesh_and_check("cube cut by one oblique joint", model, all_of(model), h) && same;
  }
  BlockGenerator three(cube, {});
  three.cut_plane(Plane::through(Vec3(0.5, 0.45, 0.55), normal_from_dip(35.0, 60.0)));
  three.cut_plane(Plane::through(Vec3(0.4, 0.6, 0.5), normal_from_dip(70.0, 150.0)));
  three.cut_plane(Plane::through(Vec3(0.55, 0.5, 0.4), normal_from_dip(80.0, 250.0)));
  const BlockModel jointed = model_of(three);
  same = mesh_and_check("cube cut by three oblique joints", jointed, all_of(jointed), h) && same;
  {
    const double thickness = 0.02;
    const Vec3 n = normal_from_dip(30.0, 110.0);
    BlockGenerator generator(cube, {});
    generator.cut_plane(Plane(n, n.dot(Vec3::Constant(0.5))));
    generator.cut_plane(Plane(n, n.dot(Vec3::Constant(0.5)) + thickness));
    BlockModel model;
    unsigned int slab = 0;
    for (const ConvexPolyhedron& b : generator.blocks())
    {
      const auto [lo, hi] = b.extent_along(Plane(n, 0.0));
      const unsigned int i = model.add_block(b, 0);
      if (hi - lo < 1.5 * thickness)
        slab = i;
    }
    same = mesh_and_check("thin slab (0.02 m)", model, {slab}, h) && same;
    const talus_test::BlockShape shape = talus_test::block_shape(model, slab);
    std::printf("  its shape forces flat zones (thickness below h/4): %s\n",
                talus_test::verdict(shape.forces_slivers(thickness, h)));
  }
  {
    // As in convex_block_mesher_02: a cube of side 2 m turned about an
    // oblique axis, its edges and six corners cut off.
    unsigned int inner = 0;
    const BlockModel model = talus_test::many_faced_block(inner);
    std::printf("block of %u faces\n", model.face_start[inner + 1] - model.face_start[inner]);
    same = mesh_and_check("24-faced block", model, {inner}, 0.3) && same;
  }
  std::printf("every block meshed twice: the same mesh, bit for bit: %s\n",
              talus_test::verdict(same));

  // Which mesher `automatic` takes: the lattice at a uniform edge length;
  // gmsh where it varies by more than 25 % (0.2 m at x = 0 to 0.3 m at x = 1).
  {
    unsigned int by_lattice = 0;
    const std::vector<unsigned int> all = all_of(jointed);
    mesh_convex_blocks_with(
        jointed, all, [](const Vec3&) { return 0.25; }, ConvexMesher::automatic, &by_lattice);
    std::printf("automatic, uniform edge length: %u of %zu blocks by the lattice: %s\n", by_lattice,
                all.size(), talus_test::verdict(by_lattice == all.size()));
    const EdgeLengthAt graded = [](const Vec3& x) { return 0.2 + 0.1 * x.x(); };
    unsigned int varied = 0;
    for (unsigned int b : all)
    {
      const auto [lo, hi] = edge_length_range(jointed, b, graded);
      varied += hi > 1.25 * lo;
    }
    const std::vector<BlockTetrahedra> meshes =
        mesh_convex_blocks_with(jointed, all, graded, ConvexMesher::automatic, &by_lattice);
    std::printf(
        "automatic, graded: the blocks whose edge length varies by more than 25 %% go "
        "to gmsh (%u of %zu), the others to the lattice: %s\n",
        varied, all.size(),
        talus_test::verdict(varied > 0 && by_lattice > 0 && by_lattice + varied == all.size()));
    unsigned int non_positive = 0;
    for (const BlockTetrahedra& t : meshes)
      for (const auto& z : t.tet)
        non_positive += !(talus_test::signed_volume(t.point[z[0]], t.point[z[1]], t.point[z[2]],
                                                    t.point[z[3]]) > 0.0);
    std::printf("  every zone of positive volume: %s\n", talus_test::verdict(non_positive == 0));
  }
}
