#pragma once

#include <talus/scene/scene.h>
#include <talus/solver/deformable_solver.h>
#include <talus/solver/rigid_solver.h>
#include <talus/zone/block_mesher.h>

#include <memory>
#include <vector>

namespace talus
{

/// The calculation of a scene with rigid blocks, deformable blocks or both:
/// the deformable blocks' zones and their solver (none when every block is
/// rigid) and the block solver that runs the cycle and the contacts.
/// PETSc must be initialised when the scene has deformable blocks.
struct BlockSystem
{
  TetMesh mesh;
  MeshReport mesh_report;
  std::vector<unsigned int> deformable_blocks;
  std::vector<int> vertex_gridpoint;
  std::unique_ptr<DeformableSolver> zones;
  std::unique_ptr<RigidSolver> solver;
};

/// Whether a joint set or joint has a water pressure of its own, from the
/// start or from a stage.
bool has_joint_pressures(const Scene& scene);

/// The order of each deformable block's zones: in columns for a block with
/// nodal mixed discretization (its strain increments then wait in cache
/// between the two stages, DeformableSolver::plan_nodal_mixed), in slabs
/// otherwise (mesh_order.h).
BlockMeshOrder deformable_zone_order(const Scene& scene, const BlockModel& model);

/// The materials of a scene's zones and each zone's index into them: the
/// scene's material, with E scaled for the blocks of 'Stiffness ratio
/// groups' and nodal mixed discretization for the blocks of 'Nodal mixed
/// groups' (or all, with 'Nodal mixed discretization'). Only the
/// combinations that some zone takes are listed, so that a scene without
/// nodal mixed zones plans none.
struct ZoneMaterials
{
  std::vector<ZoneMaterial> materials;
  std::vector<unsigned int> of_zone;
};
ZoneMaterials zone_materials(const Scene& scene, const BlockModel& model, const TetMesh& mesh);

/// Meshes blocks `which` of `model` with the scene's zone edge length and
/// element (entry 'Element'), in deformable_zone_order; an InputError of
/// the mesher is given the parameter file's name. With a `comm` of several
/// ranks, they share the meshing (mesh_blocks) and each gets the whole mesh.
TetMesh mesh_deformable_blocks(const Scene& scene, const BlockModel& model,
                               const std::vector<unsigned int>& which, MeshReport& report,
                               MPI_Comm comm = MPI_COMM_SELF);

/// Meshes the blocks of the scene's deformable groups, gives them their zone
/// surfaces as shapes in `model` (which it changes) and builds the solvers.
/// `scene` and `model` must outlive the result.
BlockSystem build_block_system(const Scene& scene, BlockModel& model);

} // namespace talus
