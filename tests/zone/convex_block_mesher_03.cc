// Patch tests on a jointed convex block meshed by mesh_convex_block (gmsh):
// the larger block of a unit cube cut by one oblique joint (7 faces), at
// h = 0.2 m (block_patch_tests.h). The traction patch holds only if the
// mesh's surface is the block's, so it checks the snapping of gmsh's
// gridpoints onto the block's faces.

#include <talus/base/parallel_environment.h>
#include <talus/zone/convex_block_mesher.h>

#include "block_patch_tests.h"

using namespace talus;

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  const double h = 0.2;
  unsigned int block = 0;
  const BlockModel blocks = block_patch::cut_cube(block);
  const BlockTetrahedra zones = mesh_convex_block(blocks, block, [h](const Vec3&) { return h; });
  block_patch::run(blocks, block, h, zones, block_patch::Hold::boundary_thirds);
}
