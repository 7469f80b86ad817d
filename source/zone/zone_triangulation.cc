#include <talus/zone/zone_triangulation.h>

#include <deal.II/grid/tria.h>

#include <stdexcept>

namespace talus
{

std::shared_ptr<dealii::Triangulation<3, 3>> build_zone_triangulation(const TetMesh& mesh)
{
  std::vector<dealii::Point<3>> vertices(mesh.n_gridpoints());
  for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
    vertices[g] =
        dealii::Point<3>(mesh.position[3 * g], mesh.position[3 * g + 1], mesh.position[3 * g + 2]);
  std::vector<dealii::CellData<3>> cells(mesh.n_zones(), dealii::CellData<3>(4));
  for (unsigned int z = 0; z < mesh.n_zones(); ++z)
  {
    for (unsigned int i = 0; i < 4; ++i)
      cells[z].vertices[i] = mesh.zone_gridpoint[z][i];
    cells[z].material_id = mesh.zone_block[z];
  }
  auto tria = std::make_shared<dealii::Triangulation<3, 3>>();
  tria->create_triangulation(vertices, cells, dealii::SubCellData());
  // Output and zone data are indexed by zone and gridpoint; a cell or
  // vertex that deal.II renumbered would silently scramble them.
  for (const auto& cell : tria->active_cell_iterators())
  {
    const auto z = cell->active_cell_index();
    for (unsigned int i = 0; i < 4; ++i)
      if (cell->vertex_index(i) != mesh.zone_gridpoint[z][i])
        throw std::logic_error("deal.II renumbered the zones of the deformable blocks");
  }
  return tria;
}

} // namespace talus
