#include <talus/base/exceptions.h>
#include <talus/base/wall_clock.h>
#include <talus/contact/contact_origin.h>
#include <talus/geometry/mass_properties.h>
#include <talus/joint/joint_model.h>
#include <talus/solver/damper.h>
#include <talus/solver/deformable_solver.h>
#include <talus/solver/rigid_solver.h>
#include <talus/solver/subcontact_exchange.h>
#include <talus/zone/zone_surface.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace talus
{

namespace
{
/// Area of block b's largest face (m^2): what bounds the stiffness of its
/// contacts (eq. 87) and, over the volume, its thickness.
double largest_face_area(const BlockModel& m, unsigned int b)
{
  double area = 0.0;
  for (unsigned int f = m.face_start[b]; f < m.face_start[b + 1]; ++f)
  {
    Vec3 twice = Vec3::Zero();
    const unsigned int first = m.face_loop_start[f], n = m.face_loop_start[f + 1] - first;
    for (unsigned int j = 0; j < n; ++j)
      twice +=
          m.vertex[m.face_vertex[first + j]].cross(m.vertex[m.face_vertex[first + (j + 1) % n]]);
    area = std::max(area, 0.5 * twice.norm());
  }
  return area;
}

} // namespace

RigidSolver::RigidSolver(BlockModel& blocks, double density, const SolverSettings& settings,
                         DeformableSolver* zones, std::vector<int> vertex_gridpoint)
    : m_(blocks), s_(settings), zones_(zones), vertex_gridpoint_(std::move(vertex_gridpoint))
{
  joints_.push_back(s_.joint);
  joints_.insert(joints_.end(), s_.joint_materials.begin(), s_.joint_materials.end());
  if (joints_.size() > 255)
    throw InputError("at most 254 joint materials besides 'Joint properties'");
  if (!s_.joint_rule.trivial())
    s_.contact.materials = &s_.joint_rule;
  s_.contact.kn.clear();
  bool dilates = false;
  for (const JointProperties& j : joints_)
  {
    s_.contact.kn.push_back(j.normal_stiffness);
    dilates |= j.dilation_angle != 0.0;
    s_.contact.yielding |= j.model == JointModel::continuously_yielding;
  }
  s_.contact.joints = s_.contact.yielding ? &joints_ : nullptr;
  // No normal offset for joints that neither dilate nor start stressed.
  s_.contact.dilation = dilates || s_.initial_stress != nullptr;
  const unsigned int nb = m_.n_blocks();
  mass.resize(nb);
  inertia.resize(nb);
  velocity.assign(nb, Vec3::Zero());
  spin.assign(nb, Vec3::Zero());
  force.assign(nb, Vec3::Zero());
  moment.assign(nb, Vec3::Zero());
  displacement.assign(nb, Vec3::Zero());
  rotation.assign(nb, Vec3::Zero());
  fixed.assign(nb, 0);
  applied_force.assign(nb, Vec3::Zero());
  applied_force_rate.assign(nb, Vec3::Zero());
  prescribed.assign(nb, 0);
  moved.assign(nb, 0.0);
  path.assign(nb, 0.0);
  last_force_.assign(nb, Vec3::Zero());
  last_moment_.assign(nb, Vec3::Zero());
  motion_dx_.assign(nb, Vec3::Zero());
  motion_dtheta_.assign(nb, Vec3::Zero());
  damping_force_.assign(nb, Vec3::Zero());
  damping_moment_.assign(nb, Vec3::Zero());
  is_deformable_.assign(nb, 0);
  removed_.assign(nb, 0);
  if (zones_ != nullptr)
  {
    for (unsigned int b = 0; b < nb; ++b)
      if (vertex_gridpoint_[m_.vertex_start[b]] >= 0)
      {
        is_deformable_[b] = 1;
        deformable_blocks_.push_back(b);
      }
    contacts_.set_deformable(&is_deformable_, &vertex_gridpoint_);
  }
  if (s_.principal_inertia)
  {
    principal_moments.resize(nb);
    axes.resize(nb);
  }
  for (unsigned int b = 0; b < nb; ++b)
  {
    const double rho = s_.block_density.empty() ? density : s_.block_density.at(b);
    mass[b] = rho * m_.volume[b];
    // The manual's approximate isotropic inertia, from the mean distance r
    // of the vertices to the centroid (below eq. 45): I = (2/9) m r^2, the
    // factor that makes it exact for a cube.
    double r = 0.0;
    for (unsigned int v = m_.vertex_start[b]; v < m_.vertex_start[b + 1]; ++v)
      r += (m_.vertex[v] - m_.centroid[b]).norm();
    r /= (m_.vertex_start[b + 1] - m_.vertex_start[b]);
    inertia[b] = 2.0 / 9.0 * mass[b] * r * r;
    if (s_.principal_inertia && !is_deformable_[b])
    {
      const MassProperties p = compute_mass_properties(m_.polyhedron(b));
      principal_moments[b] = rho * p.principal_moments;
      axes[b] = p.principal_axes;
    }
    for (unsigned int g : s_.fixed_groups)
      if (m_.group[b] == g)
        fixed[b] = 1;
    for (const BlockLoad& load : s_.loads)
      if (m_.group[b] == load.group)
      {
        // A force in time is added step by step (update_timed_loads).
        if (!load.motion.varies())
          applied_force[b] += load.force;
        applied_force_rate[b] += load.force_rate;
        if (load.prescribe_velocity)
          for (int d = 0; d < 3; ++d)
            if (load.held[d])
            {
              prescribed[b] |= 1u << d;
              velocity[b][d] = load.velocity[d] * load.motion.scale(0.0);
            }
        if (load.hold_rotation)
          prescribed[b] |= 8u;
        for (int d = 0; d < 3; ++d)
          if (!(prescribed[b] & (1u << d)) && load.initial_velocity[d] != 0.0)
            velocity[b][d] = load.initial_velocity[d];
        if (!(prescribed[b] & 8u))
          spin[b] = load.initial_spin;
      }
  }
  true_inertia_ = inertia;
  if (s_.principal_inertia)
    true_principal_ = principal_moments;
  find_timed_loads();
  set_masses_and_step();

  envelopes_.resize(nb);
  Box all{m_.vertex.empty() ? Vec3::Zero() : m_.vertex[0],
          m_.vertex.empty() ? Vec3::Zero() : m_.vertex[0]};
  for (const Vec3& v : m_.vertex)
  {
    all.lo = all.lo.cwiseMin(v);
    all.hi = all.hi.cwiseMax(v);
  }
  cells_.define(all, nb);
  detect_contacts(true);
  // The joints there at the start carry the in-situ stress; later ones
  // start free of force.
  ContactSettings first = s_.contact;
  first.initial_stress = s_.initial_stress;
  contacts_.update(m_, first);

  // Energy at the start: the blocks' initial motion (with the masses the
  // cycle moves) and the joints' initial stress; the zones add theirs.
  double weight_size = 0.0;
  count_start_energy((all.hi - all.lo).norm(), weight_size);
  build_water_loads();
  energy_floor_ = 1e-9 * weight_size + 1e-6; // J
}

ExactSum RigidSolver::start_kinetic_energy(double size, double& weight_size) const
{
  ExactSum e;
  for (unsigned int b = 0; b < m_.n_blocks(); ++b)
    if (!fixed[b] && !is_deformable_[b] && !is_ghost(b))
    {
      double k = 0.5 * inertial_mass[b] * velocity[b].squaredNorm();
      if (s_.principal_inertia)
      {
        const Vec3 p = body_momentum(b); // 1/2 w . I w with the principal moments
        k += 0.5 * p.dot(p.cwiseQuotient(principal_moments[b]));
      }
      else
        k += 0.5 * inertia[b] * spin[b].squaredNorm();
      e += k;
      weight_size += mass[b] * s_.gravity.norm() * size;
    }
  return e;
}

void RigidSolver::count_start_energy(double size, double& weight_size)
{
  std::vector<ExactSum> terms{start_kinetic_energy(size, weight_size), joint_energy_share()};
  if (ranks_.sums)
    ranks_.sums(terms);
  kinetic_whole_step_ = terms[0].value();
  terms[1] += terms[0];
  initial_stored_ = terms[1].value();
}

void RigidSolver::set_masses_and_step()
{
  // Density scaling for statics: no block lighter (in inertia) than the mean.
  // Exact sums, so that a model split among ranks has the same mean.
  const unsigned int nb = m_.n_blocks();
  ExactSum mass_sum, rigid_count;
  for (unsigned int b = 0; b < nb; ++b)
    if (!is_deformable_[b] && !removed_[b] && !is_ghost(b))
    {
      mass_sum += mass[b];
      rigid_count += 1.0;
    }
  if (ranks_.sum)
  {
    ranks_.sum(mass_sum);
    ranks_.sum(rigid_count);
  }
  const double n_rigid = rigid_count.value(), mean_mass = mass_sum.value() / n_rigid;
  inertial_mass = mass;
  inertia = true_inertia_;
  if (s_.principal_inertia)
    principal_moments = true_principal_;
  if (!s_.dynamic && s_.density_scaling && n_rigid > 0)
    for (unsigned int b = 0; b < nb; ++b)
    {
      const double scale = std::max(1.0, mean_mass / mass[b]);
      inertial_mass[b] *= scale;
      inertia[b] *= scale;
      if (s_.principal_inertia)
        principal_moments[b] *= scale;
    }
  added_mass_ = AddedMass();
  if (s_.raises_mass() && s_.time_step_fraction > 0.0) // frac 0: no eq. 87 (tests)
  {
    // The summary's figures by exact sums of the blocks this rank moves
    // (on ranks reduced: each block counted once, by its owner).
    std::vector<ExactSum> sums(3); // true mass, mass added, blocks raised
    double largest_factor = 1.0;
    // Partial density scaling (eq. 89): a free block whose own step of eq.
    // 87 (frac 2 sqrt(m / (k A)), lowered for Rayleigh's beta as in
    // stable_time_step) is below the given one gets the mass that reaches
    // it, m = k A (T^2 + 2 T beta) / 4 with T = dt / frac (mass_for_step),
    // and its rotational inertia grows by the same factor. Fixed blocks
    // too, as a stage may let them go; the summary counts the free ones.
    const double k = stiffest_joint();
    const double T = s_.time_step / s_.time_step_fraction;
    for (unsigned int b = 0; b < nb; ++b)
    {
      if (is_deformable_[b] || removed_[b])
        continue;
      const double needed = mass_for_step(k * largest_face_area(m_, b), T, s_.stiffness_damping());
      const double scale = needed > inertial_mass[b] ? needed / inertial_mass[b] : 1.0;
      inertial_mass[b] *= scale;
      inertia[b] *= scale;
      if (s_.principal_inertia)
        principal_moments[b] *= scale;
      if (!s_.dynamic || fixed[b] || is_ghost(b))
        continue; // static inertia is a device of the solution, not mass added
      sums[0] += mass[b];
      if (scale > 1.0)
      {
        sums[2] += 1.0;
        sums[1] += inertial_mass[b] - mass[b];
        largest_factor = std::max(largest_factor, inertial_mass[b] / mass[b]);
      }
    }
    if (ranks_.sums && ranks_.max)
    {
      ranks_.sums(sums);
      largest_factor = ranks_.max(largest_factor);
    }
    added_mass_.total = sums[0].value();
    added_mass_.added = sums[1].value();
    added_mass_.blocks = static_cast<unsigned int>(sums[2].value());
    added_mass_.largest_factor = largest_factor;
  }
  dt_ = s_.time_step > 0.0 ? s_.time_step : stable_time_step();
  dt_without_stiffness_damping_ = s_.time_step > 0.0 ? s_.time_step : stable_time_step(0.0);
  if (ranks_.min && s_.time_step <= 0.0)
  {
    dt_ = ranks_.min(dt_);
    dt_without_stiffness_damping_ = ranks_.min(dt_without_stiffness_damping_);
  }
  if (s_.time_step > 0.0 && s_.time_step_fraction > 0.0 && !s_.raises_mass())
  {
    // A step beyond eq. 87 without its safety fraction cannot be stable.
    const double limit = stable_time_step() / s_.time_step_fraction;
    if (s_.time_step > limit)
      throw InputError(
          s_.source + ": entry 'Time step' in subsection 'Solver': " + number(s_.time_step) +
          " s is larger than the stable step of the blocks, " + number(limit) +
          " s (eq. 87 with frac = 1); allowed: at most that, 0 for the automatic step, or "
          "'Partial density scaling = true' to add mass where the step needs it");
  }
  if (zones_ != nullptr)
  {
    // Eq. 85: the joints add their stiffness to the surface gridpoints;
    // eq. 88: the smaller of the block and zone steps governs.
    std::vector<double> joint_stiffness(zones_->mesh().n_gridpoints(), 0.0);
    const double k = stiffest_joint();
    for (unsigned int b : deformable_blocks_)
      for (unsigned int f = m_.face_start[b]; f < m_.face_start[b + 1] && !removed_[b]; ++f)
      {
        const unsigned int q = m_.face_loop_start[f];
        const Vec3& x0 = m_.vertex[m_.face_vertex[q]];
        const double area = 0.5 * (m_.vertex[m_.face_vertex[q + 1]] - x0)
                                      .cross(m_.vertex[m_.face_vertex[q + 2]] - x0)
                                      .norm();
        for (int j = 0; j < 3; ++j) // each corner's share as its contact spring has it
          joint_stiffness[vertex_gridpoint_[m_.face_vertex[q + j]]] +=
              k * area * (m_.face_corner_share.empty() ? 1.0 / 3.0 : m_.face_corner_share[f][j]);
      }
    if (s_.time_step <= 0.0 && (s_.dynamic || !s_.density_scaling))
    {
      dt_ = std::min(dt_, zones_->stable_time_step(joint_stiffness));
      dt_without_stiffness_damping_ =
          std::min(dt_without_stiffness_damping_, zones_->stable_time_step(joint_stiffness, 0.0));
    }
    else if (s_.time_step <= 0.0 && dt_ == 1e300)
      dt_ = dt_without_stiffness_damping_ = 1.0; // statics, deformable blocks only: unit step
    zones_->use_time_step(dt_, joint_stiffness);
  }
  damper_ = damper_for(s_, dt_);
}

void RigidSolver::remove_blocks(const std::vector<unsigned int>& blocks)
{
  if (blocks.empty() && !ranks_.sum) // on ranks: collective (masses and the step)
    return;
  // The energy the removed blocks and their joints hold leaves the account
  // with them: its error stays what it was.
  const double error_before = energy_account().error();
  std::vector<char> zone_block_gone;
  for (unsigned int b : blocks)
  {
    removed_[b] = 1;
    fixed[b] = 1;
    velocity[b] = spin[b] = Vec3::Zero();
    prescribed[b] = 0;
    applied_force[b] = applied_force_rate[b] = Vec3::Zero();
  }
  contacts_.remove_contacts_of(removed_);
  update_contacts(s_.contact, &path);
  subcontacts_stale_ = true;
  if (zones_ != nullptr)
  {
    bool any = false;
    for (unsigned int b : blocks)
      any |= is_deformable_[b] != 0;
    if (any)
    {
      std::vector<char> zone_gone(zones_->mesh().n_zones(), 0);
      for (unsigned int z = 0; z < zone_gone.size(); ++z)
        zone_gone[z] = removed_[zones_->mesh().zone_block[z]];
      zones_->remove_zones(zone_gone);
    }
  }
  set_masses_and_step();
  initial_stored_ -= energy_account().error() - error_before;
}

void RigidSolver::set_fixed(unsigned int b, bool fix)
{
  if (removed_[b] || is_deformable_[b])
    return;
  fixed[b] = fix ? 1 : 0;
  velocity[b] = spin[b] = Vec3::Zero();
}

void RigidSolver::set_loads(const std::vector<BlockLoad>& loads)
{
  s_.loads = loads;
  find_timed_loads();
  ExactSum work; // of the boundaries, on the blocks this rank moves
  for (unsigned int b = 0; b < m_.n_blocks(); ++b)
  {
    if (removed_[b])
      continue;
    Vec3 force = Vec3::Zero(), rate = Vec3::Zero(), v = velocity[b];
    unsigned char bits = 0;
    for (const BlockLoad& load : loads)
      if (m_.group[b] == load.group)
      {
        if (!load.motion.varies())
          force += load.force;
        rate += load.force_rate;
        if (load.prescribe_velocity)
          for (int d = 0; d < 3; ++d)
            if (load.held[d])
            {
              bits |= 1u << d;
              v[d] = load.velocity[d] * load.motion.scale(time_);
            }
        if (load.hold_rotation)
          bits |= 8u;
      }
    applied_force[b] = force;
    applied_force_rate[b] = rate;
    prescribed[b] = bits;
    if (fixed[b] || is_deformable_[b])
      continue;
    // The support gives or takes the kinetic energy of the change: the
    // boundaries' work, so that the account stays closed.
    if (!is_ghost(b))
      work += 0.5 * inertial_mass[b] * (v.squaredNorm() - velocity[b].squaredNorm());
    velocity[b] = v;
    if ((bits & 8u) && !s_.principal_inertia)
    {
      if (!is_ghost(b))
        work += -0.5 * inertia[b] * spin[b].squaredNorm();
      spin[b].setZero();
    }
  }
  if (ranks_.sum)
    ranks_.sum(work);
  boundary_work_ += work.value();
}

void RigidSolver::find_timed_loads()
{
  timed_loads_.clear();
  for (unsigned int l = 0; l < s_.loads.size(); ++l)
    if (s_.loads[l].motion.varies())
      timed_loads_.push_back(l);
  const unsigned int nb = timed_loads_.empty() ? 0 : m_.n_blocks();
  timed_force_.assign(nb, Vec3::Zero());
  timed_velocity_.assign(nb, Vec3::Zero());
  timed_held_.assign(nb, 0);
}

void RigidSolver::update_timed_loads()
{
  std::fill(timed_force_.begin(), timed_force_.end(), Vec3::Zero());
  std::fill(timed_held_.begin(), timed_held_.end(), 0);
  for (unsigned int l : timed_loads_)
  {
    // Once per load and step: forces live at whole steps, velocities at
    // half steps (eq. 47).
    const BlockLoad& load = s_.loads[l];
    const Vec3 force = load.force * load.motion.scale(time_);
    const Vec3 velocity = load.velocity * load.motion.scale(time_ + 0.5 * dt_);
    for (unsigned int b = 0; b < m_.n_blocks(); ++b)
      if (m_.group[b] == load.group && !removed_[b])
      {
        timed_force_[b] += force;
        if (load.prescribe_velocity)
          for (int d = 0; d < 3; ++d)
            if (load.held[d])
            {
              timed_held_[b] |= 1u << d;
              timed_velocity_[b][d] = velocity[d];
            }
      }
  }
}

void RigidSolver::change_rock(const std::vector<char>& blocks, double density,
                              const ZoneMaterial& material, bool account)
{
  const double error_before = account ? energy_account().error() : 0.0;
  for (unsigned int b = 0; b < m_.n_blocks(); ++b)
  {
    if (!blocks[b] || removed_[b] || is_deformable_[b])
      continue;
    // Every moment of inertia scales with the mass.
    const double scale = density * m_.volume[b] / mass[b];
    mass[b] = density * m_.volume[b];
    true_inertia_[b] *= scale;
    if (s_.principal_inertia)
      true_principal_[b] *= scale;
  }
  if (zones_ != nullptr)
  {
    const TetMesh& mesh = zones_->mesh();
    std::vector<char> zones(mesh.n_zones(), 0);
    bool any = false;
    for (unsigned int z = 0; z < mesh.n_zones(); ++z)
      any |= (zones[z] = blocks[mesh.zone_block[z]]) != 0;
    if (any || zones_->share() != nullptr) // split among ranks: collective (the step)
      zones_->change_material(zones, material, false);
  }
  set_masses_and_step();
  if (account)
    initial_stored_ -= energy_account().error() - error_before;
}

void RigidSolver::set_water(const WaterSpec& water)
{
  s_.water = water;
  build_water_loads();
  if (zones_ != nullptr)
    zones_->set_water(water);
}

void RigidSolver::build_water_loads()
{
  water_stale_ = false;
  water_loads_ = WaterLoads();
  water_global_.clear();
  if (s_.water.active())
  {
    // Fixed blocks need no water; zones take theirs; ghosts move with
    // their owners (on ranks each block's force and work are its owner's).
    std::vector<char> wet(m_.n_blocks(), 0);
    for (unsigned int b = 0; b < m_.n_blocks(); ++b)
      wet[b] = !fixed[b] && !is_deformable_[b] && !removed_[b] && !is_ghost(b);
    water_loads_ = WaterLoads(s_.water, s_.gravity.norm(), wet);
    if (!global_of_local_.empty())
      for (unsigned int b : water_loads_.blocks())
        water_global_.push_back(global_of_local_[b]);
  }
}

void RigidSolver::set_face_load_table(RigidFaceLoads table,
                                      const std::vector<unsigned int>& global_of_local)
{
  face_load_table_ = std::move(table);
  has_face_load_table_ = true;
  localize_loads(global_of_local);
}

void RigidSolver::localize_loads(const std::vector<unsigned int>& global_of_local)
{
  if (has_face_load_table_)
  {
    std::vector<char> owned(m_.n_blocks());
    for (unsigned int b = 0; b < m_.n_blocks(); ++b)
      owned[b] = !is_ghost(b) && !is_deformable_[b];
    face_loads_ = face_load_table_.localized(m_, global_of_local, owned);
  }
  // The water's blocks at the next step: until then the summary's figures
  // are those of the last step, of the blocks owned then (water_global).
  global_of_local_ = global_of_local;
  water_stale_ = true;
}

void RigidSolver::reset_displacements()
{
  for (unsigned int b = 0; b < m_.n_blocks(); ++b)
    displacement[b] = rotation[b] = Vec3::Zero();
  if (zones_ != nullptr)
    zones_->reset_displacements();
}

void RigidSolver::set_dynamic(bool dynamic)
{
  if (dynamic == s_.dynamic)
    return;
  if (!dynamic && s_.density_scaling)
  {
    // Statics with density scaling moves in a time of its own (scaled
    // masses; with zones a unit step): the velocities of the dynamics
    // before would carry into it as jumps. Free blocks start again from
    // rest (those with a prescribed motion keep it); the kinetic energy
    // they held leaves the account as damping. Ghosts alike (same rule).
    damping_work_ += kinetic_whole_step_;
    kinetic_whole_step_ = 0.0;
    for (unsigned int b = 0; b < m_.n_blocks(); ++b)
      if (!fixed[b] && prescribed[b] == 0)
      {
        velocity[b].setZero();
        spin[b].setZero();
      }
  }
  s_.dynamic = dynamic;
  if (zones_ != nullptr)
    zones_->set_dynamic(dynamic);
  set_masses_and_step();
}

void RigidSolver::change_joint_material(int origin, unsigned char material)
{
  // New contacts on the joint follow the rule; those there now change.
  if (origin > 0)
    s_.joint_rule.of_joint_set.resize(
        std::max<std::size_t>(s_.joint_rule.of_joint_set.size(), origin), JointMaterialRule::none);
  if (origin < 0)
    s_.joint_rule.of_joint.resize(std::max<std::size_t>(s_.joint_rule.of_joint.size(), -origin),
                                  JointMaterialRule::none);
  (origin > 0 ? s_.joint_rule.of_joint_set[origin - 1] : s_.joint_rule.of_joint[-origin - 1]) =
      material;
  if (s_.joint_rule.n_groups == 0)
  {
    s_.joint_rule.n_groups = static_cast<unsigned int>(m_.group_names.size());
    s_.joint_rule.of_group_pair.assign(std::size_t(s_.joint_rule.n_groups) * s_.joint_rule.n_groups,
                                       JointMaterialRule::none);
  }
  s_.contact.materials = &s_.joint_rule;
  for (unsigned int c = 0; c < contacts_.n_slots(); ++c)
    if (contacts_.alive[c] && contact_joint_origin(m_, contacts_, c) == origin)
      contacts_.material[c] = material;
  for (unsigned int i = 0; i < contacts_.n_subcontacts(); ++i)
    contacts_.sc_material[i] = contacts_.material[contacts_.sc_contact[i]];
}

void RigidSolver::change_group_pair_material(unsigned int a, unsigned int b, unsigned char material)
{
  JointMaterialRule& rule = s_.joint_rule;
  if (rule.n_groups < m_.group_names.size())
  {
    // Grow the table, keeping the rules it has.
    const unsigned int n = static_cast<unsigned int>(m_.group_names.size());
    std::vector<unsigned char> grown(std::size_t(n) * n, JointMaterialRule::none);
    for (unsigned int i = 0; i < rule.n_groups; ++i)
      for (unsigned int j = 0; j < rule.n_groups; ++j)
        grown[std::size_t(i) * n + j] = rule.of_group_pair[std::size_t(i) * rule.n_groups + j];
    rule.n_groups = n;
    rule.of_group_pair = std::move(grown);
  }
  rule.of_group_pair[std::size_t(a) * rule.n_groups + b] = material;
  rule.of_group_pair[std::size_t(b) * rule.n_groups + a] = material;
  s_.contact.materials = &rule;
  // The contacts of the pair take what the rule now gives them (a joint's
  // own material still comes first).
  for (unsigned int c = 0; c < contacts_.n_slots(); ++c)
  {
    if (!contacts_.alive[c])
      continue;
    const unsigned int ga = m_.group[contacts_.block_a[c]], gb = m_.group[contacts_.block_b[c]];
    if ((ga == a && gb == b) || (ga == b && gb == a))
      contacts_.material[c] = rule.material(m_, contacts_, c);
  }
  for (unsigned int i = 0; i < contacts_.n_subcontacts(); ++i)
    contacts_.sc_material[i] = contacts_.material[contacts_.sc_contact[i]];
}

double RigidSolver::stiffest_joint() const
{
  double k = 0.0;
  for (const JointProperties& j : joints_)
    k = std::max(k, j.stiffest());
  return k;
}

double RigidSolver::stable_time_step(double beta) const
{
  // Eq. 87 block by block: a contact is never stiffer than its joint
  // stiffness times the smaller face of its two blocks, so each free block
  // is bounded by its own mass against its own largest face. A fixed block
  // has no inertia to keep stable, and its faces (a large floor) do not
  // enter; a model of fixed blocks only takes them all. Rayleigh's
  // stiffness-proportional term lowers each block's step 2 / omega by
  // stiffness_damping_step_factor at its omega = sqrt(k A / m).
  // On ranks (collective): the least of all ranks', free blocks first.
  const double k = stiffest_joint();
  double smallest_free = 1e300, smallest_any = 1e300;
  for (unsigned int b = 0; b < m_.n_blocks(); ++b)
  {
    if (is_deformable_[b])
      continue; // a deformable block's gridpoints have their own limit (eq. 84)
    double step = 2.0 * std::sqrt(inertial_mass[b] / (k * largest_face_area(m_, b)));
    if (beta > 0.0)
      step *= stiffness_damping_step_factor(beta, 2.0 / step);
    smallest_any = std::min(smallest_any, step);
    if (!fixed[b])
      smallest_free = std::min(smallest_free, step);
  }
  if (ranks_.min)
  {
    smallest_free = ranks_.min(smallest_free);
    smallest_any = ranks_.min(smallest_any);
  }
  const double smallest = smallest_free < 1e300 ? smallest_free : smallest_any;
  if (smallest == 1e300)
    return 1e300; // no rigid block
  return s_.time_step_fraction * smallest;
}

void RigidSolver::detect_contacts(bool everything)
{
  // Eq. 1: only blocks that moved more than the tolerance are searched again.
  std::vector<char> flagged(m_.n_blocks(), 0);
  bool any = everything;
  for (unsigned int b = 0; b < m_.n_blocks(); ++b)
    if (everything || moved[b] > s_.contact.tolerance)
    {
      flagged[b] = 1;
      moved[b] = 0.0;
      any = true;
    }
  if (!any)
    return;
  // Envelopes enlarged so that blocks within the tolerance are found
  // (search volume 2 CTOL larger than the envelope, as the manual says).
  for (unsigned int b = 0; b < m_.n_blocks(); ++b)
  {
    Box e{m_.vertex[m_.vertex_start[b]], m_.vertex[m_.vertex_start[b]]};
    for (unsigned int v = m_.vertex_start[b]; v < m_.vertex_start[b + 1]; ++v)
    {
      e.lo = e.lo.cwiseMin(m_.vertex[v]);
      e.hi = e.hi.cwiseMax(m_.vertex[v]);
    }
    e.lo.array() -= s_.contact.tolerance;
    e.hi.array() += s_.contact.tolerance;
    envelopes_[b] = e;
  }
  cells_.map(envelopes_);
  cells_.candidate_pairs(envelopes_, everything ? std::vector<char>() : flagged, pairs_);
  // Split among ranks, two ghosts' contact is their owners' work alone;
  // with contacts from owners, so is one across ranks that the other rank
  // computes.
  const RankBlocks* blocks = contacts_from_owners() ? &subcontact_exchange_->blocks() : nullptr;
  for (const auto& [a, b] : pairs_)
    if (!(fixed[a] && fixed[b]) && !removed_[a] && !removed_[b] &&
        (blocks != nullptr ? blocks->computes_contact(a, b) : !(is_ghost(a) && is_ghost(b))))
      contacts_.try_create(a, b, m_, s_.contact);
}

void RigidSolver::update_contacts(const ContactSettings& settings, const std::vector<double>* path)
{
  if (!contacts_from_owners())
  {
    contacts_.update(m_, settings, path);
    return;
  }
  // The contacts across ranks through this rank's sub-contact exchange.
  struct Trade final : ContactTrade
  {
    SubContactExchange& exchange;
    bool dilation, yielding;
    const GridpointShare* gridpoints;
    Trade(SubContactExchange& e, bool d, bool y, const GridpointShare* p)
        : exchange(e), dilation(d), yielding(y), gridpoints(p)
    {
    }
    const RankBlocks& blocks() const override { return exchange.blocks(); }
    void send(const ContactSet& cs, const std::vector<unsigned int>& slots,
              const std::vector<unsigned int>& begin, const std::vector<unsigned int>& end) override
    {
      exchange.send_layout(cs, slots, begin, end, dilation, yielding, gridpoints);
    }
    void receive(ContactSet& taken) override
    {
      exchange.receive_layout(taken, dilation, yielding, gridpoints);
    }
  } trade(*subcontact_exchange_, settings.dilation, settings.yielding,
          zones_ != nullptr ? zones_->share() : nullptr);
  contacts_.update(m_, settings, path, &trade);
  subcontacts_stale_ = true;
}

void RigidSolver::contact_forces()
{
  ContactSet& cs = contacts_;
  const unsigned int n = cs.n_subcontacts();
  du_n_.resize(n);
  du_s_.resize(3 * n);
  // Split among ranks: a contact's work is counted by one rank alone. With
  // an exchange, that rank alone computes it and sends its sub-contacts'
  // state on (RankBlocks::computes_contact); without, every rank holding
  // both blocks computes it, and the owner of its first block counts it.
  const bool exchanged = contacts_from_owners();
  if (exchanged && subcontacts_stale_)
  {
    subcontact_exchange_->match(cs);
    subcontacts_stale_ = false;
  }
  if (exchanged && subcontact_exchange_->computed().size() != n)
    throw std::logic_error("RigidSolver: the contacts changed without the sub-contact "
                           "exchange's lists made again");
  // With an exchange, the sub-contacts this rank computes are known since
  // the layout was matched; without, they follow the ghosts at each step.
  const unsigned char* counted = nullptr;
  if (exchanged)
    counted = subcontact_exchange_->computed().data();
  else if (!ghost_.empty())
  {
    sc_counted_.resize(n);
    for (unsigned int i = 0; i < n; ++i)
      sc_counted_[i] = !ghost_[cs.block_a[cs.sc_contact[i]]];
    counted = sc_counted_.data();
  }
  const double beta = s_.stiffness_damping(); // Rayleigh, s
  if (beta > 0.0)
    sc_velocity_.resize(3 * n);
  // Each increment is what the blocks moved since the last pass: their
  // last motion, zero before the first one. The velocities times dt were
  // wrong twice: at step 0 an initial or prescribed velocity made a shear
  // force ks A v dt from nothing, and a velocity or step set between steps
  // (a stage's load or mode, a block fixed) replaced the motion the
  // contacts had not yet seen. Rayleigh's term below takes the velocities
  // as they are; the gridpoints' velocities are those of their last
  // motion, none before the first.
  const std::vector<Vec3>&motion = motion_dx_, &turn = motion_dtheta_;
  const double moved_dt = step_ == 0 ? 0.0 : zones_ != nullptr ? zones_->motion_dt() : dt_;
  // Relative displacement increments (eqs. 15, 20-22).
  for (unsigned int i = 0; i < n; ++i)
  {
    if (exchanged && !counted[i])
      continue; // another rank computes it and sends its state
    const unsigned int c = cs.sc_contact[i];
    const unsigned int a = cs.block_a[c], b = cs.block_b[c];
    const int* node = gp_x_ != nullptr ? &cs.sc_node[6 * i] : nullptr;
    if (node != nullptr && (node[0] >= 0 || node[3] >= 0))
    {
      // A sub-contact on deformable blocks sits where its gridpoints are
      // (the mean of both sides when both are deformable).
      Vec3 at = Vec3::Zero();
      int sides = 0;
      for (int side = 0; side < 2; ++side)
        if (node[3 * side] >= 0)
        {
          for (int j = 0; j < 3; ++j)
            if (node[3 * side + j] >= 0)
              for (int d = 0; d < 3; ++d)
                at[d] += cs.sc_weight[6 * i + 3 * side + j] * gp_x_[3 * node[3 * side + j] + d];
          ++sides;
        }
      cs.sc_position[i] = at / sides;
    }
    const Vec3& p = cs.sc_position[i];
    // Velocity of each side at the sub-contact: the block's rigid motion,
    // or the gridpoint's, or the point of a deformable face (eqs. 15-19).
    // With the blocks' velocities and spins (and scale 1), the velocity;
    // with their last motions (and the gridpoints' over moved_dt), the
    // displacement increment.
    const auto side_motion = [&](unsigned int blk, int side, const std::vector<Vec3>& v,
                                 const std::vector<Vec3>& w, double gridpoint_scale)
    {
      if (node == nullptr || node[3 * side] < 0)
        return Vec3(v[blk] + w[blk].cross(p - m_.centroid[blk]));
      Vec3 vel = Vec3::Zero();
      for (int j = 0; j < 3; ++j)
        if (node[3 * side + j] >= 0)
          for (int d = 0; d < 3; ++d)
            vel[d] += cs.sc_weight[6 * i + 3 * side + j] * gp_v_[3 * node[3 * side + j] + d];
      return Vec3(gridpoint_scale * vel);
    };
    if (beta > 0.0)
    {
      const Vec3 vel =
          side_motion(b, 1, velocity, spin, 1.0) - side_motion(a, 0, velocity, spin, 1.0);
      for (int d = 0; d < 3; ++d)
        sc_velocity_[3 * i + d] = vel[d];
    }
    const Vec3 du =
        side_motion(b, 1, motion, turn, moved_dt) - side_motion(a, 0, motion, turn, moved_dt);
    const Vec3& nrm = cs.plane[c].normal;
    const double dun = du.dot(nrm);
    // A sub-contact built at this step already has the last motion in its
    // geometric un; only the shear increment is new to it.
    du_n_[i] = cs.sc_fresh[i] ? 0.0 : dun;
    cs.sc_fresh[i] = 0;
    const Vec3 dus = du - dun * nrm;
    du_s_[3 * i] = dus[0];
    du_s_[3 * i + 1] = dus[1];
    du_s_[3 * i + 2] = dus[2];
    // The sub-contact point moves with the mean motion of both blocks (eq. 11).
    if (node == nullptr || (node[0] < 0 && node[3] < 0))
      cs.sc_position[i] += 0.5 * (motion[b] + turn[b].cross(p - m_.centroid[b]) + motion[a] +
                                  turn[a].cross(p - m_.centroid[a]));
  }
  // One joint model for the whole batch (dispatch once, not per sub-contact).
  SubContactBatch batch;
  batch.size = n;
  batch.area = cs.sc_area.data();
  batch.du_normal = du_n_.data();
  batch.du_shear = du_s_.data();
  batch.normal_displacement = cs.sc_un.data();
  batch.normal_force = cs.sc_fn.data();
  batch.shear_force = cs.sc_fs.data();
  batch.shear_displacement = cs.sc_us.data();
  batch.dilation = cs.sc_dilation.empty() ? nullptr : cs.sc_dilation.data();
  batch.state = cs.sc_state.data();
  batch.yield = cs.sc_yield.empty() ? nullptr : cs.sc_yield.data();
  batch.material = cs.sc_material.data();
  batch.counted = counted;
  if (exchanged)
  {
    // Those sent first, then the rest while the messages travel.
    std::vector<double>* velocities = beta > 0.0 ? &sc_velocity_ : nullptr;
    const std::vector<unsigned int>& first = subcontact_exchange_->sent_first();
    batch.indices = first.data();
    batch.size = static_cast<unsigned int>(first.size());
    step_energy_[step_friction] += apply_joint_model(joints_, batch);
    subcontact_exchange_->start(cs, velocities);
    batch.indices = nullptr;
    batch.size = n;
    batch.computed = subcontact_exchange_->computed_after().data();
    step_energy_[step_friction] += apply_joint_model(joints_, batch);
    subcontact_exchange_->finish(cs, velocities);
  }
  else
    step_energy_[step_friction] += apply_joint_model(joints_, batch);

  // Force and moment sums (eqs. 28-32): A pushes B along +n.
  for (unsigned int i = 0; i < n; ++i)
  {
    const unsigned int c = cs.sc_contact[i];
    const unsigned int a = cs.block_a[c], b = cs.block_b[c];
    const Vec3 f = cs.sc_fn[i] * cs.plane[c].normal +
                   Vec3(cs.sc_fs[3 * i], cs.sc_fs[3 * i + 1], cs.sc_fs[3 * i + 2]);
    const Vec3& p = cs.sc_position[i];
    const int* node = gp_x_ != nullptr ? &cs.sc_node[6 * i] : nullptr;
    // Each side takes its force: a rigid block at the point (eqs. 29-32), a
    // deformable side on its gridpoints by the weights (eq. 33).
    for (int side = 0; side < 2; ++side)
    {
      const unsigned int blk = side == 0 ? a : b;
      const Vec3 fs = side == 0 ? Vec3(-f) : f;
      if (node == nullptr || node[3 * side] < 0)
      {
        force[blk] += fs;
        moment[blk] += (p - m_.centroid[blk]).cross(fs);
      }
      else
        for (int j = 0; j < 3; ++j)
          if (node[3 * side + j] >= 0)
            for (int d = 0; d < 3; ++d)
              gp_f_[3 * node[3 * side + j] + d] += cs.sc_weight[6 * i + 3 * side + j] * fs[d];
    }
    // Rayleigh's stiffness-proportional term: beta times the spring force
    // of the relative velocity of the last half step, -beta k A v (normal
    // while in contact, shear while it sticks), outside the joint's state.
    const unsigned char state = cs.sc_state[i];
    if (beta <= 0.0 || (state & open))
      continue;
    const JointProperties& joint = joints_[cs.sc_material[i]];
    const Vec3 rv(sc_velocity_[3 * i], sc_velocity_[3 * i + 1], sc_velocity_[3 * i + 2]);
    const Vec3& nrm = cs.plane[c].normal;
    const double vn = rv.dot(nrm);
    Vec3 fd = -beta * cs.sc_area[i] * joint.normal_stiffness * vn * nrm;
    if (!(state & slipping))
      fd -= beta * cs.sc_area[i] * joint.shear_stiffness * (rv - vn * nrm);
    for (int side = 0; side < 2; ++side)
    {
      const unsigned int blk = side == 0 ? a : b;
      const Vec3 fs = side == 0 ? Vec3(-fd) : fd;
      if (node == nullptr || node[3 * side] < 0)
      {
        damping_force_[blk] += fs;
        damping_moment_[blk] += (p - m_.centroid[blk]).cross(fs);
      }
      else
        for (int j = 0; j < 3; ++j)
          if (node[3 * side + j] >= 0)
            for (int d = 0; d < 3; ++d)
              gp_damping_[3 * node[3 * side + j] + d] += cs.sc_weight[6 * i + 3 * side + j] * fs[d];
    }
  }
  // Reference points follow the blocks (eq. 11) and relative rotation (eq. 12).
  for (unsigned int c = 0; c < cs.n_slots(); ++c)
  {
    if (!cs.alive[c])
      continue;
    const unsigned int a = cs.block_a[c], b = cs.block_b[c];
    Vec3& ref = cs.plane[c].reference;
    const Vec3 dua = motion[a] + turn[a].cross(ref - m_.centroid[a]);
    const Vec3 dub = motion[b] + turn[b].cross(ref - m_.centroid[b]);
    ref += 0.5 * (dua + dub);
    if (s_.contact.rotation_constant != 0.0)
      ref += s_.contact.rotation_constant * cs.plane[c].normal.cross(turn[b] - turn[a]);
  }
}

void RigidSolver::move_blocks()
{
  // Velocities live at half steps (eq. 47). Those given at the start are at
  // t = 0, so the first kick is half a step: without it every position is
  // late by a t dt / 2 (a relative error of 1/n after n steps of free fall).
  const double h = step_ == 0 ? 0.5 * dt_ : dt_;
  const auto kick = [&](double& v, double f, double f_before, double m)
  { return damper_.kick(v, f, f_before, m, h); };
  double max_unbalanced = 0.0;
  ExactSum sum_weight, n_free; // exact: the same on any number of ranks
  ExactSum &gravity_work = step_energy_[step_gravity], &boundary_work = step_energy_[step_boundary],
           &damping_work = step_energy_[step_damping], &kinetic = step_energy_[step_kinetic];
  too_fast_.clear();
  const bool timed = !timed_loads_.empty();
  if (timed)
    update_timed_loads();
  for (unsigned int b = 0; b < m_.n_blocks(); ++b)
  {
    if (fixed[b] || is_deformable_[b] || is_ghost(b))
    {
      force[b].setZero();
      moment[b].setZero();
      damping_force_[b].setZero();
      damping_moment_[b].setZero();
      if (fixed[b]) // a deformable block's motion is its gridpoints' (step)
        motion_dx_[b] = motion_dtheta_[b] = Vec3::Zero();
      continue;
    }
    const Vec3 applied =
        applied_force[b] + applied_force_rate[b] * time_ + (timed ? timed_force_[b] : Vec3::Zero());
    // The sub-contacts' Rayleigh damping (zero without it) acts with the
    // other forces; the account takes its work apart.
    const Vec3 f = force[b] + mass[b] * s_.gravity + applied + damping_force_[b];
    const Vec3 torque = moment[b] + damping_moment_[b];
    if (f.norm() > max_unbalanced)
    {
      max_unbalanced = f.norm();
      ratio_block_ = b;
    }
    sum_weight += mass[b] * s_.gravity.norm();
    n_free += 1.0;
    // Eq. 49 for translation, damped for statics.
    Vec3 damping_force = Vec3::Zero();
    const Vec3 velocity_before = velocity[b];
    // A prescribed velocity in time: the support gives the kinetic energy
    // of its change (and takes minus the force on it, below).
    if (timed && timed_held_[b] != 0)
      for (int d = 0; d < 3; ++d)
        if ((timed_held_[b] & prescribed[b]) & (1u << d))
        {
          const double v = timed_velocity_[b][d];
          boundary_work += 0.5 * inertial_mass[b] * (v * v - velocity[b][d] * velocity[b][d]);
          velocity[b][d] = v;
        }
    for (int d = 0; d < 3; ++d)
      if (!(prescribed[b] & (1u << d)))
        damping_force[d] = kick(velocity[b][d], f[d], last_force_[b][d], inertial_mass[b]);
    last_force_[b] = f;
    Vec3 damping_moment = Vec3::Zero();
    const Vec3 spin_before = spin[b];
    Vec3 spin_turn = Vec3::Zero(); // principal inertia: h (w- + w+) / 2 at this step
    double rotational_kinetic = 0.0;
    if (prescribed[b] & 8u)
      spin[b].setZero();
    else if (s_.principal_inertia)
    {
      // Euler's equations (eq. 45) split in two: the applied moment kicks
      // the body angular momentum (eq. 49, damped in the principal frame),
      // then the block turns freely for dt. The free turn is the implicit
      // midpoint rule on the body angular momentum p, p' = p + dt pm x wm
      // with pm = (p + p') / 2 and wm = pm / I: a rotation of p (the Cayley
      // transform of dt wm), so |p| and 1/2 p . p / I stay exact, and the
      // block turns by the same rotation, which keeps the angular momentum
      // in space exact too. spin is that turn over dt.
      const Eigen::Matrix3d& Q = axes[b];
      const Vec3& I = principal_moments[b];
      Vec3 w = body_momentum(b).cwiseQuotient(I);
      const Vec3 w_before = w;
      const Vec3 mloc = Q.transpose() * torque;
      const Vec3 mloc_before = Q.transpose() * last_moment_[b];
      Vec3 md;
      for (int d = 0; d < 3; ++d)
        md[d] = kick(w[d], mloc[d], mloc_before[d], I[d]);
      const Vec3 p = w.cwiseProduct(I);
      Vec3 pm = p; // fixed-point iterations, each cutting the error by about dt |w|
      for (int it = 0; it < 100; ++it)
      {
        const Vec3 next = p + 0.5 * dt_ * pm.cross(pm.cwiseQuotient(I));
        const double change = (next - pm).norm();
        pm = next;
        if (change <= 1e-15 * p.norm())
          break;
      }
      const Vec3 wm = pm.cwiseQuotient(I);
      const double x = wm.norm() * dt_; // the Cayley turn is 2 atan(x / 2)
      spin[b] = x > 0.0 ? Vec3(Q * wm * (2.0 * std::atan(0.5 * x) / x)) : Vec3::Zero();
      damping_moment = Q * md;
      spin_turn = 0.5 * h * (Q * (w_before + w));
      rotational_kinetic = 0.5 * p.dot(w);
    }
    else
      for (int d = 0; d < 3; ++d)
        damping_moment[d] = kick(spin[b][d], torque[d], last_moment_[b][d], inertia[b]);
    last_moment_[b] = torque;
    // Eqs. 50-52, with the rotation applied exactly so that blocks keep
    // their shape through any number of turns.
    const Vec3 dx = velocity[b] * dt_;
    const Vec3 dtheta = spin[b] * dt_;
    motion_dx_[b] = dx;
    motion_dtheta_[b] = dtheta;
    // Energy account (see EnergyAccount): each force works over the mean of
    // the half steps on either side of it, h (v- + v+) / 2; a held
    // component's support supplies minus the force on it.
    const Vec3 reach = 0.5 * h * (velocity_before + velocity[b]);
    const Vec3 turn = s_.principal_inertia ? spin_turn : Vec3(0.5 * h * (spin_before + spin[b]));
    // Each block's terms go into the step's exact sums (close_energy_step).
    gravity_work += mass[b] * s_.gravity.dot(reach);
    double boundary = applied.dot(reach);
    for (int d = 0; d < 3; ++d)
      if (prescribed[b] & (1u << d))
        boundary -= f[d] * reach[d];
    boundary_work += boundary;
    damping_work += (damping_force - damping_force_[b]).dot(reach) +
                    (damping_moment - damping_moment_[b]).dot(turn);
    // Kinetic energy at the half step less half the contact forces' work
    // over it: the term that makes the account exact for linear joints.
    // With the inertial mass and inertia (any density scaling's included),
    // which the forces accelerate: so the account balances.
    double block_kinetic = 0.5 * inertial_mass[b] * velocity[b].squaredNorm() -
                           0.5 * force[b].dot(dx) - 0.5 * moment[b].dot(dtheta);
    if (s_.principal_inertia)
      block_kinetic += rotational_kinetic; // unchanged by the free turn
    else
      block_kinetic += 0.5 * inertia[b] * spin[b].squaredNorm();
    kinetic += block_kinetic;
    const double angle = dtheta.norm();
    const Eigen::Matrix3d R = angle > 0.0
                                  ? Eigen::AngleAxisd(angle, dtheta / angle).toRotationMatrix()
                                  : Eigen::Matrix3d::Identity();
    const Vec3 c = m_.centroid[b];
    double max_du = 0.0;
    for (unsigned int v = m_.vertex_start[b]; v < m_.vertex_start[b + 1]; ++v)
    {
      const Vec3 moved_to = c + dx + R * (m_.vertex[v] - c);
      max_du = std::max(max_du, (moved_to - m_.vertex[v]).cwiseAbs().maxCoeff());
      m_.vertex[v] = moved_to;
    }
    for (unsigned int f = m_.face_start[b]; f < m_.face_start[b + 1]; ++f)
      m_.face_normal[f] = R * m_.face_normal[f];
    if (s_.principal_inertia)
      axes[b] = R * axes[b];
    m_.centroid[b] += dx;
    displacement[b] += dx;
    rotation[b] += dtheta;
    moved[b] += max_du; // eq. 1
    path[b] += max_du;
    moved_beyond_tolerance_ |= moved[b] > s_.contact.tolerance;
    if (max_du > s_.contact.tolerance)
      too_fast_.emplace_back(b, max_du);
    force[b].setZero();
    moment[b].setZero();
    damping_force_[b].setZero();
    damping_moment_[b].setZero();
  }
  local_unbalanced_ = max_unbalanced;
  if (ranks_.max)
  {
    max_unbalanced = ranks_.max(max_unbalanced);
    ranks_.sum(sum_weight);
    ranks_.sum(n_free);
  }
  const double weight = sum_weight.value(), free = n_free.value();
  ratio_ = free > 0.0 && weight > 0.0 ? max_unbalanced / (weight / free) : 0.0;
}

void RigidSolver::split_among_ranks(std::vector<char> ghost, RankReductions reductions)
{
  ghost_ = std::move(ghost);
  ranks_ = std::move(reductions);
  contacts_.drop_contacts_among(ghost_);
  subcontacts_stale_ = true;
  build_water_loads(); // on the blocks this rank owns
  set_masses_and_step();
  if (step_ == 0)
  {
    // This rank's share of the energy at the start, with the masses of the
    // whole model's density scaling: its blocks and the contacts it counts.
    double weight_size = 0.0;
    count_start_energy(0.0, weight_size);
  }
  if (ranks_.sum && ranks_.max)
  {
    // The energy floor of the whole model (its weight times about its size),
    // the same on every rank.
    Box mine{m_.vertex.empty() ? Vec3::Zero() : m_.vertex[0],
             m_.vertex.empty() ? Vec3::Zero() : m_.vertex[0]};
    for (const Vec3& v : m_.vertex)
    {
      mine.lo = mine.lo.cwiseMin(v);
      mine.hi = mine.hi.cwiseMax(v);
    }
    const double size = ranks_.max((mine.hi - mine.lo).norm());
    double weight_size = 0.0;
    start_kinetic_energy(size, weight_size);
    ExactSum total;
    total += weight_size;
    ranks_.sum(total);
    energy_floor_ = 1e-9 * total.value() + 1e-6; // J
  }
}

std::size_t RigidSolver::packed_size(unsigned int b) const
{
  const std::size_t vertices = m_.vertex_start[b + 1] - m_.vertex_start[b];
  const std::size_t faces = m_.face_start[b + 1] - m_.face_start[b];
  return 3 * (vertices + faces) + 3 * 10 + 2 + (s_.principal_inertia ? 9 : 0);
}

void RigidSolver::pack_block(unsigned int b, std::vector<double>& out) const
{
  const auto put = [&](const Vec3& x) { out.insert(out.end(), x.data(), x.data() + 3); };
  for (unsigned int v = m_.vertex_start[b]; v < m_.vertex_start[b + 1]; ++v)
    put(m_.vertex[v]);
  for (unsigned int f = m_.face_start[b]; f < m_.face_start[b + 1]; ++f)
    put(m_.face_normal[f]);
  for (const Vec3* x : std::initializer_list<const Vec3*>{
           &m_.centroid[b], &velocity[b], &spin[b], &displacement[b], &rotation[b], &last_force_[b],
           &last_moment_[b], &applied_force[b], &motion_dx_[b], &motion_dtheta_[b]})
    put(*x);
  out.push_back(moved[b]);
  out.push_back(path[b]);
  if (s_.principal_inertia)
    out.insert(out.end(), axes[b].data(), axes[b].data() + 9);
}

const double* RigidSolver::unpack_block(unsigned int b, const double* in)
{
  const auto get = [&](Vec3& x)
  {
    x = Vec3(in[0], in[1], in[2]);
    in += 3;
  };
  for (unsigned int v = m_.vertex_start[b]; v < m_.vertex_start[b + 1]; ++v)
    get(m_.vertex[v]);
  for (unsigned int f = m_.face_start[b]; f < m_.face_start[b + 1]; ++f)
    get(m_.face_normal[f]);
  for (Vec3* x :
       {&m_.centroid[b], &velocity[b], &spin[b], &displacement[b], &rotation[b], &last_force_[b],
        &last_moment_[b], &applied_force[b], &motion_dx_[b], &motion_dtheta_[b]})
    get(*x);
  moved[b] = *in++;
  path[b] = *in++;
  if (s_.principal_inertia)
  {
    std::copy(in, in + 9, axes[b].data());
    in += 9;
  }
  // Eq. 1 for the ghost as its owner judged it.
  moved_beyond_tolerance_ |= moved[b] > s_.contact.tolerance;
  return in;
}

void RigidSolver::step()
{
  if (zones_ != nullptr)
    zones_->compute_forces(); // zone forces first; contacts add to them
  auto t0 = std::chrono::steady_clock::now();
  for (ExactSum& term : step_energy_)
    term.clear();
  // Eq. 1 between updates too: a block that moved more than the tolerance
  // may meet a new neighbour, whose contact must carry force from the step
  // it forms (else a fast block is deep in the other when its sub-contacts
  // come, and the overlap is energy from nowhere).
  const bool periodic = step_ > 0 && step_ % s_.contact.update_period == 0;
  // Split among ranks, all search and update when one must, as one would.
  const auto any = [&](bool mine) { return ranks_.any ? ranks_.any(mine) : mine; };
  if (any(periodic || moved_beyond_tolerance_))
  {
    const unsigned int before = contacts_.n_contacts();
    detect_contacts(false);
    moved_beyond_tolerance_ = false;
    subcontacts_stale_ = true; // on every rank: this branch is taken by all
    timing_.seconds_detection += seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    if (any(periodic || contacts_.n_contacts() > before))
      update_contacts(s_.contact, &path);
    timing_.seconds_planes += seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
  }
  if (zones_ != nullptr)
  {
    DeformableSolver::View view(*zones_);
    gp_x_ = view.x;
    gp_v_ = view.v;
    gp_f_ = view.f;
    gp_damping_ = view.damping;
    contact_forces();
    gp_x_ = gp_v_ = gp_f_ = gp_damping_ = nullptr;
  }
  else
    contact_forces();
  if (!face_loads_.empty())
    face_loads_.add(m_, force, moment, velocity, spin, time_);
  if (water_stale_)
    build_water_loads(); // on the blocks owned since a migration
  if (!water_loads_.empty())
    water_loads_.add(m_, force, moment, velocity, spin);
  timing_.seconds_forces += seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  check_finite_forces();
  move_blocks();
  if (!face_loads_.empty()) // their work is the boundaries', as that of 'Load N'
    face_loads_.account(fixed, velocity, spin, step_ == 0 ? 0.5 * dt_ : dt_, dt_,
                        step_energy_[step_boundary], step_energy_[step_kinetic]);
  if (!water_loads_.empty())
    water_loads_.account(velocity, spin, step_ == 0 ? 0.5 * dt_ : dt_, dt_,
                         step_energy_[step_boundary], step_energy_[step_kinetic]);
  if (zones_ != nullptr)
  {
    zones_->move();
    DeformableSolver::View view(*zones_);
    std::vector<double> moved_by(m_.n_blocks(), 0.0);
    std::vector<Vec3> centre_before;
    for (unsigned int b : deformable_blocks_)
      centre_before.push_back(m_.centroid[b]);
    follow_gridpoints(m_, vertex_gridpoint_, deformable_blocks_, view.x, moved_by);
    for (std::size_t k = 0; k < deformable_blocks_.size(); ++k)
    {
      // A deformable block's displacement: that of its surface's mean point.
      const unsigned int b = deformable_blocks_[k];
      displacement[b] += m_.centroid[b] - centre_before[k];
      motion_dx_[b] = m_.centroid[b] - centre_before[k];
      velocity[b] = motion_dx_[b] / dt_;
      moved[b] += moved_by[b]; // eq. 1
      path[b] += moved_by[b];
      moved_beyond_tolerance_ |= moved[b] > s_.contact.tolerance;
    }
  }
  if ((step_ + 1) % Damper::servo_period == 0)
    damper_.adjust(ranks_.sums); // on ranks: the whole model's powers
  timing_.seconds_motion += seconds_since(t0);
  time_ += dt_;
  ++step_;
  close_energy_step();
  watch_energy_growth();
  if (!too_fast_.empty())
    check_reach();
}

void RigidSolver::close_energy_step()
{
  // One message for the step's terms of the whole model; each total then
  // takes the same double on every rank as on one.
  if (ranks_.sums)
    ranks_.sums(step_energy_);
  gravity_work_ += step_energy_[step_gravity].value();
  boundary_work_ += step_energy_[step_boundary].value();
  damping_work_ += step_energy_[step_damping].value();
  friction_work_ += step_energy_[step_friction].value();
  kinetic_whole_step_ = step_energy_[step_kinetic].value();
}

void RigidSolver::check_reach()
{
  // A block that moves more than the contact tolerance in one step meets a
  // neighbour up to that deep inside, and one that moves more than half
  // the thickness of either block can pass through it between two
  // detections (eq. 1). That matters only where another block is within
  // reach: the box the block swept this step (its envelope at the last
  // detection, which holds where it started, to where it is now, widened by
  // the tolerance) meets the other's envelope.
  const double tol = s_.contact.tolerance;
  // Thickness of a block: its volume over its largest face (exact for a box).
  const auto thickness = [&](unsigned int b) { return m_.volume[b] / largest_face_area(m_, b); };
  for (const auto& [b, du] : too_fast_)
  {
    Box swept = envelopes_[b];
    for (unsigned int v = m_.vertex_start[b]; v < m_.vertex_start[b + 1]; ++v)
    {
      swept.lo = swept.lo.cwiseMin(m_.vertex[v] - Vec3::Constant(tol));
      swept.hi = swept.hi.cwiseMax(m_.vertex[v] + Vec3::Constant(tol));
    }
    for (unsigned int o = 0; o < m_.n_blocks(); ++o)
    {
      if (o == b || ((swept.lo.array() > envelopes_[o].hi.array()).any() ||
                     (swept.hi.array() < envelopes_[o].lo.array()).any()))
        continue;
      const double speed = du / dt_;
      const std::string moved = "block " + std::to_string(b) + " moved " + number(du) +
                                " m in one step (" + number(speed) +
                                " m/s), more than the contact tolerance " + number(tol) +
                                " m, with block " + std::to_string(o) + " within its reach";
      const std::string catching =
          "a time step of at most tolerance / speed = " + number(tol / speed) + " s would catch it";
      if (du <= 0.5 * std::min(thickness(b), thickness(o)))
      {
        // Contacts that start deep: the balance shows what they cost.
        if (!warned_fast_)
          std::fprintf(stderr,
                       "talus: warning in %s: at step %lu %s: its contacts can start up to that "
                       "deep; %s (later such steps are not reported)\n",
                       s_.source.c_str(), step_, moved.c_str(), catching.c_str());
        warned_fast_ = true;
        break;
      }
      // Speed beyond what the sources gave: an instability, whose cause
      // matters more than the step that would catch it.
      const double sources = growth_watch_.largest_sources();
      const double kinetic = 0.5 * inertial_mass[b] * velocity[b].squaredNorm();
      if (kinetic > 4.0 * sources + energy_floor_)
        throw DivergenceError("the run diverged at step " + std::to_string(step_) + ": " + moved +
                              ", with a kinetic energy of " + number(kinetic) +
                              " J where all sources gave at most " + number(sources) + " J; " +
                              likely_cause(b));
      throw DivergenceError("the run stopped at step " + std::to_string(step_) + ": " + moved +
                            ", more than half the thickness of either: it can pass through "
                            "without a contact (eq. 1); " +
                            catching +
                            "; lower 'Time step' or 'Time step fraction', or the "
                            "block's speed");
    }
  }
}

double RigidSolver::unbalanced_ratio() const
{
  return zones_ != nullptr ? std::max(ratio_, zones_->unbalanced_ratio()) : ratio_;
}

unsigned int RigidSolver::unbalanced_block() const
{
  // (Split among ranks the gridpoint is the whole mesh's: BlockCycle finds
  // its block.)
  if (zones_ != nullptr && zones_->share() == nullptr && zones_->unbalanced_ratio() > ratio_)
    return zones_->mesh().gridpoint_block[zones_->unbalanced_gridpoint()];
  return ratio_block_;
}

double RigidSolver::kinetic_energy() const
{
  // With the true masses: density scaling changes the path, not the physics.
  double e = 0.0;
  for (unsigned int b = 0; b < m_.n_blocks(); ++b)
  {
    e += 0.5 * mass[b] * velocity[b].squaredNorm();
    if (s_.principal_inertia && !is_deformable_[b])
    {
      const Vec3 p = body_momentum(b);
      e += 0.5 * p.dot(p.cwiseQuotient(principal_moments[b])) * mass[b] / inertial_mass[b];
    }
    else
      e += 0.5 * inertia[b] * mass[b] / inertial_mass[b] * spin[b].squaredNorm();
  }
  return e;
}

Vec3 RigidSolver::body_momentum(unsigned int b) const
{
  const Vec3& I = principal_moments[b];
  // At the start the spin is the angular velocity at t = 0.
  if (step_ == 0)
    return I.cwiseProduct(axes[b].transpose() * spin[b]);
  // Afterwards it is the last free turn over dt (see move_blocks): undo the
  // Cayley angle to find the midpoint velocity wm, whose axis that turn
  // keeps, then p = pm - dt/2 wm x pm at its end.
  const double angle = spin[b].norm() * dt_;
  if (angle == 0.0)
    return Vec3::Zero();
  const Vec3 wm = axes[b].transpose() * spin[b] * (2.0 * std::tan(0.5 * angle) / angle);
  const Vec3 pm = I.cwiseProduct(wm);
  return pm - 0.5 * dt_ * wm.cross(pm);
}

Vec3 RigidSolver::angular_momentum(unsigned int b) const
{
  if (s_.principal_inertia && !is_deformable_[b])
    return axes[b] * body_momentum(b);
  return inertia[b] * spin[b];
}

double RigidSolver::joint_energy() const
{
  ExactSum e = joint_energy_share();
  if (ranks_.sum)
    ranks_.sum(e);
  return e.value();
}

ExactSum RigidSolver::joint_energy_share() const
{
  const ContactSet& cs = contacts_;
  ExactSum e;
  for (unsigned int i = 0; i < cs.n_subcontacts(); ++i)
  {
    if (!ghost_.empty() && ghost_[cs.block_a[cs.sc_contact[i]]])
      continue; // its first block's owner counts it
    const double a = cs.sc_area[i];
    const double fs2 = cs.sc_fs[3 * i] * cs.sc_fs[3 * i] +
                       cs.sc_fs[3 * i + 1] * cs.sc_fs[3 * i + 1] +
                       cs.sc_fs[3 * i + 2] * cs.sc_fs[3 * i + 2];
    const JointProperties& j = joints_[cs.sc_material[i]];
    if (j.model == JointModel::continuously_yielding)
    {
      e += cy_stored_energy(j, cs.sc_fn[i], fs2, a);
      continue;
    }
    e += 0.5 * cs.sc_fn[i] * cs.sc_fn[i] / (j.normal_stiffness * a) +
         0.5 * fs2 / (j.shear_stiffness * a);
  }
  return e;
}

EnergyAccount RigidSolver::energy_account() const
{
  EnergyAccount e;
  e.gravity_work = gravity_work_;
  e.boundary_work = boundary_work_;
  e.kinetic = kinetic_whole_step_;
  e.joint_elastic = joint_energy();
  e.friction = friction_work_;
  e.damping = damping_work_;
  e.initial_stored = initial_stored_;
  if (zones_ != nullptr)
    zones_->add_energy(e);
  return e;
}

void RigidSolver::check_finite_forces() const
{
  // One sum over the free blocks: a NaN or infinity anywhere makes it so.
  double sum = 0.0;
  for (unsigned int b = 0; b < m_.n_blocks(); ++b)
    if (!fixed[b] && !is_deformable_[b])
      sum += force[b].sum() + moment[b].sum();
  if (!std::isfinite(sum))
    for (unsigned int b = 0; b < m_.n_blocks(); ++b)
      if (!fixed[b] && !is_deformable_[b] &&
          !(force[b].allFinite() && moment[b].allFinite() && velocity[b].allFinite()))
        throw DivergenceError("the run diverged at step " + std::to_string(step_ + 1) +
                              ": the contact force on block " + std::to_string(b) +
                              " is not finite; " + likely_cause(b));
  if (zones_ != nullptr)
    zones_->check_finite_forces(step_ + 1, dt_);
}

void RigidSolver::watch_energy_growth()
{
  double kinetic = kinetic_whole_step_,
         sources = std::abs(initial_stored_) + std::abs(gravity_work_) + std::abs(boundary_work_);
  if (zones_ != nullptr)
  {
    EnergyAccount z;
    zones_->add_work(z);
    kinetic += z.kinetic;
    sources += std::abs(z.initial_stored) + std::abs(z.gravity_work) + std::abs(z.boundary_work);
  }
  // Split among ranks, these are the whole model's (close_energy_step), so
  // that every rank decides alike.
  if (!growth_watch_.diverging(step_, kinetic, sources, energy_floor_))
    return;
  // Name the rigid block, or the zone, that moves with the most energy.
  unsigned int worst = 0;
  double largest = -1.0;
  for (unsigned int b = 0; b < m_.n_blocks(); ++b)
    if (!fixed[b] && !is_deformable_[b] &&
        0.5 * inertial_mass[b] * velocity[b].squaredNorm() > largest)
    {
      largest = 0.5 * inertial_mass[b] * velocity[b].squaredNorm();
      worst = b;
    }
  const std::string growth = "the kinetic energy, " + number(kinetic) +
                             " J, has grown far beyond its sources (the work of gravity and "
                             "boundaries and the energy at the start came to at most " +
                             number(growth_watch_.largest_sources()) + " J); ";
  if (zones_ != nullptr && zones_->largest_gridpoint_energy() > largest)
    throw DivergenceError("the run diverged at step " + std::to_string(step_) + ": " + growth +
                          zones_->divergence_site(dt_));
  throw DivergenceError("the run diverged at step " + std::to_string(step_) + ": " + growth +
                        "block " + std::to_string(worst) + " moves fastest; " +
                        likely_cause(worst));
}

std::string RigidSolver::likely_cause(unsigned int b) const
{
  // Eq. 87 for this block alone, with its largest face.
  const double area = largest_face_area(m_, b);
  const double k = stiffest_joint();
  const double limit = 2.0 * std::sqrt(inertial_mass[b] / (k * area));
  const std::string numbers =
      "the time step " + number(dt_) + " s against 2 sqrt(m / (k A)) = " + number(limit) +
      " s for this block (eq. 87 with frac = 1; m = " + number(inertial_mass[b]) +
      " kg, k = " + number(k) + " Pa/m, largest face A = " + number(area) + " m^2)";
  // A block held by several joints is stiffer than eq. 87's one joint.
  if (dt_ > 0.5 * limit)
    return "likely cause: the time step is too large for the joint stiffness: " + numbers +
           ", and a block between joints needs less; lower 'Time step' or 'Time step fraction'";
  return "likely cause: a contact that gives energy (a deep overlap, or a contact geometry that "
         "jumps between steps), since " +
         numbers + " is stable";
}

AddedMass RigidSolver::added_mass() const
{
  AddedMass a = added_mass_;
  if (zones_ != nullptr)
    a += zones_->added_mass();
  return a;
}

SolverReport RigidSolver::report() const
{
  SolverReport r = timing_;
  r.steps = step_;
  r.time = time_;
  r.time_step = dt_;
  r.ratio = unbalanced_ratio();
  r.contacts = contacts_.n_contacts();
  r.subcontacts = contacts_.n_subcontacts();
  return r;
}

std::string RigidSolver::water_summary() const
{
  unsigned int faces = water_loads_.faces_below();
  Vec3 force = water_loads_.total_force();
  if (zones_ != nullptr)
  {
    faces += zones_->water_faces_below();
    force += zones_->water_force();
  }
  return talus::water_summary(s_.water, faces, force);
}

} // namespace talus
