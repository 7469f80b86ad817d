#pragma once

// Internal to source/run: what a stage changed that a saved state does not
// hold, set again (block_cycle.cc; a stage's factor of safety builds its
// trials with it, stage_factor_of_safety.cc).

#include <talus/model/block_model.h>
#include <talus/run/rank_share.h>
#include <talus/scene/block_system.h>
#include <talus/scene/scene.h>

namespace talus
{

/// What a checkpoint (or a saved state) does not hold of a stage's
/// changes (rock materials, boundaries, water), set again on `system` after
/// its state was loaded; `built`: the blocks as built, where a stage's face
/// loads are selected. On ranks (`share`), each rank takes the face loads
/// of the blocks it holds, from `table` (the whole model's, relative to
/// each block: RigidFaceLoads::relative_to) when it is given.
void restore_changes(const Scene& scene, const BlockModel& model, const BlockModel* built,
                     BlockSystem& system, const StageSpec& stage, const RankShare* share = nullptr,
                     const RigidFaceLoads* table = nullptr);

/// The zones' material a stage's change of rock `c` gives a group.
ZoneMaterial stage_zone_material(const Scene& scene, const RockMaterialChange& c);

} // namespace talus
