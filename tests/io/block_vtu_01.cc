// The VTU writer in ASCII: a unit cube and a tetrahedron as two VTK polyhedron cells.
// The file is printed whole so that any change of format shows in the diff;
// the PVD series lists its files with their times.

#include <talus/io/block_vtu_writer.h>

#include <fstream>
#include <iostream>

int main()
{
  using namespace talus;
  BlockModel model;
  const unsigned int rock = model.group_index("rock");
  const unsigned int key = model.group_index("key");
  model.add_block(ConvexPolyhedron::box(Vec3(0, 0, 0), Vec3(1, 1, 1)), rock);
  model.add_block(
      ConvexPolyhedron::tetrahedron(Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1), Vec3(0, 0, 2)), key);
  write_blocks_vtu("blocks.vtu", model, {{"velocity", 3, {1, 2, 3, 4, 5, 6}}}, VtuEncoding::ascii);
  PvdSeries series("blocks.pvd");
  series.add(0.0, "blocks.vtu");
  series.add(0.5, "blocks_1.vtu");
  for (const char* name : {"blocks.vtu", "blocks.pvd"})
  {
    std::ifstream in(name);
    std::cout << "---- " << name << '\n' << in.rdbuf();
  }
}
