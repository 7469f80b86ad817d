// The convex block mesher (mesh_convex_blocks, gmsh) on two awkward blocks:
//  - a thin slab between two parallel oblique joints 0.02 m apart, cut from
//    a unit cube, at h = 0.25 m (12.5 times its thickness): its mesh can only
//    be its faces' triangles joined across the thickness, so zones below a
//    radius ratio of 0.1 are forced by the block's shape;
//  - a block of 24 faces, as one beside a tunnel bounded by joints and the
//    tunnel's facets: a cube turned obliquely, its 12 edges and 6 of its 8
//    corners cut off by planes, at h = 0.3 m.
// The checks of convex_block_mesher_checks.h (as in convex_block_mesher_01):
// positive zones, volumes summing to the block's to 1e-12, the mesh's
// surface on the block's faces with their areas to 1e-12, the size band for
// blocks at least 2h wide, the median radius ratio, and slivers only where
// the shape forces them. Exact counts and qualities go to standard error.

#include <talus/geometry/block_generator.h>
#include <talus/model/block_model.h>
#include <talus/zone/convex_block_mesher.h>

#include <Eigen/Geometry>

#include <cstdio>
#include <numeric>
#include <string>

#include "../tests.h"
#include "convex_block_mesher_checks.h"

using namespace talus;

int main()
{
  {
    // The slab: between two parallel joints 0.02 m apart through the cube.
    const double h = 0.25, thickness = 0.02;
    const Vec3 n = normal_from_dip(30.0, 110.0);
    BlockGenerator generator(ConvexPolyhedron::box(Vec3::Zero(), Vec3::Ones()), {});
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
    const std::vector<BlockTetrahedra> meshes =
        mesh_convex_blocks(model, {slab}, [h](const Vec3&) { return h; });
    const talus_test::BlockShape shape = talus_test::block_shape(model, slab);
    std::printf("thin slab: %u faces, %.2g m thick\n",
                model.face_start[slab + 1] - model.face_start[slab], thickness);
    const auto figures = talus_test::report_meshes("thin slab", model, meshes, {slab}, h);
    std::fprintf(stderr, "thin slab: %u zones, worst radius ratio %.3g\n", figures[0].zones,
                 figures[0].quality.front());
    std::printf("  its shape forces flat zones (thickness %.2g h, below h/4): %s\n", thickness / h,
                talus_test::verdict(shape.forces_slivers(figures[0].width, h)));
  }
  {
    // A cube of side 2 m turned about an oblique axis; its edges and six
    // corners cut off by planes at 1.25 m and 1.5 m from its centre.
    const double h = 0.3;
    unsigned int inner = 0;
    const BlockModel model = talus_test::many_faced_block(inner);
    const std::vector<BlockTetrahedra> meshes =
        mesh_convex_blocks(model, {inner}, [h](const Vec3&) { return h; });
    std::printf("block of %u faces\n", model.face_start[inner + 1] - model.face_start[inner]);
    talus_test::report_meshes("24-faced block", model, meshes, {inner}, h);
  }
}
