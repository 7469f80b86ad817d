#pragma once

#include <talus/scene/scene.h>
#include <talus/model/block_model.h>

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

/// Turns the group names the scene's solver settings refer to (fixed
/// groups, loads) into the model's group numbers.
void resolve_group_names(Scene& scene, BlockModel& model);

} // namespace talus
