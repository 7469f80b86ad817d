#pragma once

#include <talus/geometry/plane.h>
#include <talus/model/initial_stress.h>
#include <talus/solver/rigid_face_loads.h> // FacePressure
#include <talus/solver/rigid_solver.h>
#include <talus/zone/gridpoint_share.h>
#include <talus/zone/implicit_elastic.h>
#include <talus/zone/stress_batch.h>
#include <talus/zone/tet10_kernel.h>
#include <talus/zone/tet4_kernel.h>
#include <talus/zone/tet_mesh.h>
#include <talus/zone/zone_material.h>

#include <array>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace talus
{

class CheckpointReader;
class CheckpointWriter;

/// Velocity held on some components of the gridpoints in a region (fixed
/// when it is zero): velocity + velocity_gradient x, with x the
/// gridpoint's initial position (a linear field, for patch tests and
/// boundaries moving with a uniform strain rate).
struct GridpointCondition
{
  ConvexRegion region; ///< the gridpoints (at their initial positions) inside
  bool held[3] = {true, true, true};
  Vec3 force = Vec3::Zero();                                   ///< N on each gridpoint (a load)
  Vec3 velocity = Vec3::Zero();                                ///< m/s
  Eigen::Matrix3d velocity_gradient = Eigen::Matrix3d::Zero(); ///< 1/s
  /// The velocity acts for model times below this (s), then the held
  /// components stay where they are (a displacement applied, then held
  /// while the run settles to a static answer).
  double velocity_until = std::numeric_limits<double>::infinity();
  /// A velocity that varies in model time t: the held velocity times
  /// motion.scale(t); none: constant.
  TimeFunction motion;
};

/// The explicit cycle of deformable blocks: zone forces from the stresses
/// (matrix-free, constant-strain tetrahedra), gridpoint motion (eq. 57) with
/// local damping for statics (eqs. 78-79), the time step of eqs. 84-86, and
/// density scaling for statics. Gridpoint state (position, velocity, force,
/// mass) lives in PETSc vectors; the kernels take their raw arrays once per
/// stage. PETSc must have been initialised (talus::ParallelEnvironment).
class DeformableSolver
{
public:
  /// `material_of_zone[z]` indexes `materials`.
  DeformableSolver(const TetMesh& mesh, std::vector<ZoneMaterial> materials,
                   std::vector<unsigned int> material_of_zone, const SolverSettings& settings,
                   std::vector<GridpointCondition> conditions = {},
                   std::vector<FacePressure> pressures = {}, const InitialStress* initial = nullptr,
                   const GridpointShare* share = nullptr);
  ~DeformableSolver();

  /// Time step of eqs. 84-86 with the true masses (s), with the joint
  /// stiffness of boundary gridpoints (eq. 85, N/m per gridpoint) if given,
  /// lowered for the stiffness-proportional Rayleigh term of dynamics.
  double stable_time_step(const std::vector<double>& joint_stiffness = {}) const
  {
    return stable_time_step(joint_stiffness, s_.stiffness_damping());
  }
  /// The same with the stiffness-proportional coefficient `beta` (s).
  double stable_time_step(const std::vector<double>& joint_stiffness, double beta) const;
  /// The gridpoint whose mass over stiffness is smallest: the one that sets
  /// the stable step of eq. 84 (without joints), for the summary.
  unsigned int time_step_gridpoint() const;

  void step();

  /// The two halves of step(), for a cycle that adds contact forces to the
  /// gridpoints in between: zone forces (with gravity and pressures) into
  /// the force vector, then motion of the gridpoints.
  void compute_forces();
  void move();

  /// The gridpoint arrays (3 numbers per gridpoint) for the length of one
  /// stage: positions (m), velocities (m/s), forces (N).
  class View
  {
  public:
    explicit View(DeformableSolver& solver);
    ~View();
    View(const View&) = delete;
    View& operator=(const View&) = delete;
    double* x = nullptr;
    double* v = nullptr;
    double* f = nullptr;
    /// Forces of Rayleigh's stiffness-proportional term (N, 3 per
    /// gridpoint), kept apart for the energy account; null without it.
    double* damping = nullptr;

  private:
    DeformableSolver& solver_;
    struct Forms; ///< the vectors' local forms (ghosted vectors)
    std::unique_ptr<Forms> forms_;
  };

  /// Sets the time step shared with rigid blocks (s) and adds the joint
  /// stiffness at boundary gridpoints (eq. 85, N/m per gridpoint). Statics
  /// with density scaling: inertial masses k dt^2 / 4 (eq. 84 solved for m),
  /// never below the true mass (so no gridpoint falls faster than the
  /// rigid blocks beside it); otherwise throws when dt exceeds the stable
  /// step of eq. 84.
  void use_time_step(double dt, const std::vector<double>& joint_stiffness);
  /// Steps (statics) until the unbalanced-force ratio is below `ratio`;
  /// returns the steps taken.
  unsigned long run_to_ratio(double ratio, unsigned long max_steps);

  double dt() const { return dt_; }
  /// The step of the gridpoints' last motion (s): their velocities times it
  /// is that motion, though a stage's change of mode has changed dt().
  double motion_dt() const { return motion_dt_; }
  /// What partial density scaling added to the gridpoints (dynamics;
  /// nothing in static stages).
  const AddedMass& added_mass() const { return added_mass_; }
  /// Wall time spent so far in the zone stage (strain, model, nodal forces)
  /// and in the gridpoint stage (motion, damping), s.
  double seconds_zones() const { return seconds_zones_; }
  double seconds_gridpoints() const { return seconds_gridpoints_; }
  double time() const { return time_; }
  unsigned long steps_done() const { return step_; }
  /// Largest unbalanced gridpoint force over the mean gravity force of a
  /// gridpoint (or, without gravity, over the mean zone force magnitude).
  double unbalanced_ratio() const { return ratio_; }
  /// The gridpoint whose unbalanced force sets that ratio (of the last
  /// step); split among ranks, its number in the whole mesh.
  unsigned int unbalanced_gridpoint() const
  {
    return share_ ? ratio_whole_gridpoint_ : ratio_gridpoint_;
  }
  /// The rank's share of the gridpoints (null: the solver has them all).
  const GridpointShare* share() const { return share_.get(); }
  /// The gridpoints this rank moves: the first ones of the mesh (all of
  /// them unless split among ranks).
  unsigned int owned_gridpoints() const { return n_moved_; }
  /// Boundary faces of the zones with a part below the phreatic surface at
  /// the last step (0 without water).
  unsigned int water_faces_below() const { return water_faces_below_; }
  /// The sum of the water forces on the gridpoints at the last step (N).
  const Vec3& water_force() const { return water_force_; }
  /// The same two of the whole model: split among ranks, summed over them
  /// (a collective call; each face counted by one rank).
  std::pair<unsigned long, Vec3> whole_water() const;

  const TetMesh& mesh() const { return mesh_; }
  /// Copies of the gridpoint state (3 per gridpoint).
  std::vector<double> positions() const;
  std::vector<double> displacements() const;
  std::vector<double> velocities() const;
  /// Stresses, 6 per stress point (xx, yy, zz, xy, yz, zx), Pa; the stress
  /// points of zone z are [z p, z p + p), p = stress_points_per_zone() (1 for
  /// 4-node zones, the 4 Gauss points of 10-node zones). Plastic state alike.
  const std::vector<double>& stress() const { return stress_; }
  unsigned int stress_points_per_zone() const { return points_per_zone_; }
  const std::vector<unsigned char>& plastic_state() const { return state_; }
  /// The same problem for the implicit elastic reference solve: gravity and
  /// face pressures (and the water) as nodal forces on the initial geometry, held
  /// components prescribed at zero (only meaningful for elastic zones
  /// without initial stress, held at rest), and the 4-node stiffness that
  /// preconditions it (hexahedral zones' tetrahedra at half weight, 10-node
  /// zones as eight sub-tetrahedra). Its `apply` is left to the caller:
  /// elastic_operator, for the kernels' own discrete problem.
  ImplicitElasticProblem implicit_problem() const;
  /// The linear elastic operator of the explicit kernels as they are
  /// (4-node zones, nodal mixed discretization, hexahedral zones, 10-node
  /// zones): Ku = K u, minus the zone forces (N) of displacements u (m),
  /// both 3 per gridpoint, from the unstressed initial geometry with every
  /// zone elastic; no loads, no boundary conditions. The run's state is
  /// left as it was.
  void elastic_operator(const double* u, double* Ku);

  /// Adds the zones' terms to an energy account: work of gravity and of
  /// boundaries, kinetic energy at the last whole step, damping, and (a
  /// pass over the zones) elastic strain energy and plastic dissipation.
  void add_energy(EnergyAccount& e) const;
  /// The same without the pass over the zones: works, kinetic and initial
  /// energy only (for the divergence watch).
  void add_work(EnergyAccount& e) const;
  /// The same of this rank's gridpoints and zones alone (split among ranks;
  /// the whole model's otherwise).
  void add_own_energy(EnergyAccount& e) const;
  void add_own_work(EnergyAccount& e) const;
  /// Throws DivergenceError if a gridpoint force is not finite (before
  /// anything moves), naming the zone; `step` and `dt` for the message.
  void check_finite_forces(unsigned long step, double dt) const;
  /// Work dissipated so far by the dashpots of quiet boundaries (J; part
  /// of the account's damping dissipation), and the number of zone faces
  /// they act on.
  double quiet_dissipation() const { return quiet_work_; }
  unsigned int quiet_faces() const { return static_cast<unsigned int>(quiet_faces_.size()); }
  /// Largest kinetic energy of one gridpoint (J) and the message of a
  /// divergence there: the zone, and the likely cause.
  double largest_gridpoint_energy() const;
  std::string divergence_site(double dt) const;

  /// Nodal mixed discretization keeps the strain increments of a batch of
  /// zones between its two stages when its model stage comes at most this
  /// many batches (152 KB of scratch each) after its sums stage (see
  /// plan_nodal_mixed); otherwise, or with 0, it takes them twice. The
  /// results are the same either way: for tests and benchmarks. The
  /// longest wait found, in batches: nodal_mixed_lag().
  void set_nodal_mixed_ring_limit(unsigned int batches);
  unsigned int nodal_mixed_lag() const { return nmd_lag_; }
  bool nodal_mixed_keeps_strains() const { return !nmd_ring_.empty(); }
  /// Batches of scratch held for the kept strain increments.
  unsigned int nodal_mixed_ring_batches() const
  {
    return static_cast<unsigned int>(nmd_ring_.size());
  }
  /// The share of batches whose strain increments are kept.
  double nodal_mixed_kept_share() const
  {
    return nmd_batches_.empty() ? 0.0 : double(nmd_kept_) / nmd_batches_.size();
  }
  /// The zones whose material has nodal mixed discretization.
  unsigned int nodal_mixed_zones() const;
  /// Zones with nodal mixed discretization and all zones, of the whole
  /// model (split among ranks: summed over them, a collective call).
  std::array<unsigned long, 2> whole_nodal_mixed_zones() const;

  /// Stages. Removes zones (`gone[z]`, an excavation): they take a null
  /// material (no stiffness, no mass, no stress) and their gridpoints lose
  /// their share of mass and gravity; a gridpoint left without mass is held.
  /// Hexahedral zones go whole (a tetrahedron of one takes its ten).
  void remove_zones(std::vector<char> gone);
  /// Whether zone z was removed.
  bool zone_removed(unsigned int z) const { return !removed_zone_.empty() && removed_zone_[z]; }
  /// Zones `zones[z]` (not removed) take `material` from now on, their
  /// stresses and plastic states kept; masses, gravity and (alone) the
  /// time step follow. With `account`, the energy account's error is kept
  /// as it was (off when a restart sets again what a checkpoint holds).
  /// Hexahedral zones must change whole, with a hex-mixed material.
  void change_material(const std::vector<char>& zones, const ZoneMaterial& material,
                       bool account = true);
  /// Displacements start again from zero at the present positions.
  void reset_displacements();
  /// Static or dynamic from now on (masses and damping; the time step too
  /// when the solver runs alone, else the block solver sets it).
  void set_dynamic(bool dynamic);
  bool dynamic() const { return s_.dynamic; }

  /// Stages: these boundary conditions and face loads from now on, in
  /// place of those before (held gridpoints and loaded faces selected by
  /// their initial positions, as at the start). A component held anew takes
  /// its velocity at the next motion; one let go keeps its velocity. Holds
  /// of hold_gridpoint end; gridpoints of removed zones stay held.
  void set_boundaries(std::vector<GridpointCondition> conditions,
                      std::vector<FacePressure> pressures);

  /// Stages: this water from now on (the phreatic surface's hydrostatic
  /// pressure on every boundary face below it).
  void set_water(const WaterSpec& water);
  const WaterSpec& water() const { return s_.water; }
  /// What made each boundary face (zone_face_origins): the faces on a joint
  /// with a pressure of its own take it ('Joint set pressures').
  void set_face_origins(std::vector<int> origins);

  /// Holds every component of gridpoint g at velocity `v` (m/s) from now on.
  void hold_gridpoint(unsigned int g, const Vec3& v);

  /// Reaction: the sum of the internal forces on the gridpoints of a region
  /// whose motion is held (N); equal and opposite to what the support takes.
  /// Only the components `held` counts (a boundary's own 'Held components';
  /// another boundary's roller in the region holds the others); a component
  /// not held is zero. Summed exactly (ExactSum): a body split among ranks
  /// gives the serial run's bits.
  Vec3 support_force(const ConvexRegion& region, const bool held[3]) const;

  /// Checkpoints: gridpoint positions, velocities, forces and inertial
  /// masses (density-scaled), zone stresses and plastic states, damping,
  /// time and step.
  void save_state(CheckpointWriter& out) const;
  void load_state(CheckpointReader& in);

  /// Deformable blocks that change rank (issue 24; solver/zone_migration.h,
  /// defined in source/solver/zone_state_move.cc). What one gridpoint
  /// carries (the checkpoint's values: position, velocity, force, inertial
  /// mass, reference position, held components and velocities, the last
  /// step's force, the joints' stiffness behind the time step) and what one
  /// zone carries (stresses, plastic state, removed), as records of a fixed
  /// size, appended to `out` for the local gridpoints or zones `which`.
  static std::size_t gridpoint_record_size();
  std::size_t zone_record_size() const;
  void put_gridpoint_records(const std::vector<unsigned int>& which, std::vector<char>& out) const;
  void put_zone_records(const std::vector<unsigned int>& which, std::vector<char>& out) const;
  /// A solver just built on a new split of the same whole mesh takes the
  /// state: every local gridpoint's and zone's record (owned and ghost
  /// gridpoints alike, from their old owners), and what this rank's solver
  /// `before` kept of the run (time, step, time step, mode, damping, its
  /// share of the energy account), as load_state does; the stages' changes
  /// of materials and boundaries are then set again, as after a restart.
  void take_moved_state(const DeformableSolver& before,
                        const std::vector<const char*>& gridpoint_record,
                        const std::vector<const char*>& zone_record);

  /// The damping's running state: the servo of global adaptive damping
  /// (eq. 77) and combined damping's forces of the last step. A checkpoint
  /// holds it; a restart keeps it across the stage changes it sets again
  /// (a rock material remakes the damper for the zones' new masses).
  struct DampingState
  {
    Damper damper;
    std::vector<double> last_force;
  };
  DampingState damping_state() const { return {damper_, last_force_}; }
  /// The time step (s) with what it set (the joint stiffness behind it and
  /// the inertial masses, kg): a restart keeps them too, since deformable
  /// blocks among others take them anew from the joints over the current
  /// face areas, last bits off the stage start's.
  struct StepState
  {
    double dt = 0.0;
    std::vector<double> joint_stiffness, inertial_mass;
    AddedMass added_mass;
  };
  StepState step_state() const;
  void set_step_state(const StepState& state);
  void set_damping_state(DampingState state)
  {
    damper_ = state.damper;
    last_force_ = std::move(state.last_force);
  }

private:
  friend void gather_whole_zones(const DeformableSolver& split,
                                 const std::vector<unsigned int>& split_zone,
                                 DeformableSolver& whole, MPI_Comm comm);
  struct PetscState;
  /// Eq. 84, each gridpoint's step 2 sqrt(m / k) lowered by
  /// stiffness_damping_step_factor for Rayleigh's `beta` (s).
  double step_of(const std::vector<double>& mass, const std::vector<double>& stiffness,
                 double beta = 0.0) const;
  /// Dynamics with Rayleigh beta: the moduli of the viscous stress
  /// (viscous_stress.h) of material `mat` over a motion of strain_dt, for
  /// the kernels' passes that take it with the nodal forces.
  ViscousModuli viscous_moduli(const ZoneMaterial& mat, double strain_dt) const;
  void zone_forces();
  /// The zone forces alone of positions x and velocities v (3 per
  /// gridpoint) over a motion of strain_dt, added to f.
  void zone_forces(const double* x, const double* v, double* f, double strain_dt);
  /// Gravity and face loads into f (N, 3 per gridpoint), and their sizes
  /// into force_size_: where the zone forces are added.
  void external_forces(const double* x, double* f);
  void nodal_mixed_zone_forces(const double* x, const double* v, double* f, double strain_dt);
  /// The batches of nodal_mixed_zone_forces and how far its strain stage
  /// must run ahead of each (set once, from the mesh and the materials).
  void plan_nodal_mixed();
  /// Split among ranks (collective calls): whether any rank has a material
  /// of nodal mixed discretization, and one that may yield
  /// (nmd_on_ranks_), with the vectors that carry the averages to the
  /// ghosts, made once; and that carriage, for `k` numbers a gridpoint (2:
  /// eq. 69's pairs, 1: eq. 75's plastic pressures).
  void share_nodal_mixed();
  void averages_to_ghosts(double* values, unsigned int k);
  std::array<bool, 2> nmd_on_ranks_{{false, false}};
  void move_gridpoints();
  /// The model's view of 4-node zones [first, first + n): their strain
  /// increments in `scratch`, their stresses and states.
  StressBatch tet4_batch(unsigned int first, unsigned int n, Tet4Scratch& scratch);
  /// The zone model on a batch of 4-node zones of material `mat` (zone
  /// volumes `volume`, m^3), with the mean stress averaged over each
  /// hexahedron of hex-mixed zones (eqs. 64-67) and the stress work of
  /// plastic materials added up.
  void update_tet4_stresses(const ZoneMaterial& mat, StressBatch& batch, const double* volume,
                            unsigned int first);
  /// Elastic strain energy of the zones (J) and of those of plastic
  /// materials alone, with the current volumes.
  std::pair<double, double> elastic_energy(const double* x) const;
  /// The zone around gridpoint g with the smallest volume, and that volume.
  std::pair<unsigned int, double> smallest_zone_at(unsigned int g, const double* x) const;

  const TetMesh& mesh_;
  std::vector<ZoneMaterial> materials_;
  std::vector<unsigned int> material_of_zone_;
  SolverSettings s_;
  std::vector<GridpointCondition> conditions_;
  std::vector<FacePressure> pressures_;
  std::unique_ptr<PetscState> petsc_;
  /// Split among ranks: this rank's share (null in one run). Only the
  /// first n_moved_ gridpoints move here; the ghosts after them are
  /// refreshed from their owners (refresh_ghosts).
  std::unique_ptr<GridpointShare> share_;
  unsigned int n_moved_ = 0;
  void refresh_ghosts();
  /// The gridpoint vectors' local arrays (owned, then ghosts): position,
  /// velocity, force, inertial mass, 3 values a gridpoint each.
  std::array<std::vector<double>, 4> local_vectors() const;
  void set_local_vectors(const std::array<std::vector<double>, 4>& values);
  /// The least of `value` over the ranks (itself in one run).
  double least_over_ranks(double value) const;
  /// Adds `mine` summed over the ranks (split among ranks) to `e`.
  void add_over_ranks(const EnergyAccount& mine, EnergyAccount& e) const;
  /// Runs of consecutive zones with one material (the mesher keeps each
  /// block's zones together): batch k is [batch_start_[k], batch_start_[k+1]).
  std::vector<unsigned int> batch_start_;
  std::vector<double> stress_;        ///< 6 per zone, Pa
  std::vector<unsigned char> state_;  ///< per zone
  std::vector<double> gravity_force_; ///< 3 per gridpoint, N: gravity and gridpoint loads
  std::vector<double> true_mass_;     ///< kg, per gridpoint
  AddedMass added_mass_;              ///< by set_inertial_masses
  /// Gridpoint g's inertial mass (kg) at the step dt_ for its stiffness k
  /// (N/m, with the joints'): static density scaling, and partial density
  /// scaling's mass for the given step (eq. 89).
  double inertial_mass_of(unsigned int g, double k) const;
  /// Masses (kg) and the stiffness of eqs. 85-86 (N/m) per gridpoint from
  /// the zones that remain.
  void zone_masses(std::vector<double>& mass, std::vector<double>& stiffness) const;
  /// Inertial masses from the true masses and stiffness (density scaling
  /// for statics, eq. 84 solved for m), with the joints' stiffness.
  void set_inertial_masses();
  /// Batches, masses, gravity and the nodal mixed plan of the zones'
  /// materials as they are now.
  void materials_changed();
  /// gravity_force_: gravity of the true masses and the gridpoint loads of
  /// the conditions.
  void set_gravity_and_loads();
  /// held_, held_velocity_, held_until_ and gravity_force_ from conditions_.
  void apply_conditions();
  /// The faces the water may load (every boundary face), if there is water.
  void select_water_faces();
  /// The loaded boundary faces from pressures_.
  void select_pressed_faces();
  /// remove_zones' change of the model (null materials, batches, masses,
  /// gravity), also made again when a checkpoint is loaded.
  void null_zones(const std::vector<char>& gone);
  std::vector<double> joint_stiffness_; ///< N/m per gridpoint, of use_time_step
  /// Whether a block solver sets the time step (use_time_step); else the
  /// zones set their own. Alike on every rank (a rank without gridpoints
  /// has no joint stiffness), since setting it is collective.
  bool step_from_blocks_ = false;
  std::vector<double> reference_;       ///< m, 3 per gridpoint: where displacements count from
  std::vector<char> removed_zone_;      ///< per zone (empty: none removed)
  std::vector<double> nodal_stiffness_; ///< N/m, per gridpoint (eqs. 85-86)
  std::vector<unsigned char> held_;     ///< per gridpoint, bit d: component d held
  std::vector<double> held_velocity_;   ///< 3 per gridpoint, m/s
  std::vector<double> held_until_;      ///< 3 per gridpoint: model time the velocity stops, s
  /// 3 per gridpoint: the condition whose time function scales the held
  /// velocity (-1: constant), and each condition's scale at this motion.
  std::vector<int> held_motion_;
  std::vector<double> motion_scale_;
  /// The held velocity of component i at model time t (m/s).
  double held_velocity_at(unsigned int i, double t) const
  {
    const int c = held_motion_[i];
    return c < 0 ? held_velocity_[i] : held_velocity_[i] * conditions_[c].motion.scale(t);
  }
  std::vector<std::array<unsigned int, 3>> pressed_faces_; ///< gridpoints, normal outward
  std::vector<double> face_pressure_;                      ///< Pa, per pressed face
  std::vector<Vec3> face_traction_;                        ///< Pa, per pressed face
  /// Loads in time: the pressures_ entry of each pressed face (-1: it is
  /// constant) and each entry's factor at this step; the gridpoint loads
  /// of conditions that vary (gridpoint, condition) and the gridpoint
  /// forces without them (N, 3 per gridpoint).
  std::vector<int> face_function_;
  std::vector<double> pressure_scale_;
  std::vector<std::pair<unsigned int, unsigned int>> timed_load_points_;
  std::vector<double> steady_gravity_force_;
  /// Per pressed face, the fraction of its load on each of its gridpoints
  /// (a third each for 4-node zones, half that on each overlay's split of
  /// a hexahedral zone's face).
  std::vector<std::array<double, 3>> face_share_;
  /// The load of pressed face k at positions x (N).
  Vec3 face_load(std::size_t k, const double* x) const;
  /// Quiet boundaries (dynamics, 'Condition = quiet'): the boundary faces
  /// in their regions, with the shares of face_share_, their area times
  /// outward normal (m^2, initial geometry) and the wave they put in
  /// (an index into quiet_waves_, or ~0u); and the dashpot of each
  /// gridpoint on them, c = sum of share A (rho cp n n + rho cs (I - n n))
  /// (kg/s; xx, yy, zz, xy, yz, zx) in quiet_c_[quiet_slot_[g]].
  std::vector<std::array<unsigned int, 3>> quiet_faces_;
  std::vector<std::array<double, 3>> quiet_share_;
  std::vector<Vec3> quiet_area_;
  std::vector<unsigned int> quiet_wave_;
  std::vector<WaveSignal> quiet_waves_;
  std::vector<Vec3> quiet_wave_direction_; ///< of each wave; zero: the faces' inward normal
  std::vector<int> quiet_slot_;
  std::vector<std::array<double, 6>> quiet_c_;
  double quiet_work_ = 0.0; ///< J dissipated by the dashpots
  /// The quiet faces and dashpots from pressures_ (select_pressed_faces).
  void select_quiet_faces(const std::vector<char>& in_hex, const std::vector<char>& is_vertex);
  std::vector<double> force_size_; ///< 3 per gridpoint: sum of |zone force| (N), for the ratio
  Tet4Scratch scratch_;
  Tet10Scratch scratch10_;           ///< 10-node zones only
  unsigned int points_per_zone_ = 1; ///< stress points per zone
  // Nodal mixed discretization only (empty otherwise).
  bool nodal_mixed_ = false;
  /// Two per gridpoint, side by side so that one access adds both: the
  /// volume-weighted sum of the volumetric strain increments around it
  /// (then their average), and the zone volumes around it (m^3).
  std::vector<double> strain_sums_;
  std::vector<double> nmd_work_volume_;  ///< split among ranks: counted zones' volumes, m^3
  std::vector<double> plastic_average_;  ///< per gridpoint: plastic pressure, Pa
  std::vector<double> batch_volumetric_; ///< per zone of a batch: e, or plastic e^p
  std::vector<double> own_volumetric_;   ///< per zone of a batch: its own e (energy account)
  /// A batch of zones [first, first + n), of a mixed material or not; its
  /// model stage waits for the sums stage of batch `ready_after`, its force
  /// stage for the model stage at place `forces_after` of the model order.
  /// `kept`: its sums stage is the strain pass, whose scratch waits in the
  /// ring for the model stage.
  struct NodalMixedBatch
  {
    unsigned int first, n;
    bool mixed;
    unsigned int ready_after;
    unsigned int forces_after = 0;
    bool kept = false;
  };
  std::vector<NodalMixedBatch> nmd_batches_;
  /// The gridpoints whose sums batch j completes:
  /// completed_gridpoint_[completed_start_[j] .. completed_start_[j + 1]).
  std::vector<unsigned int> completed_start_, completed_gridpoint_;
  /// The model order: batches by ready_after, then by number; the batches
  /// ready after sums batch j are model_order_[model_start_[j] ..
  /// model_start_[j + 1]).
  std::vector<unsigned int> model_start_, model_order_;
  /// The gridpoints whose plastic sums the model stage at place p of the
  /// model order completes: plastic_gridpoint_[plastic_start_[p] ..
  /// plastic_start_[p + 1]).
  std::vector<unsigned int> plastic_start_, plastic_gridpoint_;
  /// Scratch of the kept batches between their sums and model stages
  /// (batch j in nmd_ring_[j % size]); empty when no batch is kept.
  std::vector<Tet4Scratch> nmd_ring_;
  unsigned int nmd_kept_ = 0; ///< batches kept
  /// 41 batches, 6.2 MB of scratch at most (see plan_nodal_mixed): a
  /// layer of up to about 40,000 zones, such as a brick of 90 x 90 cells of
  /// 5 zones in slabs; in columns a batch waits some 5 batches.
  unsigned int nmd_ring_limit_ = 41;
  unsigned int nmd_lag_ = 0;
  /// Zones whose plastic volumetric strain increment e^p is not zero this
  /// step, in order, with their e^p.
  std::vector<unsigned int> yielded_zone_;
  std::vector<double> yielded_volumetric_;
  std::vector<double> yielded_taken_; ///< and their tr d(eps) - tr d(eps~) (energy account)
  /// Whether a mixed zone yielded with a volumetric part at the last step
  /// (then the forces wait for the force stage; only speed depends on it).
  bool last_step_yielded_ = false;
  Damper damper_{Damping::none, 0.0, 0.5, 1.0};
  std::vector<double> last_force_; ///< 3 per gridpoint, N (combined damping only)
  /// Dynamics with Rayleigh beta only (empty otherwise): the forces of the
  /// zones' viscous stress and of the contacts' damping on the gridpoints
  /// (3 each, N) of this step.
  std::vector<double> damping_force_;
  unsigned int ratio_gridpoint_ = 0;
  unsigned int ratio_whole_gridpoint_ = 0; ///< split among ranks: of the whole mesh
  std::vector<double> counted_volume_;     ///< split: zone volumes, 0 where not counted
  double dt_ = 0.0, time_ = 0.0, ratio_ = 1.0;
  /// s: the step of the last motion of the gridpoints (their velocities
  /// are its), and whether free velocities start from rest at the next.
  double motion_dt_ = 0.0;
  bool rest_at_next_motion_ = false;
  double seconds_zones_ = 0.0, seconds_gridpoints_ = 0.0;
  unsigned long step_ = 0;
  // Energy account (J), see EnergyAccount.
  double gravity_work_ = 0.0, boundary_work_ = 0.0, damping_work_ = 0.0;
  double kinetic_whole_step_ = 0.0;
  std::vector<double> gauss_volume_; ///< m^3, a batch of 10-node zones' Gauss points (plastic)
  double plastic_stress_work_ = 0.0; ///< sum of V sigma : d(eps) over zones of plastic materials
  /// Nodal mixed discretization: the work of its zones' forces that their
  /// stresses do not hold, sum of V p (tr d(eps) - tr d(eps~)) (J, see
  /// replaced_strain_work), stored energy of the averaged strains.
  double nodal_mixed_work_ = 0.0;
  double initial_elastic_ = 0.0, initial_plastic_elastic_ = 0.0; ///< and held kinetic
  std::vector<double> pressure_force_; ///< 3 per gridpoint, N (face pressures, water)
  EnergyGrowthWatch growth_watch_;     ///< standalone runs (step())
  /// With water only: every boundary face of the zones (outward), with its
  /// weight (1; a half on each overlay's split of a hexahedral zone's face),
  /// loaded each step with the hydrostatic pressure below the surface
  /// (consistent nodal shares, integrate_water); and how many were wet
  /// at the last step.
  std::vector<std::array<unsigned int, 3>> water_faces_;
  std::vector<double> water_weight_;
  /// 10-node zones: per water face (a sub-triangle), its corner at a zone
  /// vertex (-1: none, the middle one).
  std::vector<int> water_vertex_corner_;
  /// Per water face, what made it (BlockModel::face_origin; empty: unknown).
  std::vector<int> water_face_origin_;
  unsigned int water_faces_below_ = 0;
  Vec3 water_force_ = Vec3::Zero();
  /// Its components as exact sums of the counted faces' shares, so that
  /// the ranks' partial sums add up to one run's, bit for bit.
  std::vector<ExactSum> water_force_sum_;
  /// Calls add(gridpoint, force) with each corner's share of the water on
  /// the boundary faces at positions x (N); returns the faces below the
  /// surface.
  template <typename Add>
  unsigned int water_shares(const double* x, Add&& add) const;
  /// Adds the water on the boundary faces at positions x to f, force_size_
  /// and pressure_force_.
  void add_water(const double* x, double* f);
};

} // namespace talus
