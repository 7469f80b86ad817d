#pragma once

#include <talus/contact/block_decomposition.h>
#include <talus/model/block_model.h>
#include <talus/scene/block_system.h>
#include <talus/scene/scene.h>
#include <talus/zone/block_mesher.h>
#include <talus/zone/tet_mesh.h>

#include <mpi.h>

#include <memory>
#include <unordered_map>
#include <vector>

namespace talus
{

class RankShare;
struct PointHistory;

/// The deformable blocks of a whole model with other blocks, meshed alike
/// on every MPI rank (as one run meshes them) before the model is split
/// among the ranks (issue 24). Kept through the run: deformable blocks that
/// change rank split it again (move_zones_on_ranks).
struct WholeZones
{
  TetMesh mesh; ///< gridpoint_block, zone_block: blocks of the whole model
  MeshReport report;
  /// Per vertex of the whole model (its deformable blocks' faces being
  /// their zones' surfaces): the gridpoint of `mesh` there, -1 on rigid blocks.
  std::vector<int> vertex_gridpoint;
  /// The whole model's vertex_start: block b's vertices are
  /// [vertex_start[b], vertex_start[b + 1]).
  std::vector<unsigned int> vertex_start;
  /// What made each boundary face of `mesh`, then each second-overlay face
  /// (zone_face_origins, on the blocks as built), when a joint has a water
  /// pressure of its own; else empty.
  std::vector<int> face_origins;
  /// Zones of each block of the whole model (0 for a rigid one): the work
  /// that the split among ranks balances.
  std::vector<double> zones_of_block;
  /// The blocks as built, before the surfaces replaced the deformable
  /// blocks' faces, when a stage needs them (else empty).
  BlockModel as_built;
  /// Wall time of the meshing and of giving the blocks their surfaces (s),
  /// for the summary's set-up time.
  double meshing_seconds = 0.0;
};

/// On several MPI ranks, for a scene whose deformable blocks lie among
/// other blocks: meshes every deformable block of `whole` and gives them
/// their zone surfaces in `whole` (printing the summary's estimate first,
/// as one run does). Null on one rank, or without deformable blocks, or
/// when the only block is deformable (a body alone: BodyCycle).
std::unique_ptr<WholeZones> mesh_zones_on_ranks(const Scene& scene, BlockModel& whole);

/// What a rank's cycle keeps of its zones' split: the global block of each
/// of its zones and gridpoints (local numbers change when blocks move
/// between ranks), the whole mesh's gridpoint numbering by blocks, and the
/// history points it reports.
struct RankZones
{
  std::vector<unsigned int> zone_global_block, gridpoint_global_block;
  /// Runs of the whole mesh's gridpoints: each run's first gridpoint and
  /// its block (global number), ascending.
  std::vector<unsigned int> run_first, run_block;
  /// Per history point: the local gridpoint (owned) and zone this rank
  /// reports, -1 where another rank does.
  std::vector<int> point_gridpoint, point_zone;
  /// Per local zone: its number in the whole mesh (ascending).
  std::vector<unsigned int> zone;
  /// The deformable blocks of other ranks whose surfaces this rank holds
  /// as ghost gridpoints (global numbers, ascending): a checkpoint keeps
  /// them, so that a restart splits the zones as the run had them.
  std::vector<unsigned int> surfaces;

  /// The global block of gridpoint `g` of the whole mesh.
  unsigned int block_of_whole_gridpoint(unsigned int g) const;
  /// The mesh's blocks as local numbers of `share` again (after blocks
  /// moved between ranks); a ghost gridpoint of a block no longer held
  /// gets block 0 (nothing reads it: its owner moves it, no contact uses it).
  void renumber(TetMesh& mesh, const RankShare& share) const;
};

/// The calculation of this rank's share (`share`, whose local model is
/// `local`) of a model whose deformable blocks (`zones`, of `whole`) lie
/// among others: the zones of the deformable blocks the rank owns, on their
/// gridpoints, then as ghost entries the surface gridpoints of the
/// deformable ghosts, refreshed from their owners after each motion, on
/// which the contacts act (GridpointShare). `history_points`: the scene's,
/// whose reporting ranks `kept` receives with the rest. `saved_surfaces`:
/// on a restart, the surfaces the rank held at its checkpoint (else those
/// near its blocks as built). Collective on the share's ranks.
BlockSystem build_block_system_on_ranks(const Scene& scene, const BlockModel& whole,
                                        BlockModel& local, const WholeZones& zones,
                                        const RankShare& share, RankZones& kept,
                                        const std::vector<unsigned int>* saved_surfaces = nullptr);

/// A rank's zones split again (move_zones_on_ranks): the new mesh, its
/// solver, and the surfaces on its gridpoints (BlockMigration::ZonesMoved).
struct MovedZones
{
  std::unique_ptr<TetMesh> mesh; ///< blocks by local numbers of the new share
  std::unique_ptr<DeformableSolver> solver;
  std::vector<int> vertex_gridpoint;
  std::unordered_map<unsigned int, std::vector<int>> held_surfaces;
};

/// When deformable blocks change rank (BlockMigration::ZoneRebuild): the
/// zones of `zones` split again for the blocks `next` holds (its model
/// `next_model`, as the blocks are now), `held_before` being the blocks
/// held until now and `before` this rank's solver until now. The surfaces
/// held are chosen as at the start, from the boxes as they are now (those
/// of the deformable blocks are sent to every rank). The new solver takes
/// the state (move_zone_state); `kept` is updated (`points`: the history
/// points as the whole mesh has them). Then the stages'
/// changes of the zones must be set again (BlockCycle). Collective.
MovedZones move_zones_on_ranks(const Scene& scene, const WholeZones& zones,
                               const PointHistory& points, const DeformableSolver& before,
                               RankZones& kept, const RankBlocks& held_before,
                               const RankBlocks& next, const BlockModel& next_model, double reach,
                               MPI_Comm comm);

/// Appends to `row` the history points' values (the columns of `points`)
/// of zones split among the ranks of `comm`: point k's displacement,
/// velocity and pore pressure from the rank whose local gridpoint
/// `point_gridpoint[k]` it is, its stress from the one whose local zone
/// `point_zone[k]` it is (-1 elsewhere). Collective.
void add_point_values_on_ranks(std::vector<double>& row, const DeformableSolver& zones,
                               const PointHistory& points, const std::vector<int>& point_gridpoint,
                               const std::vector<int>& point_zone, MPI_Comm comm);

} // namespace talus
