// Patch tests on a jointed convex block meshed by the lattice Delaunay mesher
// (mesh_convex_block_by_lattice), as convex_block_mesher_03 does for gmsh:
// the larger block of a unit cube cut by one oblique joint (7 faces), at
// h = 0.2 m (block_patch_tests.h). The traction patch holds only if the
// mesh's surface is the block's, so it checks that the lattice mesh keeps
// the block's faces (its face and edge gridpoints on their planes, flat
// cells on a face dropped).

#include <talus/base/parallel_environment.h>
#include <talus/zone/lattice_block_mesher.h>

#include "block_patch_tests.h"

using namespace talus;

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  const double h = 0.2;
  unsigned int block = 0;
  const BlockModel blocks = block_patch::cut_cube(block);
  const BlockTetrahedra zones =
      mesh_convex_block_by_lattice(blocks, block, [h](const Vec3&) { return h; });
  block_patch::run(blocks, block, h, zones, block_patch::Hold::first_three_whole);
}
