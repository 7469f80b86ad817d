#pragma once

#include <array>
#include <memory>
#include <vector>

namespace dealii
{
template <int dim, int spacedim>
class Triangulation;
}

namespace talus
{

/// One deal.II triangulation of simplices holding the given tetrahedra of
/// every deformable block: cell k is tetrahedron k (four gridpoints each),
/// vertex g is gridpoint g at `position` (3 per gridpoint, m), and
/// material_id is `block` of the cell. Blocks share no gridpoint, so each is
/// its own component. Throws if deal.II does not keep the numbering, on
/// which all data written through it depend.
std::unique_ptr<dealii::Triangulation<3, 3>>
build_zone_triangulation(const std::vector<double>& position,
                         const std::vector<std::array<unsigned int, 4>>& tetrahedra,
                         const std::vector<unsigned int>& block);

} // namespace talus
