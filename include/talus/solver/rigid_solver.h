#pragma once

#include <talus/base/exact_sum.h>
#include <talus/contact/cell_space.h>
#include <talus/contact/contact_set.h>
#include <talus/contact/joint_material_rule.h>
#include <talus/joint/joint_properties.h>
#include <talus/model/block_model.h>
#include <talus/model/initial_stress.h>
#include <talus/model/time_history.h>
#include <talus/solver/added_mass.h>
#include <talus/solver/damper.h>
#include <talus/solver/energy_account.h>
#include <talus/solver/rigid_face_loads.h>
#include <talus/solver/water_loads.h>
#include <talus/zone/zone_material.h>

#include <Eigen/Core>

#include <functional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace talus
{

class CheckpointReader;
class CheckpointWriter;
class DeformableSolver;
class SubContactExchange;

/// Loads on the blocks of one group: a force at each block's centroid that
/// may grow at a constant rate, or a prescribed velocity.
struct BlockLoad
{
  unsigned int group = 0;
  Vec3 force = Vec3::Zero();      ///< N, per block
  Vec3 force_rate = Vec3::Zero(); ///< N/s, per block
  bool prescribe_velocity = false;
  Vec3 velocity = Vec3::Zero();         ///< m/s
  bool held[3] = {true, true, true};    ///< which components of the velocity are held
  bool hold_rotation = false;           ///< the blocks do not rotate (a stiff platen)
  Vec3 initial_velocity = Vec3::Zero(); ///< m/s at t = 0 (free components)
  Vec3 initial_spin = Vec3::Zero();     ///< rad/s at t = 0 about the centroid
  /// A load that varies in model time t: the force is force motion.scale(t)
  /// + force_rate t and the prescribed velocity velocity motion.scale(t);
  /// none: constant.
  TimeFunction motion;
};

struct SolverSettings
{
  bool dynamic = false;             ///< false: static solution with damping
  unsigned long steps = 0;          ///< step limit (0: build the model only)
  double end_time = 0.0;            ///< s of model time at which the run stops (0: none)
  double target_ratio = 1e-5;       ///< static runs stop below this unbalanced-force ratio (0: off)
  Damping damping = Damping::local; ///< statics
  double local_damping = 0.8;       ///< alpha of eqs. 79 and 83
  double global_damping_ratio = 0.5; ///< R of eq. 77 that the servo keeps
  /// Dynamics: Rayleigh damping, the ratio xi(omega) = (alpha / omega +
  /// beta omega) / 2 of critical damping: a mass-proportional force -alpha
  /// m v on blocks and gridpoints (alpha, 1/s) and a stiffness-proportional
  /// one, beta times the elastic force of the velocities, in the zones and
  /// at the sub-contacts in contact (beta, s). 0: none.
  double rayleigh_alpha = 0.0;
  double rayleigh_beta = 0.0;
  /// Dynamics: alpha of local damping (eqs. 78-79); 0: none.
  double dynamic_local_damping = 0.0;
  /// The stiffness-proportional coefficient that the present mode takes (s).
  double stiffness_damping() const { return dynamic ? rayleigh_beta : 0.0; }
  /// Statics only: inertial masses raised to the mean block mass so that the
  /// time step follows the mean block, not the smallest (density scaling).
  bool density_scaling = true;
  /// Dynamics with a given 'Time step': partial density scaling (eq. 89,
  /// added_mass.h): the gridpoints and rigid blocks whose own stable step is
  /// below the step get inertial mass (blocks also rotational inertia) to
  /// reach it, the others keep their true mass. Static stages add it on top
  /// of their own density scaling where that leaves a block too light for
  /// the step.
  bool partial_density_scaling = false;
  double added_mass_limit = 0.01; ///< the largest added mass, a fraction of the total
  bool added_mass_warn = false;   ///< over the limit: a warning (true) or refusal (false)
  /// The inertial mass is raised for the given step (see above).
  bool raises_mass() const { return partial_density_scaling && time_step > 0.0; }
  /// Rotation with the full principal inertia and Euler's equations (eqs.
  /// 45, 49) instead of the manual's isotropic approximation (eq. 46).
  bool principal_inertia = false;
  double time_step_fraction = 0.1;  ///< frac of eq. 87
  double time_step = 0.0;           ///< s; 0: automatic (eq. 87)
  std::string source;               ///< parameter file, for messages
  Vec3 gravity = Vec3(0, 0, -9.81); ///< m/s^2
  ContactSettings contact;
  JointProperties joint; ///< joint material 0 ('Joint properties')
  /// Joint materials 1, 2, ... ('Joint material N'), and which one each
  /// contact takes (JointMaterialRule; empty: material 0 for all).
  std::vector<JointProperties> joint_materials;
  JointMaterialRule joint_rule;
  /// kg/m^3 of each block (empty: the density given to the solver, for all).
  std::vector<double> block_density;
  std::vector<unsigned int> fixed_groups; ///< group indices of fixed blocks
  std::vector<BlockLoad> loads;
  std::vector<unsigned int> history_blocks; ///< blocks whose motion is recorded
  std::vector<Vec3> history_points; ///< m: nearest gridpoint and zone recorded (deformable blocks)
  /// In-situ stress that the joints existing at the start carry (none when
  /// null); zones take theirs from the deformable solver.
  const InitialStress* initial_stress = nullptr;
  /// Water in the joints and on the faces below a phreatic surface
  /// ('Water'; none by default): hydrostatic pressure on every face of the
  /// free rigid blocks (WaterLoads) and on the zones' boundary faces.
  WaterSpec water;
  unsigned int history_interval = 10; ///< steps between history rows
  unsigned long output_interval = 0;  ///< steps between VTU files (0: first and last)
};

/// The damper the settings ask for at time step `dt` (s): for dynamics
/// local damping if asked for and the mass-proportional Rayleigh term, the
/// static damping chosen otherwise.
inline Damper damper_for(const SolverSettings& s, double dt)
{
  if (s.dynamic)
    return Damper(s.dynamic_local_damping > 0.0 ? Damping::local : Damping::none,
                  s.dynamic_local_damping, s.global_damping_ratio, dt, s.rayleigh_alpha);
  return Damper(s.damping, s.local_damping, s.global_damping_ratio, dt);
}

/// What a model split among ranks reduces across them; a member left null
/// means one rank (the value stays as it is).
struct RankReductions
{
  std::function<bool(bool)> any;                    ///< whether any rank's is true
  std::function<double(double)> min, max;           ///< the least and the largest of all ranks'
  std::function<void(ExactSum&)> sum;               ///< each rank's partial sum becomes the total
  std::function<void(std::vector<ExactSum>&)> sums; ///< the same for several, in one message
};

/// What a run did, for the summary.
struct SolverReport
{
  unsigned long steps = 0;
  double time = 0.0;      ///< s
  double time_step = 0.0; ///< s
  double ratio = 0.0;     ///< unbalanced-force ratio at the end
  unsigned int contacts = 0, subcontacts = 0;
  double seconds_detection = 0, seconds_planes = 0, seconds_forces = 0, seconds_motion = 0;
};

/// The rigid-block distinct element cycle: contacts (cell space, common
/// plane, sub-contacts), sub-contact forces by the joint model, block motion
/// (eqs. 44-52) with local damping for statics.
class RigidSolver
{
public:
  /// With `zones`, the blocks whose vertices map to gridpoints
  /// (`vertex_gridpoint`, see use_zone_surfaces) are deformable: the zone
  /// solver moves them, and their contacts act on their gridpoints.
  RigidSolver(BlockModel& blocks, double density, const SolverSettings& settings,
              DeformableSolver* zones = nullptr, std::vector<int> vertex_gridpoint = {});

  /// Pressures and tractions of 'Boundary N' on the faces of the rigid
  /// blocks (rigid_face_loads.h), from the faces as they are now.
  void set_face_loads(const std::vector<FacePressure>& loads)
  {
    std::vector<char> rigid(m_.n_blocks());
    for (unsigned int b = 0; b < m_.n_blocks(); ++b)
      rigid[b] = !is_deformable_[b];
    face_loads_ = RigidFaceLoads(m_, rigid, loads);
  }
  /// Whether block b is deformable (its zones move it).
  bool is_deformable(unsigned int b) const { return is_deformable_[b] != 0; }
  /// The same, selected elsewhere (a stage's, on the blocks as built).
  void set_face_loads(RigidFaceLoads loads) { face_loads_ = std::move(loads); }

  /// Stages: the blocks `blocks[b]` (not removed) are made of another
  /// rock from now on: rigid ones of `density` (kg/m^3), the zones of
  /// deformable ones of `material` (stresses kept); masses and the time
  /// step follow. With `account`, the energy account's error is kept as it
  /// was (off when a restart sets again what a checkpoint holds).
  void change_rock(const std::vector<char>& blocks, double density, const ZoneMaterial& material,
                   bool account = true);

  /// Stages: contacts between blocks of groups `a` and `b` (indices of the
  /// model's groups) that lie on no joint with a material take joint
  /// material `material` from now on, those there now and new ones.
  void change_group_pair_material(unsigned int a, unsigned int b, unsigned char material);

  /// Stages: this water from now on (rigid blocks' faces and the zones).
  void set_water(const WaterSpec& water);
  const WaterSpec& water() const { return s_.water; }

  /// Stages: these loads ('Load N') from now on, in place of those before.
  /// A velocity prescribed anew is set at once (the kinetic energy of the
  /// change is the boundaries' work); one let go keeps its velocity.
  void set_loads(const std::vector<BlockLoad>& loads);

  /// Stages. Removes blocks (an excavation): they lose their contacts and
  /// stop, and the zones of deformable ones go (DeformableSolver::
  /// remove_zones); masses and the time step follow.
  void remove_blocks(const std::vector<unsigned int>& blocks);
  /// Whether block b was removed.
  bool removed(unsigned int b) const { return removed_[b] != 0; }
  const std::vector<char>& removed_blocks() const { return removed_; }
  /// Holds a rigid block still (fix) or lets it move.
  void set_fixed(unsigned int b, bool fix);
  /// Displacements and rotations (and gridpoint displacements) start again
  /// from zero; forces and stresses stay.
  void reset_displacements();
  /// Static (damped, density-scaled) or dynamic from now on: masses, time
  /// step and damping follow.
  void set_dynamic(bool dynamic);
  bool dynamic() const { return s_.dynamic; }
  /// The contacts on joint set or joint `origin` (BlockModel::
  /// joint_set_origin, joint_origin), now and later, take joint material
  /// `material`.
  void change_joint_material(int origin, unsigned char material);
  /// The water pressure on the free rigid blocks' faces (empty without
  /// 'Water'), with its figures of the last step.
  const WaterLoads& water_loads() const { return water_loads_; }
  /// The summary's 'Water:' line (water_summary) for the faces of the
  /// rigid blocks and of the zones at the last step.
  std::string water_summary() const;

  /// Stable time step of eq. 87 for this model (s), lowered for the
  /// stiffness-proportional Rayleigh term of dynamics
  /// (stiffness_damping_step_factor).
  double stable_time_step() const { return stable_time_step(s_.stiffness_damping()); }
  /// The time step the run would take without the stiffness-proportional
  /// Rayleigh term (s): dt() when there is none or the step is given.
  double time_step_without_stiffness_damping() const { return dt_without_stiffness_damping_; }

  /// Runs to the step limit or (statics) the target ratio. `output` is
  /// called with (step, time) whenever output is due.
  template <typename Output, typename History>
  SolverReport run(Output&& output, History&& history)
  {
    return run(output, history, [](unsigned long) {});
  }
  /// The same, calling `after_step(step)` after every step (checkpoints).
  template <typename Output, typename History, typename AfterStep>
  SolverReport run(Output&& output, History&& history, AfterStep&& after_step);

  /// One cycle.
  void step();

  /// A model split among ranks (issue 24): the blocks marked in `ghost`
  /// are copies of blocks other ranks own. This solver computes their
  /// contacts but does not move them; their state comes from their owners'
  /// pack_block through unpack_block after every step. What the step needs
  /// of the whole model (the mean mass of density scaling, the time step,
  /// the unbalanced-force ratio, when to search for and update contacts)
  /// comes through `reductions`. Masses and the time step are set again.
  void split_among_ranks(std::vector<char> ghost, RankReductions reductions);
  bool is_ghost(unsigned int b) const { return !ghost_.empty() && ghost_[b] != 0; }
  /// Split among ranks: each contact across ranks found, updated and
  /// computed by one of its two ranks alone, which sends the contact at each
  /// update and its sub-contacts' state at each step to the other
  /// (`exchange`: kept by the caller, with the blocks it was made with;
  /// null: every rank that holds both blocks computes their contact).
  void share_subcontacts(SubContactExchange* exchange)
  {
    subcontact_exchange_ = exchange;
    subcontacts_stale_ = true;
  }
  /// On ranks: 'Boundary N' face loads as a table on the whole model
  /// (RigidFaceLoads::relative_to), kept to place them again on the blocks
  /// owned after a migration; `global_of_local`: the global numbers of the
  /// blocks held now.
  void set_face_load_table(RigidFaceLoads table, const std::vector<unsigned int>& global_of_local);
  /// On ranks, after the blocks held or owned changed (BlockMigration): the
  /// face loads (from the table) and the water on the blocks owned now.
  void localize_loads(const std::vector<unsigned int>& global_of_local);
  /// On ranks: the global numbers of water_loads().blocks().
  const std::vector<unsigned int>& water_global() const { return water_global_; }
  /// The largest unbalanced force on a block this rank moves, at the last
  /// step (N): on unbalanced_block().
  double local_unbalanced_force() const { return local_unbalanced_; }
  /// Appends block b's moving state (vertices, face normals, centroid,
  /// velocities, displacements, eq. 1's measures, the last unbalanced
  /// force and moment, the last motion; principal axes) to `out`:
  /// packed_size(b) doubles.
  void pack_block(unsigned int b, std::vector<double>& out) const;
  std::size_t packed_size(unsigned int b) const;
  /// Reads what pack_block wrote for block b; returns the end of it.
  const double* unpack_block(unsigned int b, const double* in);

  /// Split among ranks with zones: the deformable blocks (global numbers)
  /// whose surfaces this rank holds, each with its vertices' local gridpoints.
  void hold_surfaces(std::unordered_map<unsigned int, std::vector<int>> surfaces)
  {
    held_surfaces_ = std::move(surfaces);
  }
  /// The zone solver of the deformable blocks (null without): on ranks it
  /// changes when deformable blocks change rank (BlockMigration).
  DeformableSolver* zone_solver() const { return zones_; }

  /// Largest unbalanced force over the mean gravity force of free blocks.
  /// (with deformable blocks, the larger of that and the gridpoints' ratio).
  double unbalanced_ratio() const;
  /// The rigid blocks' part of it alone.
  double rigid_unbalanced_ratio() const { return ratio_; }
  /// The block whose unbalanced force sets that ratio (of the last step; for
  /// deformable blocks, the block of the gridpoint that sets it).
  unsigned int unbalanced_block() const;
  double kinetic_energy() const;
  /// Angular momentum of block b about its centroid (kg m^2/s, scaled
  /// inertia), at the last whole step with the principal inertia.
  Vec3 angular_momentum(unsigned int b) const;
  /// Energy bookkeeping (J): work done by gravity, elastic energy stored in
  /// the joints, dissipated by friction and by damping. Of the whole model
  /// when split among ranks, the same double on every rank and in a serial
  /// run: each step's terms are exact sums (over blocks and sub-contacts,
  /// and across ranks), rounded once and added to the totals, and the
  /// joints' energy is an exact sum (a reduction across the ranks: every
  /// rank must ask for it at once, as for energy_account()).
  double gravity_work() const { return gravity_work_; }
  double joint_energy() const;
  /// The joint materials, 'Joint properties' first.
  const std::vector<JointProperties>& joints() const { return joints_; }
  double friction_dissipation() const { return friction_work_; }
  double damping_dissipation() const { return damping_work_; }
  /// Every term of the energy balance of blocks and zones, and its error.
  /// Costs a pass over the sub-contacts (and zones): call it for histories.
  EnergyAccount energy_account() const;

  // Block state (per block).
  std::vector<double> mass;            ///< kg, gravitational
  std::vector<double> inertial_mass;   ///< kg, after density scaling
  std::vector<double> inertia;         ///< kg m^2, isotropic (see constructor), scaled
  std::vector<Vec3> principal_moments; ///< kg m^2, scaled (principal inertia only)
  std::vector<Eigen::Matrix3d> axes;   ///< principal axes as columns (principal inertia only)
  std::vector<Vec3> velocity, spin;    ///< m/s, rad/s
  std::vector<Vec3> force, moment;     ///< N, N m (reset every cycle)
  std::vector<Vec3> displacement;      ///< m, since the start
  std::vector<Vec3> rotation;          ///< rad, sum of increments
  std::vector<char> fixed;
  std::vector<Vec3> applied_force, applied_force_rate; ///< N, N/s
  std::vector<unsigned char> prescribed; ///< bit d: velocity component d held; bit 3: no rotation
  std::vector<double> moved;             ///< u_acc of eq. 1, m
  std::vector<double> path;              ///< m, distance travelled since the start (never reset)

  const ContactSet& contacts() const { return contacts_; }
  double time() const { return time_; }
  unsigned long steps_done() const { return step_; }
  double dt() const { return dt_; }
  /// What partial density scaling added to the free rigid blocks and the
  /// zones (dynamics; nothing in static stages).
  AddedMass added_mass() const;
  SolverReport report() const;

  /// Checkpoints (source/io/checkpoint.cc): the state of the cycle, its
  /// contacts and the model's geometry. A solver that has loaded one
  /// continues the run it came from.
  void save_state(CheckpointWriter& out) const;
  void load_state(CheckpointReader& in);
  /// The damper with its running state (the servo of global adaptive
  /// damping, eq. 77): a restart keeps it across the stage changes it sets
  /// again, which remake it with the blocks' masses.
  const Damper& damper() const { return damper_; }
  void set_damper(const Damper& damper) { damper_ = damper; }
  /// The time step (s) and the step without Rayleigh's stiffness term,
  /// likewise kept by a restart: made anew they would come from the
  /// blocks' face areas in their turned geometry, last bits off the
  /// stage start's.
  std::pair<double, double> time_steps() const { return {dt_, dt_without_stiffness_damping_}; }
  void set_time_steps(const std::pair<double, double>& steps)
  {
    dt_ = steps.first;
    dt_without_stiffness_damping_ = steps.second;
  }

private:
  /// Moves blocks, their state and contacts between ranks (block_migration.h).
  friend class BlockMigration;
  /// The loads that vary in time (s_.loads indices), and their sum on each
  /// block at this step: force (N, at time_) and the velocity of the held
  /// components (m/s, at time_ + dt_ / 2; bits in timed_held_).
  void find_timed_loads();
  void update_timed_loads();
  std::vector<unsigned int> timed_loads_;
  std::vector<Vec3> timed_force_, timed_velocity_;
  std::vector<unsigned char> timed_held_;

  void detect_contacts(bool everything);
  /// Whether each contact across ranks is computed by one of its two ranks
  /// and taken by the other (share_subcontacts on a split model), which
  /// neither finds nor updates it.
  bool contacts_from_owners() const { return subcontact_exchange_ != nullptr && !ghost_.empty(); }
  /// ContactSet::update with `settings`; split among ranks with an
  /// exchange, with the contacts across ranks traded (ContactTrade).
  void update_contacts(const ContactSettings& settings, const std::vector<double>* path);
  /// Eq. 87 block by block with the stiffness-proportional coefficient
  /// `beta` (s) of Rayleigh damping.
  double stable_time_step(double beta) const;
  void contact_forces();
  void move_blocks();
  /// Throws DivergenceError, before anything moves, if a force or moment
  /// on a free block (or a gridpoint) is not finite.
  void check_finite_forces() const;
  /// Every EnergyGrowthWatch::period steps: throws DivergenceError if the
  /// kinetic energy grows geometrically with no source.
  void watch_energy_growth();
  /// Principal inertia: block b's angular momentum in its principal frame
  /// at the last whole step (kg m^2/s), from its spin (see move_blocks).
  Vec3 body_momentum(unsigned int b) const;
  /// For the blocks of too_fast_ with another block within reach: warns
  /// once (standard error) of contacts that can start deep, and throws
  /// DivergenceError for a move that can pass through a block.
  void check_reach();
  /// The likely cause of a divergence at block b, for the message.
  std::string likely_cause(unsigned int b) const;

  BlockModel& m_;
  SolverSettings s_;
  std::vector<char> ghost_;       ///< per block; empty: no ghosts
  double local_unbalanced_ = 0.0; ///< N, see local_unbalanced_force
  RankReductions ranks_;          ///< members null: one rank
  CellSpace cells_;
  ContactSet contacts_;
  std::vector<Box> envelopes_;
  std::vector<std::pair<unsigned int, unsigned int>> pairs_;
  std::vector<double> du_n_, du_s_;
  std::vector<unsigned char> sc_counted_; ///< split among ranks: see contact_forces
  SubContactExchange* subcontact_exchange_ = nullptr;
  /// The exchange's lists are made again at the next contact pass: set,
  /// on every rank alike, wherever the contacts' layout may have changed.
  bool subcontacts_stale_ = true;
  /// Dynamics with Rayleigh beta only: the relative velocity at each
  /// sub-contact (3 per sub-contact, m/s) of the step, and the damping
  /// force and moment of the sub-contacts on each rigid block (N, N m),
  /// kept apart from force and moment for the energy account.
  std::vector<double> sc_velocity_;
  std::vector<Vec3> damping_force_, damping_moment_;
  double* gp_damping_ = nullptr; ///< the zones' damping forces during the contact stage
  /// Unbalanced force and moment of the last step (combined damping, eq. 83).
  std::vector<Vec3> last_force_, last_moment_;
  /// Each block's last motion, its centroid's displacement and its turn
  /// (m, rad; zero before the first): the contacts' increments are that
  /// motion, whatever a stage or a test set the velocities or the step to
  /// since.
  std::vector<Vec3> motion_dx_, motion_dtheta_;
  Damper damper_{Damping::none, 0.0, 0.5, 1.0};
  // Deformable blocks (none without a zone solver).
  DeformableSolver* zones_ = nullptr;
  std::vector<int> vertex_gridpoint_;
  /// Split among ranks: the deformable blocks (by global number) whose
  /// surface gridpoints this rank holds, with the local gridpoint of each
  /// of their vertices, so that such a block can become a ghost here when
  /// blocks move (BlockMigration).
  std::unordered_map<unsigned int, std::vector<int>> held_surfaces_;
  std::vector<char> is_deformable_;
  std::vector<unsigned int> deformable_blocks_;
  double* gp_x_ = nullptr; ///< gridpoint arrays during the contact stage
  double* gp_v_ = nullptr;
  double* gp_f_ = nullptr;
  std::vector<JointProperties> joints_; ///< material 0, then s_.joint_materials
  /// Inertial masses (density scaling), the time step (eqs. 87-88) and
  /// the damper, from the settings and the blocks that remain.
  void set_masses_and_step();
  /// The kinetic energy of the free blocks this rank moves, with the masses
  /// the cycle moves (J); adds each one's weight times `size` (N m) to
  /// `weight_size`.
  ExactSum start_kinetic_energy(double size, double& weight_size) const;
  /// initial_stored_ and kinetic_whole_step_ at the start (the whole
  /// model's, exact), with start_kinetic_energy's `size` and `weight_size`.
  void count_start_energy(double size, double& weight_size);
  /// The joints' stored energy of the sub-contacts this rank counts.
  ExactSum joint_energy_share() const;
  /// This step's energy terms, summed exactly over the blocks and
  /// sub-contacts (in any order, on any rank); close_energy_step() reduces
  /// them across the ranks (one message with the divergence watch's) and
  /// rounds them once into the totals below.
  enum StepTerm
  {
    step_gravity,
    step_boundary,
    step_damping,
    step_friction,
    step_kinetic,
    n_step_terms
  };
  std::vector<ExactSum> step_energy_ = std::vector<ExactSum>(n_step_terms);
  void close_energy_step();
  /// water_loads_ from s_.water, on the rigid blocks that move.
  void build_water_loads();
  std::vector<char> removed_;        ///< per block: excavated by a stage
  std::vector<double> true_inertia_; ///< kg m^2, isotropic, before scaling
  std::vector<Vec3> true_principal_; ///< kg m^2, before scaling (principal inertia)
  AddedMass added_mass_;             ///< of the rigid blocks, by set_masses_and_step
  /// The stiffest joint spring per unit area of any material, max(kn, ks) (Pa/m).
  double stiffest_joint() const;
  unsigned int ratio_block_ = 0;
  double dt_ = 0.0, time_ = 0.0, ratio_ = 1.0;
  double dt_without_stiffness_damping_ = 0.0; ///< s, for the summary
  double gravity_work_ = 0.0, friction_work_ = 0.0, damping_work_ = 0.0;
  double boundary_work_ = 0.0;          ///< J: applied forces and prescribed velocities
  double kinetic_whole_step_ = 0.0;     ///< J: kinetic term of the account (see EnergyAccount)
  bool moved_beyond_tolerance_ = false; ///< a block moved more than CTOL since detection (eq. 1)
  double initial_stored_ = 0.0;         ///< J: kinetic and joint energy at the start
  double energy_floor_ = 0.0;           ///< J: below this, growth is not judged
  EnergyGrowthWatch growth_watch_;
  /// Blocks that moved more than the contact tolerance in the last step,
  /// with that move (m, eq. 1's measure).
  std::vector<std::pair<unsigned int, double>> too_fast_;
  bool warned_fast_ = false;       ///< the warning of check_reach() was given
  RigidFaceLoads face_loads_;      ///< pressures and tractions on rigid blocks' faces
  RigidFaceLoads face_load_table_; ///< on ranks: face_loads_ of the whole model, relative
  bool has_face_load_table_ = false;
  std::vector<unsigned int> global_of_local_; ///< on ranks, from localize_loads
  std::vector<unsigned int> water_global_;    ///< see water_global()
  bool water_stale_ = false; ///< water_loads_ to be built again before its next use
  WaterLoads water_loads_;   ///< water on free rigid blocks' faces (none without water)
  unsigned long step_ = 0;
  unsigned long last_output_ = 0; ///< step of the last output in run()
  bool resumed_ = false;          ///< state loaded from a checkpoint
  mutable SolverReport timing_;
};

template <typename Output, typename History, typename AfterStep>
SolverReport RigidSolver::run(Output&& output, History&& history, AfterStep&& after_step)
{
  // A continued run has its first output and history row already.
  if (!resumed_)
  {
    output(step_, time_);
    history(step_, time_);
    last_output_ = step_;
  }
  // The step of the last history row: a run that ends on a multiple of the
  // history interval has its last row already.
  unsigned long last_history = step_;
  while (step_ < s_.steps)
  {
    step();
    if (s_.history_interval > 0 && step_ % s_.history_interval == 0)
    {
      history(step_, time_);
      last_history = step_;
    }
    if (s_.output_interval > 0 && step_ % s_.output_interval == 0)
    {
      output(step_, time_);
      last_output_ = step_;
    }
    if (!s_.dynamic && s_.target_ratio > 0.0 && unbalanced_ratio() < s_.target_ratio && step_ > 10)
      break;
    after_step(step_);
  }
  if (last_history != step_)
    history(step_, time_);
  if (last_output_ != step_)
    output(step_, time_);
  return report();
}

} // namespace talus
