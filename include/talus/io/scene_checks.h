#pragma once

#include <talus/base/exceptions.h>
#include <talus/io/scene.h>
#include <talus/model/build_blocks.h>
#include <talus/zone/tet_mesh.h>

#include <string>

namespace talus
{

/// Largest model talus builds: about 1 KB per block and 620 bytes per zone
/// while meshing, so that a mistyped spacing or edge length is refused with
/// a message instead of taking the machine's memory for hours.
constexpr double max_blocks = 1e7;
constexpr double max_zones = 3e7;

/// An InputError about `entry` of subsection `section` (or about the whole
/// subsection when `entry` is empty), at its line in the parameter file.
InputError scene_error(const Scene& scene, const std::string& section, const std::string& entry,
                       const std::string& problem, const std::string& allowed);

/// Before any block is cut: refuses joint sets that would cut the brick into
/// more than max_blocks blocks (estimated from the number of joints of each
/// set that cross the brick).
void check_model_size(const Scene& scene);

/// Once the blocks exist, before anything is meshed or written: refuses a
/// scene that cannot work with them - a joint set or joint that cuts
/// nothing, an excavation that removes nothing or everything, history
/// blocks that do not exist, deformable groups with no block, a mesh file
/// for a scene of several blocks, a zone edge length larger than every
/// deformable block, or more zones than max_zones.
void check_built_model(const Scene& scene, const BlockModel& model, const BuildReport& report);

/// Once the deformable blocks are meshed (`mesh`: their zones, empty when
/// every block is rigid), before the run: refuses a 'Boundary N' that
/// selects nothing - a fixed, velocity or load boundary whose box holds no
/// gridpoint, a pressure or traction boundary whose box holds the centroid
/// of no boundary face of the zones and no part of a rigid block's face -
/// naming it.
void check_boundary_selections(const Scene& scene, const BlockModel& model, const TetMesh& mesh);

} // namespace talus
