#pragma once

// The lines of a run's summary that more than one kind of cycle prints, and
// the records they share: zone frames for ParaView and history points.

#include <talus/io/block_vtu_writer.h>
#include <talus/io/zone_vtu_writer.h>
#include <talus/model/block_model.h>
#include <talus/scene/model_digest.h>
#include <talus/scene/scene.h>
#include <talus/solver/deformable_solver.h>
#include <talus/zone/block_mesher.h>

#include <string>
#include <vector>

namespace talus
{

/// How the zones' edge length was asked for, for the summary.
std::string edge_length_text(const EdgeLengthField& f);

/// The summary's lines on the zones' shapes: the radius ratio (1 for a
/// regular tetrahedron), where the poor zones are, and the gridpoint that
/// sets the stable step of eq. 84 (`step_gridpoint`, of `mesh`: see
/// DeformableSolver::time_step_gridpoint) with its worst zone.
void print_mesh_quality(const MeshReport& r, const TetMesh& mesh, unsigned int step_gridpoint,
                        const BlockModel& model);

/// The summary's line on the zones about to be meshed: how many and how much
/// memory, estimated before meshing.
void print_zone_estimate(const Scene& scene, const BlockModel& model);

/// The summary's line on nodal mixed discretization, when some zones have it.
void print_nodal_mixed(const DeformableSolver& solver);

/// The summary's lines on the history blocks, with a warning for a fixed one.
void print_history_blocks(const Scene& scene, const ModelDigest& model);

/// The summary's line on partial density scaling (eq. 89) in a dynamic run
/// with it: gridpoints and blocks given mass, the mass added as a fraction
/// of the total, the largest scaled over true mass. Above 'Added mass
/// limit' throws InputError, or with 'Added mass over limit = warn' prints
/// a warning. `indent` starts each line (a stage's lines).
void print_added_mass(const SolverSettings& s, const AddedMass& added, const char* indent = "");

/// The summary's line on the damping of a dynamic run (nothing when it has
/// none, or is static): Rayleigh's coefficients and the time step `dt` (s)
/// against `dt_without` (s), the step without the stiffness-proportional
/// term; local damping. `indent` starts each line (a stage's lines).
void print_dynamic_damping(const SolverSettings& s, double dt, double dt_without,
                           const char* indent = "");

/// The largest displacement of a gridpoint (m).
double largest_gridpoint_displacement(const DeformableSolver& solver);

/// Writes the zones at their current state as frame `frame` of the zone
/// series; after a divergence (`with_stress` false) non-finite stresses are
/// written as 0.
void write_zone_frame(const Scene& scene, const TetMesh& mesh, const DeformableSolver& solver,
                      ZoneWriter& writer, PvdSeries& series, unsigned int frame,
                      bool with_stress = true);
/// Writes the zones' VTU file at `path`: those of `mesh`, the solver's; or,
/// with `zones`, a piece: `mesh` holds 4-node zones on the solver's
/// gridpoints, its zone k being the solver's zones[k] (split among ranks).
void write_zone_file(const std::string& path, const TetMesh& mesh, const DeformableSolver& solver,
                     ZoneWriter& writer, bool with_stress,
                     const std::vector<unsigned int>* zones = nullptr);

/// History columns of deformable blocks at chosen points: the nearest
/// gridpoint's displacement and velocity, the nearest zone's stress.
struct PointHistory
{
  std::vector<unsigned int> gridpoint, zone;
  /// With water somewhere in the run: a pore pressure column per point
  /// (the water's pressure at its present position, Pa).
  bool water = false;
  double gravity = 9.81; ///< m/s^2, its magnitude

  PointHistory(const TetMesh& mesh, const std::vector<Vec3>& points);
  void add_columns(std::vector<std::string>& columns) const;
  void add_values(std::vector<double>& row, const DeformableSolver& zones) const;
};

/// Whether the scene has water, from the start or from a stage.
bool has_water(const Scene& scene);

/// The pressure of `water` at `x` (Pa): rho_w g (z_w - z) below the
/// phreatic surface, 0 above it or without one.
double pore_pressure(const WaterSpec& water, double gravity, const Vec3& x);

} // namespace talus
