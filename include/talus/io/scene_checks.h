#pragma once

#include <talus/base/exceptions.h>
#include <talus/scene/build_blocks.h>
#include <talus/scene/model_digest.h>
#include <talus/scene/scene.h>
#include <talus/zone/tet_mesh.h>

#include <string>

namespace talus
{

/// Largest model talus builds: about 1 KB per block and 620 bytes per zone
/// while meshing, so that a mistyped spacing or edge length is refused with
/// a message instead of taking the machine's memory for hours.
constexpr double max_blocks = 1e7;
constexpr double max_zones = 3e7;

/// Memory estimates (bytes) checked against the memory the machine has
/// left before anything is built: a block with its contacts and
/// sub-contacts in a run (about 1 KB for the block, 12 contacts of about
/// 100 bytes and 40 sub-contacts of about 160 bytes, measured by
/// benchmark_rigid_settling), a block that is only built and written, and
/// a 4-node zone while meshing (the peak of benchmark_zone_cycle; a
/// 10-node zone takes about four times as much).
constexpr double bytes_per_running_block = 10e3;
constexpr double bytes_per_built_block = 2e3;
constexpr double bytes_per_zone = 650.0;

/// An InputError about `entry` of subsection `section` (or about the whole
/// subsection when `entry` is empty), at its line in the parameter file.
InputError scene_error(const Scene& scene, const std::string& section, const std::string& entry,
                       const std::string& problem, const std::string& allowed);

/// Before any block is cut: refuses joint sets that would cut the brick into
/// more than max_blocks blocks (estimated from the number of joints of each
/// set that cross the brick), or into more than the memory left holds.
void check_model_size(const Scene& scene);

/// Once the blocks exist, before anything is meshed or written: refuses a
/// scene that cannot work with them - a joint set or joint that cuts
/// nothing, an excavation that removes nothing or everything, history
/// blocks that do not exist, deformable groups with no block, a mesh file
/// for a scene of several blocks, a zone edge length larger than every
/// deformable block, or more zones than max_zones or than the memory left
/// holds; fixed or loaded groups with no block. Then prints the scene's
/// warnings ("Warning: ...").
/// `model`: the digest of the whole model; `whole`: the whole model, needed
/// (and only read) when the scene has deformable blocks.
void check_built_model(const Scene& scene, const ModelDigest& model, const BuildReport& report,
                       const BlockModel* whole);

/// The zones meshing the deformable blocks will make, and the memory that
/// takes, estimated from each block's volume and the edge length before
/// anything is meshed (count_zones); zero for a scene whose zones come from
/// a mesh file.
struct ZoneEstimate
{
  double zones = 0.0, bytes = 0.0;
  std::size_t blocks = 0;
  bool quadratic = false;
};
ZoneEstimate estimate_zones(const Scene& scene, const BlockModel& model);

/// Once the deformable blocks are meshed (`mesh`: their zones, empty when
/// every block is rigid), before the run: refuses a 'Boundary N' that
/// selects nothing - a fixed, velocity or load boundary whose box holds no
/// gridpoint, a pressure or traction boundary whose box holds the centroid
/// of no boundary face of the zones and no part of a rigid block's face -
/// naming it; those of every stage too.
void check_boundary_selections(const Scene& scene, const BlockModel& model, const TetMesh& mesh);
/// The same for one set of boundaries (the file's, or a stage's).
void check_boundary_selections(const Scene& scene, const BlockModel& model, const TetMesh& mesh,
                               const BoundarySet& set);
/// The same on a model's digest (ModelDigest with face loads): a rank that
/// holds only its region checks the whole model's faces.
void check_boundary_selections(const Scene& scene, const ModelDigest& model, const TetMesh& mesh);

} // namespace talus
