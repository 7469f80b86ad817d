#include <talus/base/exceptions.h>
#include <talus/solver/deformable_solver.h>
#include <talus/zone/zone_models.h>

#include <deal.II/lac/petsc_vector.h>

#include <petscsys.h>
#include <petscvec.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <tuple>

namespace talus
{

namespace
{
bool inside(const Box& b, const double* p)
{
  return p[0] >= b.lo.x() && p[0] <= b.hi.x() && p[1] >= b.lo.y() && p[1] <= b.hi.y() &&
         p[2] >= b.lo.z() && p[2] <= b.hi.z();
}

/// The raw local array of a PETSc vector for the length of one stage.
class LocalArray
{
public:
  explicit LocalArray(const dealii::PETScWrappers::MPI::Vector& v) : vec_(v)
  {
    VecGetArray(vec_, &data_);
  }
  ~LocalArray() { VecRestoreArray(vec_, &data_); }
  double* data() { return data_; }
  double& operator[](std::size_t i) { return data_[i]; }

private:
  Vec vec_;
  double* data_ = nullptr;
};

constexpr unsigned int zone_batch = 1024; ///< zones per kernel call (fits in cache)

/// Sum over n zones of V sigma : d(eps) (J); tensors as six numbers xx, yy,
/// zz, xy, yz, zx with tensor shear components.
double stress_power(unsigned int n, const double* strain, const double* stress,
                    const double* volume)
{
  double w = 0.0;
  for (unsigned int z = 0; z < n; ++z)
  {
    const double* e = strain + 6 * z;
    const double* s = stress + 6 * z;
    w += volume[z] * (s[0] * e[0] + s[1] * e[1] + s[2] * e[2] +
                      2.0 * (s[3] * e[3] + s[4] * e[4] + s[5] * e[5]));
  }
  return w;
}

double tet_volume(const double* x, const std::array<unsigned int, 4>& t)
{
  const auto P = [&](unsigned int g) { return Vec3(x[3 * g], x[3 * g + 1], x[3 * g + 2]); };
  return (P(t[1]) - P(t[0])).dot((P(t[2]) - P(t[0])).cross(P(t[3]) - P(t[0]))) / 6.0;
}
} // namespace

/// Gridpoint state, 3 numbers per gridpoint in each vector.
struct DeformableSolver::PetscState
{
  dealii::PETScWrappers::MPI::Vector position, velocity, force, inertial_mass;
};

DeformableSolver::DeformableSolver(const TetMesh& mesh, std::vector<ZoneMaterial> materials,
                                   std::vector<unsigned int> material_of_zone,
                                   const SolverSettings& settings,
                                   std::vector<GridpointCondition> conditions,
                                   std::vector<FacePressure> pressures,
                                   const InitialStress* initial)
    : mesh_(mesh), materials_(std::move(materials)), material_of_zone_(std::move(material_of_zone)),
      s_(settings), conditions_(std::move(conditions)), pressures_(std::move(pressures))
{
  PetscBool petsc_ready = PETSC_FALSE;
  PetscInitialized(&petsc_ready);
  if (!petsc_ready)
    throw InputError(
        "internal: PETSc is not initialised (create a talus::ParallelEnvironment first)");
  const unsigned int ng = mesh_.n_gridpoints(), nz = mesh_.n_zones();
  if (material_of_zone_.size() != nz)
    throw InputError("internal: one material index per zone is needed");

  for (const ZoneMaterial& m : materials_)
    nodal_mixed_ |= m.nodal_mixed;
  // Batches: runs of one material.
  for (unsigned int z = 0; z < nz; ++z)
    if (z == 0 || material_of_zone_[z] != material_of_zone_[z - 1])
      batch_start_.push_back(z);
  batch_start_.push_back(nz);

  // Initial stress.
  stress_.assign(6 * nz, 0.0);
  state_.assign(nz, 0);
  if (initial != nullptr)
    for (unsigned int z = 0; z < nz; ++z)
    {
      double zc = 0.0;
      for (unsigned int a = 0; a < 4; ++a)
        zc += 0.25 * mesh_.position[3 * mesh_.zone_gridpoint[z][a] + 2];
      initial->at(zc, &stress_[6 * z]);
    }

  // Masses: a quarter of each zone's mass to each of its gridpoints; and
  // the stiffness of eq. 86 summed at each gridpoint (eq. 85).
  std::vector<double> mass(ng, 0.0), stiffness(ng, 0.0);
  const auto P = [&](unsigned int g)
  { return Vec3(mesh_.position[3 * g], mesh_.position[3 * g + 1], mesh_.position[3 * g + 2]); };
  for (unsigned int z = 0; z < nz; ++z)
  {
    const auto& t = mesh_.zone_gridpoint[z];
    const ZoneMaterial& mat = materials_[material_of_zone_[z]];
    const double V = (P(t[1]) - P(t[0])).dot((P(t[2]) - P(t[0])).cross(P(t[3]) - P(t[0]))) / 6.0;
    double b_max = 0.0, largest_face = 0.0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
      {
        b_max = std::max(b_max, (P(t[i]) - P(t[j])).norm());
        for (int k = j + 1; k < 4; ++k)
          largest_face =
              std::max(largest_face, 0.5 * (P(t[j]) - P(t[i])).cross(P(t[k]) - P(t[i])).norm());
      }
    const double h_min = 3.0 * V / largest_face;
    const double k_zone =
        8.0 / 3.0 * (mat.bulk_modulus + 4.0 / 3.0 * mat.shear_modulus) * b_max * b_max / h_min;
    for (int a = 0; a < 4; ++a)
    {
      mass[t[a]] += 0.25 * mat.density * V;
      stiffness[t[a]] += k_zone;
    }
  }
  gravity_force_.assign(3 * ng, 0.0);
  for (unsigned int g = 0; g < ng; ++g)
    for (int d = 0; d < 3; ++d)
      gravity_force_[3 * g + d] = mass[g] * s_.gravity[d]; // eq. 56

  // Time step (eq. 84); statics with density scaling: unit time step and
  // each gridpoint's inertial mass set from its stiffness, m = k dt^2 / 4.
  const bool scaled = !s_.dynamic && s_.density_scaling;
  if (s_.time_step > 0.0)
  {
    dt_ = s_.time_step;
    if (!scaled && dt_ > stable_time_step_of(mass, stiffness))
      throw InputError(s_.source + ": entry 'Time step' in subsection 'Solver': " + number(dt_) +
                       " s is larger than the stable step of the zones, " +
                       number(stable_time_step_of(mass, stiffness)) +
                       " s (eq. 84); allowed: at most that, or 0 for the automatic step");
  }
  else
    dt_ = scaled ? 1.0 : stable_time_step_of(mass, stiffness);
  petsc_ = std::make_unique<PetscState>();
  for (auto* v : {&petsc_->position, &petsc_->velocity, &petsc_->force, &petsc_->inertial_mass})
    v->reinit(MPI_COMM_WORLD, 3 * ng, 3 * ng);
  {
    LocalArray x(petsc_->position), m(petsc_->inertial_mass);
    for (unsigned int g = 0; g < ng; ++g)
      for (int d = 0; d < 3; ++d)
      {
        x[3 * g + d] = mesh_.position[3 * g + d];
        m[3 * g + d] = scaled ? stiffness[g] * dt_ * dt_ / 4.0 : mass[g];
      }
  }
  true_mass_ = mass;
  nodal_stiffness_ = stiffness;

  // Boundary conditions, by the gridpoints' initial positions.
  held_.assign(ng, 0);
  held_velocity_.assign(3 * ng, 0.0);
  for (unsigned int g = 0; g < ng; ++g)
    for (const GridpointCondition& c : conditions_)
      if (inside(c.region, &mesh_.position[3 * g]))
        for (int d = 0; d < 3; ++d)
        {
          gravity_force_[3 * g + d] += c.force[d];
          if (c.held[d])
          {
            held_[g] |= 1u << d;
            held_velocity_[3 * g + d] =
                c.velocity[d] + c.velocity_gradient.row(d).dot(Vec3(mesh_.position[3 * g],
                                                                    mesh_.position[3 * g + 1],
                                                                    mesh_.position[3 * g + 2]));
          }
        }
  {
    LocalArray v(petsc_->velocity);
    for (unsigned int i = 0; i < 3 * ng; ++i)
      v[i] = held_velocity_[i];
  }
  for (unsigned int f = 0; f < mesh_.n_faces(); ++f)
  {
    double c[3] = {0, 0, 0};
    for (unsigned int g : mesh_.face_gridpoint[f])
      for (int d = 0; d < 3; ++d)
        c[d] += mesh_.position[3 * g + d] / 3.0;
    for (const FacePressure& p : pressures_)
      if (inside(p.region, c))
      {
        pressed_faces_.push_back(f);
        face_pressure_.push_back(p.pressure);
        face_traction_.push_back(p.traction);
        break;
      }
  }
  force_size_.assign(3 * ng, 0.0);
  if (!pressed_faces_.empty())
    pressure_force_.assign(3 * ng, 0.0);
  std::tie(initial_elastic_, initial_plastic_elastic_) = elastic_energy(mesh_.position.data());
  {
    // Held velocities are there from the start: energy at the start.
    LocalArray m(petsc_->inertial_mass);
    for (unsigned int i = 0; i < 3 * ng; ++i)
      initial_elastic_ += 0.5 * m[i] * held_velocity_[i] * held_velocity_[i];
  }
  damper_ = Damper(s_.dynamic ? Damping::none : s_.damping, s_.local_damping,
                   s_.global_damping_ratio, dt_);
  if (!s_.dynamic && s_.damping == Damping::combined)
    last_force_.assign(3 * ng, 0.0);
}

DeformableSolver::~DeformableSolver() = default;

double DeformableSolver::stable_time_step_of(const std::vector<double>& mass,
                                             const std::vector<double>& stiffness)
{
  // Eq. 84: dt = 2 min sqrt(m_i / k_i).
  double ratio = 1e300;
  for (std::size_t g = 0; g < mass.size(); ++g)
    if (stiffness[g] > 0.0)
      ratio = std::min(ratio, mass[g] / stiffness[g]);
  return 2.0 * std::sqrt(ratio);
}

double DeformableSolver::stable_time_step(const std::vector<double>& joint_stiffness) const
{
  std::vector<double> k = nodal_stiffness_;
  for (std::size_t g = 0; g < k.size() && g < joint_stiffness.size(); ++g)
    k[g] += joint_stiffness[g];
  return stable_time_step_of(true_mass_, k);
}

void DeformableSolver::zone_forces()
{
  LocalArray x(petsc_->position), v(petsc_->velocity), f(petsc_->force);
  const unsigned int ng = mesh_.n_gridpoints();
  for (unsigned int i = 0; i < 3 * ng; ++i)
  {
    f[i] = gravity_force_[i];
    force_size_[i] = std::abs(gravity_force_[i]);
  }
  // Pressure on boundary faces, in the current geometry: -p n A / 3 on each
  // of the face's gridpoints.
  for (std::size_t k = 0; k < pressed_faces_.size(); ++k)
  {
    const Vec3 share = face_load_share(k, x.data());
    for (unsigned int g : mesh_.face_gridpoint[pressed_faces_[k]])
      for (int d = 0; d < 3; ++d)
      {
        f[3 * g + d] += share[d];
        force_size_[3 * g + d] += std::abs(share[d]);
      }
  }
  if (!pressure_force_.empty())
  {
    std::fill(pressure_force_.begin(), pressure_force_.end(), 0.0);
    for (std::size_t k = 0; k < pressed_faces_.size(); ++k)
    {
      const Vec3 share = face_load_share(k, x.data());
      for (unsigned int g : mesh_.face_gridpoint[pressed_faces_[k]])
        for (int d = 0; d < 3; ++d)
          pressure_force_[3 * g + d] += share[d];
    }
  }
  // The velocities are those of the last motion (x - v dt -> x); before the
  // first motion there is none, so no strain.
  const double strain_dt = step_ == 0 ? 0.0 : dt_;
  if (nodal_mixed_)
  {
    nodal_mixed_zone_forces(x.data(), v.data(), f.data(), strain_dt);
    return;
  }
  // Zones, one batch of one material at a time: strain increments, the
  // material model once for the batch, nodal forces.
  scratch_.resize(zone_batch);
  for (std::size_t r = 0; r + 1 < batch_start_.size(); ++r)
  {
    const ZoneMaterial& mat = materials_[material_of_zone_[batch_start_[r]]];
    for (unsigned int first = batch_start_[r]; first < batch_start_[r + 1]; first += zone_batch)
    {
      const unsigned int n = std::min(zone_batch, batch_start_[r + 1] - first);
      tet4_strain_increments(mesh_, first, n, x.data(), v.data(), strain_dt, stress_.data(),
                             scratch_);
      StressBatch batch;
      batch.size = n;
      batch.strain_increment = scratch_.strain_increment.data();
      batch.stress = stress_.data() + 6 * first;
      batch.state = state_.data() + first;
      // Plastic materials: the stress work of the step, V (s_old + s_new) / 2
      // : d(eps), from which the plastic dissipation follows (elastic ones
      // store all of it, so theirs is not summed).
      const bool plastic = mat.model != ZoneModel::elastic;
      if (plastic)
        plastic_stress_work_ +=
            0.5 * stress_power(n, batch.strain_increment, batch.stress, scratch_.volume.data());
      apply_zone_model(mat, batch);
      if (plastic)
        plastic_stress_work_ +=
            0.5 * stress_power(n, batch.strain_increment, batch.stress, scratch_.volume.data());
      tet4_nodal_forces(mesh_, first, n, stress_.data(), scratch_, f.data(), force_size_.data());
    }
  }
}

void DeformableSolver::nodal_mixed_zone_forces(const double* x, const double* v, double* f,
                                               double strain_dt)
{
  // Nodal mixed discretization (eqs. 68-76) for the zones whose material
  // asks for it: every zone's strain first, then the volumetric part
  // averaged at the gridpoints and back over each zone's four, the model,
  // and the same averaging for the plastic volumetric stress.
  const unsigned int nz = mesh_.n_zones(), ng = mesh_.n_gridpoints();
  full_scratch_.resize(nz);
  tet4_strain_increments(mesh_, 0, nz, x, v, strain_dt, stress_.data(), full_scratch_);
  double* de = full_scratch_.strain_increment.data();
  const double* volume = full_scratch_.volume.data();
  const auto mixed = [&](unsigned int z) { return materials_[material_of_zone_[z]].nodal_mixed; };
  // Eq. 69: volume-weighted nodal averages of the zones' volumetric strain
  // increment (e = trace / 3, eq. 68).
  nodal_sum_.assign(2 * ng, 0.0);
  for (unsigned int z = 0; z < nz; ++z)
    if (mixed(z))
    {
      const double e = (de[6 * z] + de[6 * z + 1] + de[6 * z + 2]) / 3.0;
      for (unsigned int g : mesh_.zone_gridpoint[z])
      {
        nodal_sum_[2 * g] += e * volume[z];
        nodal_sum_[2 * g + 1] += volume[z];
      }
    }
  // Eqs. 70-71: the zone keeps its deviatoric part and takes the mean of
  // its gridpoints' averages as its volumetric part.
  for (unsigned int z = 0; z < nz; ++z)
    if (mixed(z))
    {
      double mean = 0.0;
      for (unsigned int g : mesh_.zone_gridpoint[z])
        mean += 0.25 * nodal_sum_[2 * g] / nodal_sum_[2 * g + 1];
      const double shift = mean - (de[6 * z] + de[6 * z + 1] + de[6 * z + 2]) / 3.0;
      for (int c = 0; c < 3; ++c)
        de[6 * z + c] += shift;
    }
  // The zone models, one material run at a time, with their plastic
  // volumetric strain increments.
  plastic_volumetric_.assign(nz, 0.0);
  bool any_plastic = false;
  for (std::size_t r = 0; r + 1 < batch_start_.size(); ++r)
  {
    const unsigned int first = batch_start_[r];
    StressBatch batch;
    batch.size = batch_start_[r + 1] - first;
    batch.strain_increment = de + 6 * first;
    batch.stress = stress_.data() + 6 * first;
    batch.state = state_.data() + first;
    batch.plastic_volumetric = plastic_volumetric_.data() + first;
    const bool plastic = materials_[material_of_zone_[first]].model != ZoneModel::elastic;
    any_plastic |= plastic;
    if (plastic) // the stress work of the step, as in zone_forces()
      plastic_stress_work_ +=
          0.5 * stress_power(batch.size, batch.strain_increment, batch.stress, volume + first);
    apply_zone_model(materials_[material_of_zone_[first]], batch);
  }
  // Eqs. 73-76: the plastic pressure K e^p (e^p the trace of the plastic
  // strain increment, which lowers the mean stress by K e^p) averaged the
  // same way; each zone trades its own for the mean of its gridpoints'.
  nodal_sum_.assign(2 * ng, 0.0);
  for (unsigned int z = 0; z < nz; ++z)
    if (mixed(z))
    {
      const double sp = materials_[material_of_zone_[z]].bulk_modulus * plastic_volumetric_[z];
      for (unsigned int g : mesh_.zone_gridpoint[z])
      {
        nodal_sum_[2 * g] += sp * volume[z];
        nodal_sum_[2 * g + 1] += volume[z];
      }
    }
  for (unsigned int z = 0; z < nz; ++z)
    if (mixed(z) && plastic_volumetric_[z] != 0.0)
    {
      double mean = 0.0;
      for (unsigned int g : mesh_.zone_gridpoint[z])
        mean += 0.25 * nodal_sum_[2 * g] / nodal_sum_[2 * g + 1];
      const double sp = materials_[material_of_zone_[z]].bulk_modulus * plastic_volumetric_[z];
      for (int c = 0; c < 3; ++c)
        stress_[6 * z + c] += sp - mean;
    }
  if (any_plastic)
    for (std::size_t r = 0; r + 1 < batch_start_.size(); ++r)
      if (materials_[material_of_zone_[batch_start_[r]]].model != ZoneModel::elastic)
      {
        const unsigned int first = batch_start_[r];
        plastic_stress_work_ += 0.5 * stress_power(batch_start_[r + 1] - first, de + 6 * first,
                                                   stress_.data() + 6 * first, volume + first);
      }
  tet4_nodal_forces(mesh_, 0, nz, stress_.data(), full_scratch_, f, force_size_.data());
}

void DeformableSolver::move_gridpoints()
{
  LocalArray x(petsc_->position), v(petsc_->velocity), f(petsc_->force), m(petsc_->inertial_mass);
  const bool combined = !s_.dynamic && s_.damping == Damping::combined;
  // Velocities at half steps (eq. 57): the first kick is half a step.
  const double h = step_ == 0 ? 0.5 * dt_ : dt_;
  double largest = 0.0, size_sum = 0.0;
  unsigned int n_free = 0;
  const unsigned int ng = mesh_.n_gridpoints();
  // Energy account (see EnergyAccount): each force works over h (v- + v+) / 2.
  double gravity_work = 0.0, boundary_work = 0.0, damping_work = 0.0, kinetic = 0.0;
  const bool pressed = !pressure_force_.empty();
  for (unsigned int g = 0; g < ng; ++g)
  {
    double f2 = 0.0, size2 = 0.0;
    for (int d = 0; d < 3; ++d)
    {
      const unsigned int i = 3 * g + d;
      const double weight = true_mass_[g] * s_.gravity[d];
      const double load = gravity_force_[i] - weight + (pressed ? pressure_force_[i] : 0.0);
      if (held_[g] & (1u << d))
      {
        v[i] = held_velocity_[i];
        // The support supplies minus the force on the component.
        const double reach = h * v[i];
        gravity_work += weight * reach;
        boundary_work += (load - f[i]) * reach;
        kinetic += 0.5 * m[i] * v[i] * v[i] - 0.5 * (f[i] - weight - load) * v[i] * dt_;
        continue;
      }
      f2 += f[i] * f[i];
      size2 += force_size_[i] * force_size_[i];
      // Eq. 57 with the static damping chosen (eqs. 77-79, 83).
      const double v_before = v[i];
      const double fd = damper_.kick(v[i], f[i], combined ? last_force_[i] : 0.0, m[i], h);
      if (combined)
        last_force_[i] = f[i];
      const double reach = 0.5 * h * (v_before + v[i]);
      gravity_work += weight * reach;
      boundary_work += load * reach;
      damping_work += fd * reach;
      kinetic += 0.5 * m[i] * v[i] * v[i] - 0.5 * (f[i] - weight - load) * v[i] * dt_;
    }
    if (held_[g] != 7u)
    {
      largest = std::max(largest, std::sqrt(f2));
      size_sum += std::sqrt(size2);
      ++n_free;
    }
    for (int d = 0; d < 3; ++d)
      x[3 * g + d] += v[3 * g + d] * dt_;
  }
  ratio_ = n_free > 0 && size_sum > 0.0 ? largest / (size_sum / n_free) : 0.0;
  gravity_work_ += gravity_work;
  boundary_work_ += boundary_work;
  damping_work_ += damping_work;
  kinetic_whole_step_ = kinetic;
}

void DeformableSolver::step()
{
  compute_forces();
  check_finite_forces(step_ + 1, dt_);
  move();
  if (s_.dynamic) // statics: scaled masses, gridpoints held at velocities set later
  {
    EnergyAccount e;
    add_work(e);
    if (growth_watch_.diverging(step_, e.kinetic,
                                std::abs(e.initial_stored) + std::abs(e.gravity_work) +
                                    std::abs(e.boundary_work),
                                1e-6))
      throw DivergenceError("the run diverged at step " + std::to_string(step_) +
                            ": the kinetic energy, " + number(e.kinetic) +
                            " J, has grown far beyond its sources; " + divergence_site(dt_));
  }
}

void DeformableSolver::add_work(EnergyAccount& e) const
{
  e.gravity_work += gravity_work_;
  e.boundary_work += boundary_work_;
  e.damping += damping_work_;
  e.kinetic += kinetic_whole_step_;
  e.initial_stored += initial_elastic_;
}

void DeformableSolver::add_energy(EnergyAccount& e) const
{
  add_work(e);
  LocalArray x(petsc_->position);
  const auto [elastic, plastic_elastic] = elastic_energy(x.data());
  e.zone_elastic += elastic;
  // Plastic dissipation: the stress work of plastic zones less the change
  // of their elastic energy.
  e.plastic += plastic_stress_work_ - (plastic_elastic - initial_plastic_elastic_);
}

std::pair<double, double> DeformableSolver::elastic_energy(const double* x) const
{
  // V / 2 sigma : C^-1 : sigma = V / 2 (p^2 / K + s : s / (2 G)).
  double all = 0.0, plastic = 0.0;
  for (unsigned int z = 0; z < mesh_.n_zones(); ++z)
  {
    const ZoneMaterial& mat = materials_[material_of_zone_[z]];
    const double* s = &stress_[6 * z];
    const double p = (s[0] + s[1] + s[2]) / 3.0;
    const double ss = (s[0] - p) * (s[0] - p) + (s[1] - p) * (s[1] - p) + (s[2] - p) * (s[2] - p) +
                      2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]);
    const double e = 0.5 * tet_volume(x, mesh_.zone_gridpoint[z]) *
                     (p * p / mat.bulk_modulus + ss / (2.0 * mat.shear_modulus));
    all += e;
    if (mat.model != ZoneModel::elastic)
      plastic += e;
  }
  return {all, plastic};
}

std::pair<unsigned int, double> DeformableSolver::smallest_zone_at(unsigned int g,
                                                                   const double* x) const
{
  // A pass over the zones, only when a run has failed.
  unsigned int best = 0;
  double smallest = 1e300;
  for (unsigned int z = 0; z < mesh_.n_zones(); ++z)
    for (unsigned int a : mesh_.zone_gridpoint[z])
      if (a == g && tet_volume(x, mesh_.zone_gridpoint[z]) < smallest)
      {
        smallest = tet_volume(x, mesh_.zone_gridpoint[z]);
        best = z;
      }
  return {best, smallest};
}

void DeformableSolver::check_finite_forces(unsigned long step, double dt) const
{
  LocalArray f(petsc_->force);
  const unsigned int n = 3 * mesh_.n_gridpoints();
  double sum = 0.0;
  for (unsigned int i = 0; i < n; ++i)
    sum += f[i];
  if (std::isfinite(sum))
    return;
  unsigned int g = 0;
  while (g + 1 < n / 3 && std::isfinite(f[3 * g]) && std::isfinite(f[3 * g + 1]) &&
         std::isfinite(f[3 * g + 2]))
    ++g;
  LocalArray x(petsc_->position);
  const auto [zone, volume] = smallest_zone_at(g, x.data());
  throw DivergenceError(
      "the run diverged at step " + std::to_string(step) + ": the force on gridpoint " +
      std::to_string(g) + " (zone " + std::to_string(zone) + ") is not finite; likely cause: " +
      (volume <= 0.0
           ? "zone " + std::to_string(zone) + " is inverted (volume " + number(volume) + " m^3)"
           : "the time step " + number(dt) + " s against the stable step of the zones, " +
                 number(stable_time_step()) + " s (eq. 84)"));
}

double DeformableSolver::largest_gridpoint_energy() const
{
  LocalArray v(petsc_->velocity), m(petsc_->inertial_mass);
  double largest = 0.0;
  for (unsigned int i = 0; i < 3 * mesh_.n_gridpoints(); i += 3)
    largest =
        std::max(largest, 0.5 * m[i] * (v[i] * v[i] + v[i + 1] * v[i + 1] + v[i + 2] * v[i + 2]));
  return largest;
}

std::string DeformableSolver::divergence_site(double dt) const
{
  LocalArray v(petsc_->velocity), m(petsc_->inertial_mass), x(petsc_->position);
  unsigned int worst = 0;
  double largest = -1.0;
  for (unsigned int g = 0; g < mesh_.n_gridpoints(); ++g)
  {
    const unsigned int i = 3 * g;
    const double e = 0.5 * m[i] * (v[i] * v[i] + v[i + 1] * v[i + 1] + v[i + 2] * v[i + 2]);
    if (e > largest)
    {
      largest = e;
      worst = g;
    }
  }
  const auto [zone, volume] = smallest_zone_at(worst, x.data());
  std::string cause;
  if (volume <= 0.0)
    cause = "zone " + std::to_string(zone) + " is inverted (volume " + number(volume) + " m^3)";
  else
    cause = "the time step " + number(dt) +
            " s is too large for the zones or the joints on them: "
            "eq. 84 with the joint stiffness gives at most " +
            number(stable_time_step()) + " s";
  return "gridpoint " + std::to_string(worst) + " of zone " + std::to_string(zone) +
         " moves fastest; likely cause: " + cause;
}

void DeformableSolver::compute_forces()
{
  const auto t0 = std::chrono::steady_clock::now();
  zone_forces();
  seconds_zones_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void DeformableSolver::move()
{
  const auto t0 = std::chrono::steady_clock::now();
  move_gridpoints();
  if ((step_ + 1) % Damper::servo_period == 0)
    damper_.adjust();
  time_ += dt_;
  ++step_;
  seconds_gridpoints_ +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

DeformableSolver::View::View(DeformableSolver& solver) : solver_(solver)
{
  VecGetArray(static_cast<const Vec&>(solver_.petsc_->position), &x);
  VecGetArray(static_cast<const Vec&>(solver_.petsc_->velocity), &v);
  VecGetArray(static_cast<const Vec&>(solver_.petsc_->force), &f);
}

DeformableSolver::View::~View()
{
  VecRestoreArray(static_cast<const Vec&>(solver_.petsc_->position), &x);
  VecRestoreArray(static_cast<const Vec&>(solver_.petsc_->velocity), &v);
  VecRestoreArray(static_cast<const Vec&>(solver_.petsc_->force), &f);
}

void DeformableSolver::use_time_step(double dt, const std::vector<double>& joint_stiffness)
{
  const unsigned int ng = mesh_.n_gridpoints();
  std::vector<double> k = nodal_stiffness_;
  for (unsigned int g = 0; g < ng && g < joint_stiffness.size(); ++g)
    k[g] += joint_stiffness[g];
  const bool scaled = !s_.dynamic && s_.density_scaling;
  if (!scaled && dt > stable_time_step_of(true_mass_, k) * (1.0 + 1e-12))
    throw InputError("the time step " + number(dt) + " s exceeds the stable step of the zones, " +
                     number(stable_time_step_of(true_mass_, k)) + " s (eq. 84)");
  dt_ = dt;
  LocalArray m(petsc_->inertial_mass);
  for (unsigned int g = 0; g < ng; ++g)
    for (int d = 0; d < 3; ++d)
      m[3 * g + d] = scaled ? std::max(true_mass_[g], k[g] * dt * dt / 4.0) : true_mass_[g];
  damper_ = Damper(s_.dynamic ? Damping::none : s_.damping, s_.local_damping,
                   s_.global_damping_ratio, dt_);
}

unsigned long DeformableSolver::run_to_ratio(double ratio, unsigned long max_steps)
{
  unsigned long n = 0;
  while ((n < 20 || ratio_ >= ratio) && n < max_steps)
  {
    step();
    ++n;
  }
  return n;
}

std::vector<double> DeformableSolver::positions() const
{
  LocalArray x(petsc_->position);
  return std::vector<double>(x.data(), x.data() + 3 * mesh_.n_gridpoints());
}

std::vector<double> DeformableSolver::displacements() const
{
  std::vector<double> u = positions();
  for (std::size_t i = 0; i < u.size(); ++i)
    u[i] -= mesh_.position[i];
  return u;
}

std::vector<double> DeformableSolver::velocities() const
{
  LocalArray v(petsc_->velocity);
  return std::vector<double>(v.data(), v.data() + 3 * mesh_.n_gridpoints());
}

void DeformableSolver::hold_gridpoint(unsigned int g, const Vec3& v)
{
  // Takes effect at the next motion: the velocity that brought the
  // gridpoint here is still needed for the strain of the coming step.
  held_[g] = 7u;
  for (int d = 0; d < 3; ++d)
    held_velocity_[3 * g + d] = v[d];
}

Vec3 DeformableSolver::support_force(const Box& region) const
{
  // The unbalanced force of the last step at held gridpoints is what the
  // support must supply, reversed.
  LocalArray f(petsc_->force);
  Vec3 sum = Vec3::Zero();
  for (unsigned int g = 0; g < mesh_.n_gridpoints(); ++g)
    if (held_[g] != 0 && inside(region, &mesh_.position[3 * g]))
      for (int d = 0; d < 3; ++d)
        if (held_[g] & (1u << d))
          sum[d] += f[3 * g + d];
  return sum;
}

Vec3 DeformableSolver::face_load_share(std::size_t k, const double* x) const
{
  const auto& t = mesh_.face_gridpoint[pressed_faces_[k]];
  const Vec3 a(x[3 * t[0]], x[3 * t[0] + 1], x[3 * t[0] + 2]);
  const Vec3 b(x[3 * t[1]], x[3 * t[1] + 1], x[3 * t[1] + 2]);
  const Vec3 c(x[3 * t[2]], x[3 * t[2] + 1], x[3 * t[2] + 2]);
  const Vec3 area_normal = 0.5 * (b - a).cross(c - a); // outward, |.| = area
  // -p n A + t A, shared equally by the three gridpoints.
  return (-face_pressure_[k] * area_normal + face_traction_[k] * area_normal.norm()) / 3.0;
}

ImplicitElasticProblem DeformableSolver::implicit_problem() const
{
  ImplicitElasticProblem p;
  p.mesh = &mesh_;
  for (unsigned int z = 0; z < mesh_.n_zones(); ++z)
  {
    p.zone_bulk.push_back(materials_[material_of_zone_[z]].bulk_modulus);
    p.zone_shear.push_back(materials_[material_of_zone_[z]].shear_modulus);
  }
  p.nodal_force = gravity_force_;
  for (std::size_t k = 0; k < pressed_faces_.size(); ++k)
  {
    const Vec3 share = face_load_share(k, mesh_.position.data());
    for (unsigned int g : mesh_.face_gridpoint[pressed_faces_[k]])
      for (int d = 0; d < 3; ++d)
        p.nodal_force[3 * g + d] += share[d];
  }
  p.fixed = held_;
  return p;
}

} // namespace talus
