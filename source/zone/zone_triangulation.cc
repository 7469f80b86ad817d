#include <talus/zone/zone_triangulation.h>

#include <deal.II/grid/tria.h>

#include <stdexcept>

namespace talus
{

std::unique_ptr<dealii::Triangulation<3, 3>>
build_zone_triangulation(const std::vector<double>& position,
                         const std::vector<std::array<unsigned int, 4>>& tetrahedra,
                         const std::vector<unsigned int>& block)
{
  std::vector<dealii::Point<3>> vertices(position.size() / 3);
  for (std::size_t g = 0; g < vertices.size(); ++g)
    vertices[g] = dealii::Point<3>(position[3 * g], position[3 * g + 1], position[3 * g + 2]);
  std::vector<dealii::CellData<3>> cells(tetrahedra.size(), dealii::CellData<3>(4));
  for (std::size_t k = 0; k < tetrahedra.size(); ++k)
  {
    for (unsigned int i = 0; i < 4; ++i)
      cells[k].vertices[i] = tetrahedra[k][i];
    cells[k].material_id = block[k];
  }
  auto tria = std::make_unique<dealii::Triangulation<3, 3>>();
  tria->create_triangulation(vertices, cells, dealii::SubCellData());
  for (const auto& cell : tria->active_cell_iterators())
    for (unsigned int i = 0; i < 4; ++i)
      if (cell->vertex_index(i) != tetrahedra[cell->active_cell_index()][i])
        throw std::logic_error("deal.II renumbered the zones of the deformable blocks");
  return tria;
}

} // namespace talus
