// The convex block mesher (mesh_convex_blocks, gmsh) on a unit cube, the
// cube cut by one oblique joint, and by three oblique joints (every block
// of each), at a target edge length h = 0.25 m. For every block's mesh:
//  - every zone has a positive volume;
//  - the zones' volumes sum to the block's volume to 1e-12;
//  - no zone face is shared by more than two zones, and the faces used once
//    (the mesh's surface) lie on the block's face planes (within 1e-12 of
//    the block's size), facing out, their areas summing to each face's area
//    to 1e-12: the surface of the mesh is the block's surface;
//  - blocks at least 2h wide have 0.5 to 2 times the zones of regular
//    tetrahedra of edge h filling them (regular_tetrahedra_in); a narrower
//    block has no room for a gridpoint h from its faces, so its zones are
//    its faces' triangles joined up, with at most one interior gridpoint;
// and over each model the median normalised radius ratio of blocks at
// least h/2 wide is at least 0.6, zones below 0.1 only in blocks whose
// shape forces them (a face or dihedral angle below 20 degrees, an edge or
// a width below h/4). And the measures radius_ratio and
// regular_tetrahedra_in against closed forms. Verdicts go to standard
// output; counts and qualities to standard error, since gmsh's meshes
// follow the build's rounding.

#include <talus/geometry/block_generator.h>
#include <talus/model/block_model.h>
#include <talus/zone/convex_block_mesher.h>

#include <cmath>
#include <cstdio>
#include <numeric>
#include <string>

#include "../tests.h"
#include "convex_block_mesher_checks.h"

using namespace talus;

namespace
{
void mesh_and_check(const std::string& name, const BlockModel& model, double h)
{
  std::vector<unsigned int> all(model.n_blocks());
  std::iota(all.begin(), all.end(), 0u);
  const std::vector<BlockTetrahedra> meshes =
      mesh_convex_blocks(model, all, [h](const Vec3&) { return h; });
  talus_test::report_meshes(name, model, meshes, all, h);
}
} // namespace

int main()
{
  // The measures themselves, against closed forms: a regular tetrahedron
  // has radius ratio 1 and is the one regular tetrahedron in its volume
  // (edge a: V = a^3 sqrt(2) / 12); the corner tetrahedron (0, e1, e2, e3)
  // has r_in = 1 / (3 + sqrt(3)) and r_circ = sqrt(3) / 2, so 3 r_in / r_circ
  // = 2 / (1 + sqrt(3)); a flat one has 0.
  {
    const double a = 0.3;
    const Vec3 p0(0, 0, 0), p1(a, 0, 0), p2(a / 2, a * std::sqrt(3.0) / 2, 0),
        p3(a / 2, a * std::sqrt(3.0) / 6, a * std::sqrt(2.0 / 3.0));
    talus_test::check("radius ratio of a regular tetrahedron", radius_ratio(p0, p1, p2, p3), 1.0,
                      1e-14);
    talus_test::check("regular tetrahedra of edge a in a^3 sqrt(2)/12",
                      regular_tetrahedra_in(a * a * a * std::sqrt(2.0) / 12.0, a), 1.0, 1e-14);
    talus_test::check("radius ratio of the corner tetrahedron",
                      radius_ratio(p0, Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()),
                      2.0 / (1.0 + std::sqrt(3.0)), 1e-14);
    std::printf("radius ratio of a flat tetrahedron: %s\n",
                talus_test::verdict(radius_ratio(p0, p1, p2, Vec3(0.1, 0.1, 0)) == 0.0));
  }
  const double h = 0.25;
  const ConvexPolyhedron cube = ConvexPolyhedron::box(Vec3::Zero(), Vec3::Ones());
  {
    BlockModel model;
    model.add_block(cube, 0);
    mesh_and_check("unit cube", model, h);
  }
  {
    BlockGenerator generator(cube, {});
    generator.cut_plane(Plane::through(Vec3(0.5, 0.45, 0.55), normal_from_dip(35.0, 60.0)));
    BlockModel model;
    for (const ConvexPolyhedron& b : generator.blocks())
      model.add_block(b, 0);
    mesh_and_check("cube cut by one oblique joint", model, h);
  }
  {
    BlockGenerator generator(cube, {});
    generator.cut_plane(Plane::through(Vec3(0.5, 0.45, 0.55), normal_from_dip(35.0, 60.0)));
    generator.cut_plane(Plane::through(Vec3(0.4, 0.6, 0.5), normal_from_dip(70.0, 150.0)));
    generator.cut_plane(Plane::through(Vec3(0.55, 0.5, 0.4), normal_from_dip(80.0, 250.0)));
    BlockModel model;
    for (const ConvexPolyhedron& b : generator.blocks())
      model.add_block(b, 0);
    mesh_and_check("cube cut by three oblique joints", model, h);
  }
}
