#pragma once

#include <talus/zone/tet_mesh.h>

#include <memory>

namespace talus
{

/// One deal.II triangulation of simplices holding the zones of every
/// deformable block: cell z is zone z, vertex g is gridpoint g, and each
/// block is its own component (no shared vertices) with material_id = block
/// id. deal.II's tools (DataOut, DoFHandler) work on it; the explicit cycle
/// reads the flat TetMesh arrays. Throws if deal.II does not keep the
/// numbering.
std::shared_ptr<dealii::Triangulation<3, 3>> build_zone_triangulation(const TetMesh& mesh);

} // namespace talus
