#pragma once

#include <talus/base/output_format.h>
#include <talus/geometry/block_generator.h>
#include <talus/geometry/region.h>
#include <talus/solver/deformable_solver.h>
#include <talus/solver/rigid_solver.h>
#include <talus/solver/strength_reduction.h>
#include <talus/zone/edge_length_field.h>
#include <talus/zone/lattice_block_mesher.h>

#include <algorithm>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace talus
{

/// One joint plane (as opposed to a set of parallel joints).
struct JointPlaneSpec
{
  double dip = 0.0;           ///< degrees
  double dip_direction = 0.0; ///< degrees clockwise from north
  Vec3 origin = Vec3::Zero(); ///< m, a point on the plane
  bool limited = false;       ///< only blocks with centroid in `extent`
  Box extent;
};

/// A named selection: blocks whose centroid lies in `region` join `name`,
/// or, when `blocks` lists block numbers (as built), those blocks.
struct GroupSpec
{
  std::string name;
  ConvexRegion region;
  std::vector<unsigned int> blocks;
  std::string section; ///< "Group N"
  /// 'Side of joint': "Joint N" or "Joint set N" (empty: none). The
  /// region then keeps only the side of that joint's plane (of its joint
  /// `joint_index` for a set) that `above` says; read_scene makes it so.
  std::string side_of;
  long joint_index = 0;
  bool above = true;
};

/// A 'Group contact N': contacts between blocks of groups `a` and `b` that
/// lie on no joint with a material take material `material`.
struct GroupContactSpec
{
  std::string a, b;
  unsigned char material = 0;
  std::string section; ///< "Group contact N"
};

/// A region to remove from the model, with a description for the summary.
struct ExcavationSpec
{
  ConvexRegion region;
  std::string description;
  std::string section; ///< its subsection, "Excavation N"
};

/// A joint set or single joint that takes another joint material at a
/// stage's start ("Joint set 2 = weak").
struct JointMaterialChange
{
  int origin = 0; ///< BlockModel::joint_set_origin(i) or joint_origin(j)
  unsigned char material = 0;
};

/// Contacts between blocks of groups `a` and `b` that lie on no joint with
/// a material take `material` from a stage's start ("Group contacts").
struct GroupContactChange
{
  std::string a, b;
  unsigned char material = 0;
};

/// A group whose blocks take another rock material at a stage's start
/// ("joints = grout").
struct RockMaterialChange
{
  std::string group;
  int material = -1; ///< index into Scene::rock_materials; -1: 'Material' and 'Deformable'
};

/// The 'Boundary N' and 'Load N' in force: those of the file, then as the
/// stages add, replace and release them.
struct BoundarySet
{
  std::vector<GridpointCondition> gridpoint_conditions;
  std::vector<FacePressure> face_pressures;
  std::vector<BlockLoad> loads;
  /// The subsection of each ("Boundary 2", or "Stage 3 / Boundary 2" for
  /// one a stage gave); a stage's 'Boundary 2' replaces any 'Boundary 2'.
  std::vector<std::string> gridpoint_condition_sections, face_pressure_sections, load_sections;
  std::vector<std::string> load_groups; ///< group name of each load
};

/// A 'Stage N': what changes at its start, and how its calculation runs.
/// The stages run in order after the model is built; a scene without any
/// is one stage with the settings of 'Solver'.
struct StageSpec
{
  std::string section; ///< "Stage N"
  std::string name;    ///< its 'Name'
  bool dynamic = false;
  /// 'Mode = factor of safety': the strength reduction search from the
  /// state the stage starts in (its steps and target ratio per trial); the
  /// model goes on unchanged.
  bool factor_of_safety = false;
  unsigned long steps = 0;   ///< step limit of this stage
  double target_ratio = 0.0; ///< statics: stop below this ratio (0: never)
  double time_limit = 0.0;   ///< s of model time this stage may take (0: no limit)
  /// Groups whose blocks are removed at the start.
  std::vector<std::string> excavate_groups;
  /// Regions removed at the start: the model is cut along their boundaries
  /// when it is built, and the blocks (zones of a meshed body) whose
  /// centroid lies inside are removed.
  std::vector<ExcavationSpec> excavations;
  std::vector<std::string> fix_groups, free_groups;
  bool reset_displacements = false;
  std::vector<JointMaterialChange> joint_materials;
  std::vector<RockMaterialChange> rock_materials;
  std::vector<GroupContactChange> group_contacts;
  /// Its 'Boundary M' and 'Load M' (each added, or replacing the one of
  /// that name) and its 'Release' list changed the boundaries and loads.
  bool changes_boundaries = false;
  /// The boundaries and loads in force during the stage (all of them).
  BoundarySet boundaries;
  /// What changed, for the summary ("Boundary 3 added", ...).
  std::vector<std::string> boundary_changes;
  /// Its 'Water' subsection: the water from the stage's start (in place of
  /// that of the file or of an earlier stage).
  bool changes_water = false;
  WaterSpec water;
};

/// Which blocks are deformable and what they are made of.
struct DeformableSpec
{
  std::vector<std::string> groups;     ///< groups whose blocks are meshed into zones
  EdgeLengthField edge_length;         ///< m, target zone edge (uniform or graded)
  ZoneMaterial material;               ///< density taken from 'Material'
  std::string mesh_file;               ///< gmsh file of the body's zones (empty: mesh the block)
  std::shared_ptr<const TetMesh> mesh; ///< the zones read from mesh_file (block 0)
  bool implicit_check = false;         ///< compare a static run with the implicit elastic solve
  /// Blocks of these groups take nodal mixed discretization (eqs. 68-76)
  /// when `material.nodal_mixed` does not give it to every block.
  std::vector<std::string> nodal_mixed_groups;
  /// Mesher of the convex blocks that are not axis-aligned bricks.
  ConvexMesher mesher = ConvexMesher::automatic;

  /// Whether the zones of a block of group `group` have nodal mixed
  /// discretization.
  bool nodal_mixed(const std::string& group) const
  {
    return material.nodal_mixed || std::find(nodal_mixed_groups.begin(), nodal_mixed_groups.end(),
                                             group) != nodal_mixed_groups.end();
  }
};

/// A 'Rock material N': what the blocks of its groups are made of.
struct RockMaterialSpec
{
  std::string name;
  std::vector<std::string> groups;
  double density = 2600.0; ///< kg/m^3, rigid and deformable blocks
  ZoneMaterial zone;       ///< deformable blocks (element and nodal mixed from 'Deformable')
  std::string section;     ///< "Rock material N"
};

/// A 'Boundary N' of held gridpoints whose reaction (the force the
/// support takes, N) goes to the history and the summary: on the
/// components this boundary holds only (a roller of another boundary in
/// its box takes the other components).
struct ReactionReport
{
  std::string name; ///< "Boundary N"
  ConvexRegion region;
  bool held[3] = {true, true, true}; ///< its 'Held components'
};

struct OutputSettings
{
  std::string directory = "output"; ///< created if missing
  std::string base_name = "talus";  ///< prefix of every file written
  bool write_vtu = true;
  VtuEncoding vtu_encoding = VtuEncoding::binary; ///< of every VTU file written
  unsigned long checkpoint_interval = 0; ///< steps between checkpoints (0: only on a signal)
};

/// Everything a parameter file describes, as plain values; built by
/// read_scene(), which has already checked every value.
struct Scene
{
  std::string parameter_file;
  Box brick;
  double density = 2600.0; ///< kg/m^3
  CuttingSettings cutting;
  std::vector<JointSetSpec> joint_sets;
  std::vector<JointPlaneSpec> joint_planes;
  std::vector<std::string> joint_set_sections;   ///< "Joint set N" of each joint set
  std::vector<std::string> joint_plane_sections; ///< "Joint N" of each joint plane
  /// Name of each joint material: "default" ('Joint properties', material
  /// 0, solver.joint), then those of 'Joint material N' (solver.joint_materials).
  std::vector<std::string> joint_material_names{"default"};
  /// Resolved into solver.joint_rule by resolve_group_names.
  std::vector<GroupContactSpec> group_contacts;
  std::vector<ExcavationSpec> excavations;
  /// The 'Stage N' in order (empty: one stage, 'Solver').
  std::vector<StageSpec> stages;
  std::string default_group = "rock";
  std::vector<GroupSpec> groups;
  OutputSettings output;
  /// The calculation (steps = 0: build and write the model only).
  SolverSettings solver;
  /// 'Mode' = factor of safety: the search and its settings.
  StrengthReductionSettings strength_reduction;
  std::vector<std::string> fixed_groups; ///< names; resolved to solver.fixed_groups
  /// m: the blocks containing or nearest to these points join
  /// solver.history_blocks (resolve_history_blocks).
  std::vector<Vec3> history_block_points;
  std::vector<std::string> load_groups;   ///< group name of each solver.loads entry
  std::vector<std::string> load_sections; ///< "Load N" of each solver.loads entry
  DeformableSpec deformable;
  /// Groups made of a material of their own; the others take 'Material'
  /// and the constants of 'Deformable'.
  std::vector<RockMaterialSpec> rock_materials;
  const RockMaterialSpec* rock_material_of(const std::string& group) const
  {
    for (const RockMaterialSpec& r : rock_materials)
      if (std::find(r.groups.begin(), r.groups.end(), group) != r.groups.end())
        return &r;
    return nullptr;
  }
  /// kg/m^3 of the blocks of `group`.
  double density_of(const std::string& group) const
  {
    const RockMaterialSpec* r = rock_material_of(group);
    return r != nullptr ? r->density : density;
  }
  std::vector<GridpointCondition> gridpoint_conditions; ///< from 'Boundary N' (velocity)
  std::vector<FacePressure> face_pressures;             ///< from 'Boundary N' (pressure)
  std::vector<ReactionReport> reactions;                ///< 'Boundary N' with 'Report reaction'
  /// "Boundary N" of each gridpoint condition and of each face pressure.
  std::vector<std::string> gridpoint_condition_sections, face_pressure_sections;
  bool has_initial_stress = false;
  InitialStress initial_stress;
  /// The parameters as used, every entry with its value (defaults included).
  std::string used_parameters;
  /// Line in the parameter file of each subsection ("Joint set 1") and of
  /// each entry it sets ("Joint set 1 / Spacing"), for messages about
  /// problems found once the blocks exist (scene_error).
  std::map<std::string, unsigned int> lines;
  /// The included file that holds a key of `lines`, when not parameter_file.
  std::map<std::string, std::string> line_files;
  /// Input that is legal but surely not meant (an entry the run ignores),
  /// as "file:line: entry ...: ..."; printed by check_built_model.
  std::vector<std::string> warnings;
};

/// Reads and checks a parameter file. Throws InputError with file, line,
/// entry, the problem and what is allowed for the first thing wrong. With
/// `prepare_output`, also creates the output folder (after every check has
/// passed) and fails if it cannot be written.
Scene read_scene(const std::string& filename, bool prepare_output = true);

/// The stages a run of `scene` goes through: its 'Stage N', or one made of
/// 'Solver' when it has none.
std::vector<StageSpec> stages_to_run(const Scene& scene);

/// The steps of every stage of `scene` added up (0: the model only).
unsigned long steps_to_run(const Scene& scene);

} // namespace talus
