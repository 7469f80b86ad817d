#pragma once

#include <talus/model/block_model.h>
#include <talus/scene/scene.h>

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace talus
{

/// What building the blocks did, for the run summary.
struct BuildReport
{
  CuttingReport cutting;
  std::vector<double> excavated_volume; ///< m^3, one per excavation in order
  /// m^3 inside each stage's excavations, in order (cut, removed later).
  std::vector<double> stage_excavated_volume;
  /// Cuts made and cuts refused by the minimum block volume, per joint set
  /// and per single joint in order (a set that cuts nothing is refused).
  std::vector<std::pair<unsigned long, unsigned long>> joint_set_cuts, joint_cuts;
};

/// Builds the blocks a scene describes: the brick cut by every joint set,
/// then every single joint, then the excavations removed; blocks are put
/// into groups by centroid and every block is checked to be a closed convex
/// polyhedron.
BlockModel build_blocks(const Scene& scene, BuildReport& report);

/// Whether a rank keeps a block: its number in the whole model and its
/// shape.
using KeepBlock = std::function<bool(unsigned int number, const ConvexPolyhedron& block)>;

/// The blocks of build_blocks() that `keep` takes, and only those: the
/// brick is cut one piece at a time (BlockGenerator::cut_depth_first), so
/// the memory held is that of the blocks kept (issue 24: each rank builds
/// its region). Each kept block is as build_blocks() makes it, bit for
/// bit, in its group; `global` gets their numbers in the whole model,
/// ascending, and `n_blocks` the whole model's count. The report is the
/// whole model's. Only kept blocks are checked to be closed convex
/// polyhedra.
BlockModel build_blocks_where(const Scene& scene, BuildReport& report, const KeepBlock& keep,
                              std::vector<unsigned int>& global, unsigned int& n_blocks);

/// A model of no blocks with the scene's groups, numbered as build_blocks
/// numbers them.
BlockModel scene_groups(const Scene& scene);

/// Block `number` of the whole model alone, checked and in its group, as
/// build_blocks makes it from the cut piece `block`.
BlockModel scene_block(const Scene& scene, const ConvexPolyhedron& block, unsigned int number);

/// Turns the group names the scene's solver settings refer to (fixed
/// groups, loads) into the model's group numbers.
void resolve_group_names(Scene& scene, BlockModel& model);

} // namespace talus
