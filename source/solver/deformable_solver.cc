#include <talus/base/archive.h>
#include <talus/base/exact_sum.h>
#include <talus/base/exceptions.h>
#include <talus/base/wall_clock.h>
#include <talus/solver/deformable_solver.h>
#include <talus/solver/ghost_exchange.h>
#include <talus/solver/water_loads.h>
#include <talus/zone/hex_mixed.h>
#include <talus/zone/nodal_mixed.h>
#include <talus/zone/tet10_mesh.h>
#include <talus/zone/viscous_stress.h>
#include <talus/zone/zone_models.h>

#include <deal.II/lac/petsc_vector.h>

#include <petscsys.h>
#include <petscvec.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

namespace talus
{

namespace
{
/// 10-node zones: whether each gridpoint is a zone's vertex (not a
/// midpoint); empty for 4-node zones.
std::vector<char> zone_vertices(const TetMesh& mesh)
{
  std::vector<char> is_vertex(mesh.quadratic() ? mesh.n_gridpoints() : 0, 0);
  if (mesh.quadratic())
    for (const auto& t : mesh.zone_gridpoint)
      for (unsigned int g : t)
        is_vertex[g] = 1;
  return is_vertex;
}

bool inside(const ConvexRegion& r, const double* p)
{
  return r.holds(Vec3(p[0], p[1], p[2]));
}

/// The raw array of a gridpoint vector: a ghosted vector's local form
/// (owned entries, then the ghosts), or the vector itself.
double* get_local_array(Vec v, Vec& form)
{
  form = nullptr;
  PetscBool ghosted = PETSC_FALSE;
  PetscObjectTypeCompare(reinterpret_cast<PetscObject>(v), VECMPI, &ghosted);
  if (ghosted)
    VecGhostGetLocalForm(v, &form); // null when the vector has no ghosts
  double* data = nullptr;
  VecGetArray(form != nullptr ? form : v, &data);
  return data;
}

void restore_local_array(Vec v, Vec& form, double*& data)
{
  VecRestoreArray(form != nullptr ? form : v, &data);
  if (form != nullptr)
    VecGhostRestoreLocalForm(v, &form);
}

/// The raw local array of a PETSc vector for the length of one stage.
class LocalArray
{
public:
  explicit LocalArray(const dealii::PETScWrappers::MPI::Vector& v) : vec_(v)
  {
    data_ = get_local_array(vec_, form_);
  }
  ~LocalArray() { restore_local_array(vec_, form_, data_); }
  double* data() { return data_; }
  double& operator[](std::size_t i) { return data_[i]; }

private:
  Vec vec_, form_ = nullptr;
  double* data_ = nullptr;
};

constexpr unsigned int zone_batch = 1024; ///< zones per kernel call (fits in cache)

/// Zones per kernel call for a material: hexahedral zones in whole
/// hexahedra (their averages are taken over a hexahedron's ten tetrahedra).
unsigned int zone_chunk(const ZoneMaterial& m)
{
  return m.element == ZoneElement::hex_mixed
             ? zone_batch / TetMesh::tets_per_hex * TetMesh::tets_per_hex
             : zone_batch;
}

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

/// The volume each Gauss point of 10-node zone z stands for in the current
/// geometry `x` (m^3): w_q det J(xi_q) with w_q = 1/24, J = sum_n x_n (x)
/// grad_xi N_n (N_i = l_i (2 l_i - 1) at vertices, 4 l_i l_j at the
/// midpoint of edge i-j; l_0 = 1 - xi - eta - zeta). The midpoints move
/// with the zone, so under large strain its edges curve and the corners'
/// volume is not the zone's.
void tet10_gauss_volumes(const TetMesh& mesh, unsigned int z, const double* x, double* volume)
{
  static constexpr unsigned int edge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  unsigned int node[10];
  for (int i = 0; i < 4; ++i)
    node[i] = mesh.zone_gridpoint[z][i];
  for (int e = 0; e < 6; ++e)
    node[4 + e] = mesh.zone_edge_gridpoint[z][e];
  for (int q = 0; q < 4; ++q)
  {
    double l[4];
    for (int m = 0; m < 4; ++m)
      l[m] = m == q ? tet10_gauss_b : tet10_gauss_a;
    // dN/dl_m of every node, then dN/dxi_k = dN/dl_k - dN/dl_0 (k = 1..3).
    double dl[10][4] = {};
    for (int i = 0; i < 4; ++i)
      dl[i][i] = 4.0 * l[i] - 1.0;
    for (int e = 0; e < 6; ++e)
    {
      dl[4 + e][edge[e][0]] = 4.0 * l[edge[e][1]];
      dl[4 + e][edge[e][1]] = 4.0 * l[edge[e][0]];
    }
    Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
    for (int n = 0; n < 10; ++n)
      for (int k = 0; k < 3; ++k)
        for (int d = 0; d < 3; ++d)
          J(d, k) += x[3 * node[n] + d] * (dl[n][k + 1] - dl[n][0]);
    volume[q] = J.determinant() / 24.0;
  }
}
/// The indices i with key[i] below n_keys, listed by key and in order
/// within one key (a counting sort): those of key k are
/// items[start[k] .. start[k + 1]).
void list_by_key(const std::vector<unsigned int>& key, unsigned int n_keys,
                 std::vector<unsigned int>& start, std::vector<unsigned int>& items)
{
  start.assign(n_keys + 1, 0);
  for (unsigned int k : key)
    if (k < n_keys)
      ++start[k + 1];
  for (unsigned int k = 0; k < n_keys; ++k)
    start[k + 1] += start[k];
  items.resize(start[n_keys]);
  std::vector<unsigned int> fill(start.begin(), start.end() - 1);
  for (unsigned int i = 0; i < key.size(); ++i)
    if (key[i] < n_keys)
      items[fill[key[i]]++] = i;
}
} // namespace

/// Gridpoint state, 3 numbers per gridpoint in each vector.
struct DeformableSolver::PetscState
{
  dealii::PETScWrappers::MPI::Vector position, velocity, force, inertial_mass;
  /// Split among ranks with nodal mixed discretization: the gridpoint
  /// averages of eq. 69 (two numbers a gridpoint: the average and the
  /// volume) and of eq. 75 (one), sent from their owners to the ghosts.
  dealii::PETScWrappers::MPI::Vector strain_pairs, plastic_average;
};

DeformableSolver::DeformableSolver(const TetMesh& mesh, std::vector<ZoneMaterial> materials,
                                   std::vector<unsigned int> material_of_zone,
                                   const SolverSettings& settings,
                                   std::vector<GridpointCondition> conditions,
                                   std::vector<FacePressure> pressures,
                                   const InitialStress* initial, const GridpointShare* share)
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
  {
    nodal_mixed_ |= m.nodal_mixed;
    if (m.nodal_mixed && m.element == ZoneElement::hex_mixed)
      throw InputError("internal: nodal mixed discretization and hex-mixed zones do not combine");
    if ((m.element == ZoneElement::tet10) != mesh_.quadratic())
      throw InputError("internal: the zone type of a material does not match the mesh "
                       "(make_quadratic makes 10-node zones)");
  }
  if (mesh_.quadratic() && nodal_mixed_)
    throw InputError("nodal mixed discretization is for 4-node zones only; 10-node zones do "
                     "not lock and need none (allowed: Element tet4 with it, or tet10 without)");
  points_per_zone_ = mesh_.quadratic() ? 4 : 1;
  // Batches: runs of one material.
  for (unsigned int z = 0; z < nz; ++z)
    if (z == 0 || material_of_zone_[z] != material_of_zone_[z - 1])
      batch_start_.push_back(z);
  batch_start_.push_back(nz);
  // Hexahedral zones (eqs. 60-67): each material run of hex-mixed zones
  // must be whole hexahedra, and only hex-mixed zones may be in one.
  const std::vector<char> in_hex = zones_in_hexes(mesh_);
  {
    std::vector<char> hex_start(nz + 1, 0);
    for (unsigned int first : mesh_.hex_first_zone)
      hex_start[first] = 1;
    hex_start[nz] = 1;
    for (std::size_t r = 0; r + 1 < batch_start_.size(); ++r)
    {
      const bool hex =
          materials_[material_of_zone_[batch_start_[r]]].element == ZoneElement::hex_mixed;
      bool whole = hex_start[batch_start_[r]] && hex_start[batch_start_[r + 1]];
      for (unsigned int z = batch_start_[r]; z < batch_start_[r + 1]; ++z)
        whole &= in_hex[z] == hex;
      if (hex ? !whole
              : std::count(in_hex.begin() + batch_start_[r], in_hex.begin() + batch_start_[r + 1],
                           1) != 0)
        throw InputError("internal: hex-mixed zones must be whole hexahedra of the mesh, and "
                         "hexahedra of the mesh must have a hex-mixed material");
    }
  }

  // Initial stress.
  stress_.assign(6 * points_per_zone_ * nz, 0.0);
  state_.assign(points_per_zone_ * nz, 0);
  if (initial != nullptr && mesh_.quadratic())
    for (unsigned int z = 0; z < nz; ++z)
    {
      double point[4][3];
      tet10_gauss_points(mesh_, z, point);
      for (int q = 0; q < 4; ++q)
        initial->at(point[q][2], &stress_[6 * (4 * z + q)]);
    }
  else if (initial != nullptr)
    for (unsigned int z = 0; z < nz; ++z)
    {
      double zc = 0.0;
      for (unsigned int a = 0; a < 4; ++a)
        zc += 0.25 * mesh_.position[3 * mesh_.zone_gridpoint[z][a] + 2];
      initial->at(zc, &stress_[6 * z]);
    }
  if (initial != nullptr)
    for (unsigned int h = 0; h < mesh_.n_hexes(); ++h)
    {
      // The ten tetrahedra of a hexahedron start at its centroid's stress,
      // so that they share one mean stress (eq. 67).
      double zc = 0.0;
      for (unsigned int g : mesh_.hex_gridpoint[h])
        zc += 0.125 * mesh_.position[3 * g + 2];
      for (unsigned int k = 0; k < TetMesh::tets_per_hex; ++k)
        initial->at(zc, &stress_[6 * (mesh_.hex_first_zone[h] + k)]);
    }

  // Masses: a quarter of each zone's mass to each of its gridpoints; and
  // the stiffness of eq. 86 summed at each gridpoint (eq. 85). The
  // tetrahedra of a hexahedral zone count half, as each overlay fills it.
  std::vector<double> mass, stiffness;
  zone_masses(mass, stiffness);
  gravity_force_.assign(3 * ng, 0.0);
  for (unsigned int g = 0; g < ng; ++g)
    for (int d = 0; d < 3; ++d)
      gravity_force_[3 * g + d] = mass[g] * s_.gravity[d]; // eq. 56

  n_moved_ = ng;
  if (share != nullptr)
  {
    share_ = std::make_unique<GridpointShare>(*share);
    n_moved_ = share_->n_owned;
  }

  // Time step (eq. 84); statics with density scaling: unit time step and
  // each gridpoint's inertial mass set from its stiffness, m = k dt^2 / 4.
  const bool scaled = !s_.dynamic && s_.density_scaling;
  const double beta = s_.stiffness_damping(); // Rayleigh, s
  if (s_.time_step > 0.0)
  {
    dt_ = s_.time_step;
    if (!scaled && !s_.raises_mass() && dt_ > step_of(mass, stiffness, beta))
      throw InputError(s_.source + ": entry 'Time step' in subsection 'Solver': " + number(dt_) +
                       " s is larger than the stable step of the zones, " +
                       number(step_of(mass, stiffness, beta)) + " s (eq. 84" +
                       (beta > 0.0 ? " with Rayleigh beta" : "") +
                       "); allowed: at most that, 0 for the automatic step, or 'Partial density "
                       "scaling = true' to add mass where the step needs it");
  }
  else
    dt_ = scaled ? 1.0 : step_of(mass, stiffness, beta);
  petsc_ = std::make_unique<PetscState>();
  if (share != nullptr)
  {
    // Split among ranks: vectors of the whole model, this rank's
    // gridpoints as its range and the ghosts as ghost entries.
    unsigned long mine = n_moved_, before = 0, all = 0;
    MPI_Exscan(&mine, &before, 1, MPI_UNSIGNED_LONG, MPI_SUM, share_->comm);
    MPI_Allreduce(&mine, &all, 1, MPI_UNSIGNED_LONG, MPI_SUM, share_->comm);
    int rank = 0;
    MPI_Comm_rank(share_->comm, &rank);
    if (rank == 0)
      before = 0; // MPI_Exscan leaves rank 0's undefined
    dealii::IndexSet owned(3 * all), ghosts(3 * all);
    owned.add_range(3 * before, 3 * (before + mine));
    for (unsigned int k : share_->ghost_index)
      ghosts.add_range(3 * std::size_t(k), 3 * std::size_t(k) + 3);
    if (ghosts.n_elements() != 3 * (ng - n_moved_))
      throw std::logic_error("DeformableSolver: one ghost index per ghost gridpoint is needed");
    for (auto* v : {&petsc_->position, &petsc_->velocity, &petsc_->force, &petsc_->inertial_mass})
      v->reinit(owned, ghosts, share_->comm);
    share_nodal_mixed();
    nodal_mixed_ |= nmd_on_ranks_[0];
  }
  else // this rank's own (a collective on the world would wait for the other ranks)
    for (auto* v : {&petsc_->position, &petsc_->velocity, &petsc_->force, &petsc_->inertial_mass})
      v->reinit(MPI_COMM_SELF, 3 * ng, 3 * ng);
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
  reference_ = mesh_.position;
  if (s_.raises_mass())
    set_inertial_masses(); // partial density scaling (eq. 89)

  apply_conditions();
  {
    LocalArray v(petsc_->velocity);
    for (unsigned int i = 0; i < 3 * ng; ++i)
      v[i] = held_velocity_at(i, 0.0);
  }
  select_pressed_faces();
  select_water_faces();
  force_size_.assign(3 * ng, 0.0);
  if (!pressed_faces_.empty() || !water_faces_.empty() || !quiet_waves_.empty())
    pressure_force_.assign(3 * ng, 0.0);
  std::tie(initial_elastic_, initial_plastic_elastic_) = elastic_energy(mesh_.position.data());
  {
    // Held velocities are there from the start: energy at the start.
    LocalArray m(petsc_->inertial_mass);
    for (unsigned int i = 0; i < 3 * n_moved_; ++i)
      initial_elastic_ += 0.5 * m[i] * held_velocity_at(i, 0.0) * held_velocity_at(i, 0.0);
  }
  damper_ = damper_for(s_, dt_);
  if (!s_.dynamic && s_.damping == Damping::combined)
    last_force_.assign(3 * ng, 0.0);
  if (nodal_mixed_)
    plan_nodal_mixed();
}

void DeformableSolver::set_gravity_and_loads()
{
  const unsigned int ng = mesh_.n_gridpoints();
  for (unsigned int g = 0; g < ng; ++g)
    for (int d = 0; d < 3; ++d)
      gravity_force_[3 * g + d] = true_mass_[g] * s_.gravity[d]; // eq. 56
  timed_load_points_.clear();
  for (unsigned int g = 0; g < ng; ++g)
    for (const GridpointCondition& c : conditions_)
      if (inside(c.region, &mesh_.position[3 * g]))
      {
        if (c.motion.varies()) // added step by step (external_forces)
          timed_load_points_.emplace_back(g, unsigned(&c - conditions_.data()));
        else
          for (int d = 0; d < 3; ++d)
            gravity_force_[3 * g + d] += c.force[d];
      }
  steady_gravity_force_.clear();
  if (!timed_load_points_.empty())
    steady_gravity_force_ = gravity_force_;
}

void DeformableSolver::apply_conditions()
{
  // By the gridpoints' initial positions, whatever they have moved since.
  const unsigned int ng = mesh_.n_gridpoints();
  held_.assign(ng, 0);
  held_velocity_.assign(3 * ng, 0.0);
  held_until_.assign(3 * ng, std::numeric_limits<double>::infinity());
  held_motion_.assign(3 * ng, -1);
  motion_scale_.assign(conditions_.size(), 1.0);
  for (unsigned int g = 0; g < ng; ++g)
    for (const GridpointCondition& c : conditions_)
      if (inside(c.region, &mesh_.position[3 * g]))
        for (int d = 0; d < 3; ++d)
          if (c.held[d])
          {
            held_[g] |= 1u << d;
            held_velocity_[3 * g + d] =
                c.velocity[d] + c.velocity_gradient.row(d).dot(Vec3(mesh_.position[3 * g],
                                                                    mesh_.position[3 * g + 1],
                                                                    mesh_.position[3 * g + 2]));
            held_until_[3 * g + d] = c.velocity_until;
            held_motion_[3 * g + d] = c.motion.varies() ? int(&c - conditions_.data()) : -1;
          }
  // A gridpoint of removed zones only stays where it is.
  if (!removed_zone_.empty())
    for (unsigned int g = 0; g < ng; ++g)
      if (true_mass_[g] == 0.0)
      {
        held_[g] = 7u;
        std::fill_n(&held_velocity_[3 * g], 3, 0.0);
        std::fill_n(&held_motion_[3 * g], 3, -1);
      }
  set_gravity_and_loads();
}

void DeformableSolver::select_pressed_faces()
{
  pressed_faces_.clear();
  face_pressure_.clear();
  face_traction_.clear();
  face_function_.clear();
  pressure_scale_.assign(pressures_.size(), 1.0);
  face_share_.clear();
  const std::vector<char> in_hex = zones_in_hexes(mesh_);
  // Loaded faces: the boundary triangles; those of hexahedral zones once
  // for each overlay's split of the boundary quadrilaterals, each half.
  // 10-node zones: a zone vertex (not a midpoint) is where a boundary
  // sub-triangle takes no load.
  const std::vector<char> is_vertex = zone_vertices(mesh_);
  const auto press = [&](const std::array<unsigned int, 3>& face, double weight)
  {
    double c[3] = {0, 0, 0};
    for (unsigned int g : face)
      for (int d = 0; d < 3; ++d)
        c[d] += mesh_.position[3 * g + d] / 3.0;
    for (const FacePressure& p : pressures_)
      if (!p.quiet && inside(p.region, c))
      {
        pressed_faces_.push_back(face);
        face_pressure_.push_back(p.pressure);
        face_traction_.push_back(p.traction);
        face_function_.push_back(p.motion.varies() ? int(&p - pressures_.data()) : -1);
        // Share of the face's load on each of its gridpoints (times the
        // overlay weight of hexahedral zones). A 10-node
        // zone's face is four sub-triangles; the consistent load of a
        // uniform pressure on a 6-node triangle is nothing at the vertices
        // and a third at each midpoint, which the sub-triangles give when
        // a corner one puts half its load on each of its two midpoints and
        // the middle one a third on each (2 A/8 + A/12 = A/3).
        std::array<double, 3> share{{1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0}};
        for (int k = 0; k < 3 && mesh_.quadratic(); ++k)
          if (is_vertex[face[k]])
          {
            share = {{0.5, 0.5, 0.5}};
            share[k] = 0.0;
          }
        for (double& w : share)
          w *= weight;
        face_share_.push_back(share);
        break;
      }
  };
  for (unsigned int f = 0; f < mesh_.n_faces(); ++f)
    press(mesh_.face_gridpoint[f], in_hex[mesh_.face_zone[f]] ? 0.5 : 1.0);
  for (const auto& face : mesh_.second_overlay_face_gridpoint)
    press(face, 0.5);
  select_quiet_faces(in_hex, is_vertex);
}

void DeformableSolver::select_quiet_faces(const std::vector<char>& in_hex,
                                          const std::vector<char>& is_vertex)
{
  quiet_faces_.clear();
  quiet_share_.clear();
  quiet_area_.clear();
  quiet_wave_.clear();
  quiet_waves_.clear();
  quiet_wave_direction_.clear();
  quiet_slot_.clear();
  quiet_c_.clear();
  std::vector<unsigned int> wave_of_pressure(pressures_.size(), ~0u);
  for (std::size_t i = 0; i < pressures_.size(); ++i)
    if (pressures_[i].quiet && pressures_[i].wave.active())
    {
      wave_of_pressure[i] = static_cast<unsigned int>(quiet_waves_.size());
      quiet_waves_.push_back(pressures_[i].wave);
      quiet_wave_direction_.push_back(pressures_[i].wave_direction);
    }
  // The second overlay's faces: the zone of the hexahedron holding all
  // three corners (one boundary quadrilateral has one hexahedron).
  std::vector<std::vector<unsigned int>> hexes_at;
  if (!mesh_.second_overlay_face_gridpoint.empty())
  {
    hexes_at.resize(mesh_.n_gridpoints());
    for (unsigned int h = 0; h < mesh_.n_hexes(); ++h)
      for (unsigned int g : mesh_.hex_gridpoint[h])
        hexes_at[g].push_back(h);
  }
  const auto hex_zone_of = [&](const std::array<unsigned int, 3>& face)
  {
    for (unsigned int h : hexes_at[face[0]])
    {
      const auto& corners = mesh_.hex_gridpoint[h];
      const auto has = [&](unsigned int g)
      { return std::find(corners.begin(), corners.end(), g) != corners.end(); };
      if (has(face[1]) && has(face[2]))
        return mesh_.hex_first_zone[h];
    }
    return 0u;
  };
  const auto quiet = [&](const std::array<unsigned int, 3>& face, unsigned int zone, double weight)
  {
    if (zone_removed(zone))
      return;
    const double* p0 = &mesh_.position[3 * face[0]];
    const double* p1 = &mesh_.position[3 * face[1]];
    const double* p2 = &mesh_.position[3 * face[2]];
    const double c[3] = {(p0[0] + p1[0] + p2[0]) / 3.0, (p0[1] + p1[1] + p2[1]) / 3.0,
                         (p0[2] + p1[2] + p2[2]) / 3.0};
    for (std::size_t i = 0; i < pressures_.size(); ++i)
      if (pressures_[i].quiet && inside(pressures_[i].region, c))
      {
        // The shares of a pressure (select_pressed_faces): a third at each
        // corner, a 10-node face's load on its midpoints, half on each
        // overlay's split of a hexahedral zone's face.
        std::array<double, 3> share{{1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0}};
        for (int k = 0; k < 3 && mesh_.quadratic(); ++k)
          if (is_vertex[face[k]])
          {
            share = {{0.5, 0.5, 0.5}};
            share[k] = 0.0;
          }
        for (double& w : share)
          w *= weight;
        const Vec3 a(p0[0], p0[1], p0[2]), b(p1[0], p1[1], p1[2]), e(p2[0], p2[1], p2[2]);
        const Vec3 area = 0.5 * (b - a).cross(e - a); // A n, outward
        quiet_faces_.push_back(face);
        quiet_share_.push_back(share);
        quiet_area_.push_back(area);
        quiet_wave_.push_back(wave_of_pressure[i]);
        // Lysmer and Kuhlemeyer: t = -rho cp (v.n) n - rho cs (v - (v.n) n).
        const ZoneMaterial& mat = materials_[material_of_zone_[zone]];
        const double rho = mat.density;
        const double cp = std::sqrt((mat.bulk_modulus + 4.0 * mat.shear_modulus / 3.0) / rho);
        const double cs = std::sqrt(mat.shear_modulus / rho);
        const double A = area.norm();
        const Vec3 n = area / A;
        const double cn = rho * cp * A, ct = rho * cs * A;
        if (quiet_slot_.empty())
          quiet_slot_.assign(mesh_.n_gridpoints(), -1);
        for (int k = 0; k < 3; ++k)
        {
          if (share[k] == 0.0)
            continue;
          int& slot = quiet_slot_[face[k]];
          if (slot < 0)
          {
            slot = static_cast<int>(quiet_c_.size());
            quiet_c_.push_back({{0, 0, 0, 0, 0, 0}});
          }
          auto& cg = quiet_c_[slot];
          const int row[6] = {0, 1, 2, 0, 1, 2}, col[6] = {0, 1, 2, 1, 2, 0};
          for (int j = 0; j < 6; ++j)
            cg[j] += share[k] * ((cn - ct) * n[row[j]] * n[col[j]] + (j < 3 ? ct : 0.0));
        }
        break;
      }
  };
  for (unsigned int f = 0; f < mesh_.n_faces(); ++f)
    quiet(mesh_.face_gridpoint[f], mesh_.face_zone[f], in_hex[mesh_.face_zone[f]] ? 0.5 : 1.0);
  for (const auto& face : mesh_.second_overlay_face_gridpoint)
    quiet(face, hex_zone_of(face), 0.5);
}

void DeformableSolver::select_water_faces()
{
  water_faces_.clear();
  water_weight_.clear();
  if (!s_.water.active())
    return;
  // Water on every boundary face, in contact or not (water_loads.h).
  const std::vector<char> in_hex = zones_in_hexes(mesh_);
  for (unsigned int f = 0; f < mesh_.n_faces(); ++f)
  {
    water_faces_.push_back(mesh_.face_gridpoint[f]);
    water_weight_.push_back(in_hex[mesh_.face_zone[f]] ? 0.5 : 1.0);
  }
  for (const auto& face : mesh_.second_overlay_face_gridpoint)
  {
    water_faces_.push_back(face);
    water_weight_.push_back(0.5);
  }
  water_vertex_corner_.clear();
  if (mesh_.quadratic())
  {
    const std::vector<char> is_vertex = zone_vertices(mesh_);
    for (const auto& face : water_faces_)
    {
      int v = -1;
      for (int j = 0; j < 3; ++j)
        if (is_vertex[face[j]])
          v = j;
      water_vertex_corner_.push_back(v);
    }
  }
}

void DeformableSolver::set_face_origins(std::vector<int> origins)
{
  if (origins.size() != mesh_.n_faces() + mesh_.second_overlay_face_gridpoint.size())
    throw InputError("internal: one face origin per boundary face of the zones is needed");
  water_face_origin_ = std::move(origins);
}

void DeformableSolver::set_water(const WaterSpec& water)
{
  s_.water = water;
  select_water_faces();
  water_faces_below_ = 0;
  water_force_ = Vec3::Zero();
  water_force_sum_.assign(3, ExactSum());
  if (pressed_faces_.empty() && water_faces_.empty())
    pressure_force_.clear();
  else
    pressure_force_.assign(3 * mesh_.n_gridpoints(), 0.0);
}

void DeformableSolver::set_boundaries(std::vector<GridpointCondition> conditions,
                                      std::vector<FacePressure> pressures)
{
  conditions_ = std::move(conditions);
  pressures_ = std::move(pressures);
  // A component held from now on takes its velocity at the next motion,
  // which accounts for the kinetic energy that takes (move_gridpoints); a
  // component let go keeps the velocity it has.
  apply_conditions();
  select_pressed_faces();
  if (pressed_faces_.empty() && water_faces_.empty() && quiet_waves_.empty())
    pressure_force_.clear();
  else
    pressure_force_.assign(3 * mesh_.n_gridpoints(), 0.0);
}

void DeformableSolver::zone_masses(std::vector<double>& mass, std::vector<double>& stiffness) const
{
  const unsigned int ng = mesh_.n_gridpoints(), nz = mesh_.n_zones();
  const std::vector<char> in_hex = zones_in_hexes(mesh_);
  mass.assign(ng, 0.0);
  stiffness.assign(ng, 0.0);
  const auto P = [&](unsigned int g)
  { return Vec3(mesh_.position[3 * g], mesh_.position[3 * g + 1], mesh_.position[3 * g + 2]); };
  for (unsigned int z = 0; z < nz; ++z)
  {
    const auto& t = mesh_.zone_gridpoint[z];
    const ZoneMaterial& mat = materials_[material_of_zone_[z]];
    if (mesh_.quadratic())
    {
      // The bound of tet10_mass_and_stiffness is for the undamped cycle.
      // Local damping (eq. 79) and combined damping (eq. 83) change the
      // force on a component by -alpha |F| sign(.), so by at most a factor
      // 1 + alpha (when it adds to a force opposing the motion); the
      // largest eigenvalue that the step sees grows by that factor at most,
      // and so must the nodal stiffness.
      const double damped =
          !s_.dynamic && (s_.damping == Damping::local || s_.damping == Damping::combined)
              ? 1.0 + s_.local_damping
          : s_.dynamic ? 1.0 + s_.dynamic_local_damping
                       : 1.0;
      double m10[10], k10[10];
      tet10_mass_and_stiffness(mesh_, z, mat.density, mat.bulk_modulus, mat.shear_modulus, m10,
                               k10);
      for (int a = 0; a < 10; ++a)
      {
        const unsigned int g = a < 4 ? t[a] : mesh_.zone_edge_gridpoint[z][a - 4];
        mass[g] += m10[a];
        stiffness[g] += damped * k10[a];
      }
      continue;
    }
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
    const double weight = in_hex[z] ? 0.5 : 1.0;
    for (int a = 0; a < 4; ++a)
    {
      mass[t[a]] += weight * 0.25 * mat.density * V;
      stiffness[t[a]] += weight * k_zone;
    }
  }
}

DeformableSolver::~DeformableSolver() = default;

unsigned int DeformableSolver::nodal_mixed_zones() const
{
  unsigned int n = 0;
  for (std::size_t r = 0; r + 1 < batch_start_.size(); ++r)
    if (materials_[material_of_zone_[batch_start_[r]]].nodal_mixed)
      n += batch_start_[r + 1] - batch_start_[r];
  return n;
}

std::pair<unsigned long, Vec3> DeformableSolver::whole_water() const
{
  if (!share_)
    return {water_faces_below_, water_force_};
  std::vector<ExactSum> sums = water_force_sum_;
  sums.resize(4);
  sums[3].add(double(water_faces_below_));
  reductions_over(share_->comm).sums(sums);
  return {static_cast<unsigned long>(sums[3].value()),
          Vec3(sums[0].value(), sums[1].value(), sums[2].value())};
}

std::array<unsigned long, 2> DeformableSolver::whole_nodal_mixed_zones() const
{
  if (!share_)
    return {{nodal_mixed_zones(), mesh_.n_zones()}};
  // Each zone once, by the rank that counts it.
  std::array<unsigned long, 2> n{{0, 0}};
  for (unsigned int z = 0; z < mesh_.n_zones(); ++z)
    if (share_->counts(mesh_.zone_gridpoint[z][0]))
    {
      n[0] += materials_[material_of_zone_[z]].nodal_mixed ? 1 : 0;
      ++n[1];
    }
  MPI_Allreduce(MPI_IN_PLACE, n.data(), 2, MPI_UNSIGNED_LONG, MPI_SUM, share_->comm);
  return n;
}

void DeformableSolver::set_nodal_mixed_ring_limit(unsigned int batches)
{
  nmd_ring_limit_ = batches;
  if (nodal_mixed_)
    plan_nodal_mixed();
}

double DeformableSolver::step_of(const std::vector<double>& mass,
                                 const std::vector<double>& stiffness, double beta) const
{
  // Eq. 84: dt = 2 min sqrt(m_i / k_i); with Rayleigh's stiffness term,
  // each gridpoint's 2 / omega_i lowered at its own omega_i = sqrt(k_i / m_i).
  // Split among ranks: the owned gridpoints of every rank (a ghost's mass
  // and stiffness are partial: some of its zones are elsewhere).
  double ratio = 1e300, step = 1e300;
  for (std::size_t g = 0; g < std::min<std::size_t>(mass.size(), n_moved_); ++g)
    if (stiffness[g] > 0.0)
    {
      ratio = std::min(ratio, mass[g] / stiffness[g]);
      if (beta > 0.0 && mass[g] > 0.0)
        step = std::min(step,
                        2.0 * std::sqrt(mass[g] / stiffness[g]) *
                            stiffness_damping_step_factor(beta, std::sqrt(stiffness[g] / mass[g])));
    }
  return least_over_ranks(beta > 0.0 ? std::min(step, 2.0 * std::sqrt(ratio))
                                     : 2.0 * std::sqrt(ratio));
}

double DeformableSolver::stable_time_step(const std::vector<double>& joint_stiffness,
                                          double beta) const
{
  std::vector<double> k = nodal_stiffness_;
  for (std::size_t g = 0; g < k.size() && g < joint_stiffness.size(); ++g)
    k[g] += joint_stiffness[g];
  return step_of(true_mass_, k, beta);
}

ViscousModuli DeformableSolver::viscous_moduli(const ZoneMaterial& mat, double strain_dt) const
{
  return ViscousModuli(mat.bulk_modulus, mat.shear_modulus, s_.stiffness_damping() / strain_dt);
}

unsigned int DeformableSolver::time_step_gridpoint() const
{
  unsigned int found = 0;
  double ratio = 1e300;
  for (std::size_t g = 0; g < n_moved_; ++g)
    if (nodal_stiffness_[g] > 0.0 && true_mass_[g] / nodal_stiffness_[g] < ratio)
    {
      ratio = true_mass_[g] / nodal_stiffness_[g];
      found = static_cast<unsigned int>(g);
    }
  if (!share_)
    return found;
  // The whole mesh's first gridpoint of the least m / k (MPI_MINLOC keeps
  // the lowest index of equal values).
  struct
  {
    double value;
    int index;
  } mine{ratio, static_cast<int>(share_->whole_gridpoint.empty() ? found
                                                                 : share_->whole_gridpoint[found])},
      all{0.0, 0};
  MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE_INT, MPI_MINLOC, share_->comm);
  return static_cast<unsigned int>(all.index);
}

void DeformableSolver::external_forces(const double* x, double* f)
{
  const unsigned int ng = mesh_.n_gridpoints();
  // Loads in time: each boundary's factor once per step, at its time.
  for (std::size_t p = 0; p < pressures_.size(); ++p)
    pressure_scale_[p] = pressures_[p].motion.scale(time_);
  if (!timed_load_points_.empty())
  {
    gravity_force_ = steady_gravity_force_;
    std::vector<double> scale(conditions_.size(), 1.0);
    for (std::size_t c = 0; c < conditions_.size(); ++c)
      scale[c] = conditions_[c].motion.scale(time_);
    for (const auto& [g, c] : timed_load_points_)
      for (int d = 0; d < 3; ++d)
        gravity_force_[3 * g + d] += conditions_[c].force[d] * scale[c];
  }
  for (unsigned int i = 0; i < 3 * ng; ++i)
  {
    f[i] = gravity_force_[i];
    force_size_[i] = std::abs(gravity_force_[i]);
  }
  // Pressure on boundary faces, in the current geometry: -p n A / 3 on each
  // of the face's gridpoints, kept apart too for the energy account.
  if (!pressure_force_.empty())
    std::fill(pressure_force_.begin(), pressure_force_.end(), 0.0);
  for (std::size_t k = 0; k < pressed_faces_.size(); ++k)
  {
    const Vec3 load = face_load(k, x);
    for (int a = 0; a < 3; ++a)
    {
      const unsigned int g = pressed_faces_[k][a];
      const Vec3 share = face_share_[k][a] * load;
      for (int d = 0; d < 3; ++d)
      {
        f[3 * g + d] += share[d];
        force_size_[3 * g + d] += std::abs(share[d]);
        pressure_force_[3 * g + d] += share[d];
      }
    }
  }
  // An incident wave through a quiet boundary (dynamics): the pressure
  // 2 sigma_in(t) on its faces, so that with the dashpot's rho cp v the
  // face carries sigma_in and the wave enters at v_in = sigma_in / (rho cp)
  // (initial geometry, as the dashpots); along a direction of the faces,
  // the traction 2 tau_in(t) with the dashpot rho cs: a shear wave.
  if (s_.dynamic)
    for (std::size_t k = 0; k < quiet_faces_.size(); ++k)
    {
      if (quiet_wave_[k] == ~0u)
        continue;
      const double stress = 2.0 * quiet_waves_[quiet_wave_[k]](time_);
      const Vec3& direction = quiet_wave_direction_[quiet_wave_[k]];
      const Vec3 load = direction == Vec3::Zero()
                            ? Vec3(-stress * quiet_area_[k])
                            : Vec3(stress * quiet_area_[k].norm() * direction);
      for (int a = 0; a < 3; ++a)
      {
        const unsigned int g = quiet_faces_[k][a];
        for (int d = 0; d < 3; ++d)
        {
          const double share = quiet_share_[k][a] * load[d];
          f[3 * g + d] += share;
          force_size_[3 * g + d] += std::abs(share);
          pressure_force_[3 * g + d] += share;
        }
      }
    }
  if (!water_faces_.empty())
    add_water(x, f);
}

template <typename Add>
unsigned int DeformableSolver::water_shares(const double* x, Add&& add) const
{
  // The hydrostatic pressure of the water in the current geometry: on each
  // corner, -n times its consistent share of the pressure (exact for the
  // linear pressure under a plane surface; the resultant and its moment are
  // those of the pressure on the face). A 10-node zone's face takes it on
  // its four sub-triangles as a 4-node one would: the same resultant.
  const double gamma = s_.water.density * s_.gravity.norm();
  const double highest = s_.water.table.highest();
  unsigned int below = 0;
  for (std::size_t k = 0; k < water_faces_.size(); ++k)
  {
    const auto& t = water_faces_[k];
    const Vec3 a(x[3 * t[0]], x[3 * t[0] + 1], x[3 * t[0] + 2]);
    const Vec3 b(x[3 * t[1]], x[3 * t[1] + 1], x[3 * t[1] + 2]);
    const Vec3 c(x[3 * t[2]], x[3 * t[2] + 1], x[3 * t[2] + 2]);
    // A face on a joint with a pressure of its own ('Joint set pressures'):
    // that pressure, uniform, a third of its force on each corner.
    const double fixed =
        water_face_origin_.empty() ? std::nan("") : s_.water.fixed_pressure(water_face_origin_[k]);
    TriangleWater w;
    if (fixed == fixed)
    {
      const double area = 0.5 * (b - a).cross(c - a).norm(); // m^2
      w.force = fixed * area;
      w.corner[0] = w.corner[1] = w.corner[2] = w.force / 3.0;
    }
    else
    {
      if (std::min({a.z(), b.z(), c.z()}) >= highest)
        continue;
      integrate_water(s_.water.table, gamma, a, b, c, w);
    }
    if (!(w.force > 0.0))
      continue;
    // Split among ranks, each face counted once over them (by the owner of
    // its first gridpoint, which holds it); every held face loads its
    // gridpoints.
    const bool counted = !share_ || t[0] < n_moved_;
    below += counted;
    // A corner sub-triangle of a 10-node zone's face gives its vertex's
    // share to its two midpoints, half each: the consistent load of a
    // uniform pressure on a 6-node triangle (none at its vertices), as
    // pressures and the joints' springs have it.
    if (!water_vertex_corner_.empty() && water_vertex_corner_[k] >= 0)
    {
      const int v = water_vertex_corner_[k];
      w.corner[(v + 1) % 3] += 0.5 * w.corner[v];
      w.corner[(v + 2) % 3] += 0.5 * w.corner[v];
      w.corner[v] = 0.0;
    }
    const Vec3 n = (b - a).cross(c - a).normalized(); // outward
    for (int j = 0; j < 3; ++j)
      add(t[j], Vec3(-water_weight_[k] * w.corner[j] * n), counted);
  }
  return below;
}

void DeformableSolver::add_water(const double* x, double* f)
{
  water_force_sum_.assign(3, ExactSum());
  water_faces_below_ = water_shares(x,
                                    [&](unsigned int g, const Vec3& share, bool counted)
                                    {
                                      if (counted)
                                        for (int d = 0; d < 3; ++d)
                                          water_force_sum_[d].add(share[d]);
                                      for (int d = 0; d < 3; ++d)
                                      {
                                        f[3 * g + d] += share[d];
                                        force_size_[3 * g + d] += std::abs(share[d]);
                                        pressure_force_[3 * g + d] += share[d];
                                      }
                                    });
  water_force_ =
      Vec3(water_force_sum_[0].value(), water_force_sum_[1].value(), water_force_sum_[2].value());
}

void DeformableSolver::zone_forces()
{
  LocalArray x(petsc_->position), v(petsc_->velocity), f(petsc_->force);
  // Rayleigh's stiffness-proportional term (dynamics): its forces apart.
  if (s_.stiffness_damping() > 0.0)
    damping_force_.assign(3 * std::size_t(mesh_.n_gridpoints()), 0.0);
  else if (!damping_force_.empty())
    damping_force_.clear();
  external_forces(x.data(), f.data());
  // The velocities are those of the last motion (x - v dt -> x), over the
  // step it took (a stage's change of mode changes dt_ after it); before
  // the first motion there is none, so no strain.
  zone_forces(x.data(), v.data(), f.data(), step_ == 0 ? 0.0 : motion_dt_);
}

namespace
{
/// The material remove_zones (null_zones) gives excavated zones: no
/// stiffness and no mass, so their stresses stay zero and they add no
/// force; the zone loops leave their batches out (an excavation then takes
/// its zones' work away too).
bool excavated(const ZoneMaterial& m)
{
  return m.density == 0.0 && m.bulk_modulus == 0.0 && m.shear_modulus == 0.0;
}
} // namespace

void DeformableSolver::zone_forces(const double* x, const double* v, double* f, double strain_dt)
{
  if (nodal_mixed_)
  {
    nodal_mixed_zone_forces(x, v, f, strain_dt);
    return;
  }
  // Rayleigh's stiffness-proportional term: the forces of the viscous
  // stress into damping_force_ (none before the first motion).
  const bool viscous = !damping_force_.empty() && strain_dt > 0.0;
  if (mesh_.quadratic())
  {
    // 10-node zones: the same three stages, the model at every Gauss point.
    constexpr unsigned int batch10 = zone_batch / 4;
    scratch10_.resize(batch10);
    for (std::size_t r = 0; r + 1 < batch_start_.size(); ++r)
    {
      const ZoneMaterial& mat = materials_[material_of_zone_[batch_start_[r]]];
      if (excavated(mat))
        continue;
      for (unsigned int first = batch_start_[r]; first < batch_start_[r + 1]; first += batch10)
      {
        const unsigned int n = std::min(batch10, batch_start_[r + 1] - first);
        tet10_strain_increments(mesh_, first, n, x, v, strain_dt, stress_.data(), scratch10_);
        StressBatch batch;
        batch.size = 4 * n;
        batch.strain_increment = scratch10_.strain_increment.data();
        batch.stress = stress_.data() + 24 * std::size_t(first);
        batch.state = state_.data() + 4 * std::size_t(first);
        // Plastic materials: the stress work of the step as for 4-node
        // zones, each Gauss point with the volume it stands for.
        const bool plastic = mat.model != ZoneModel::elastic;
        if (plastic)
        {
          gauss_volume_.resize(4 * n);
          for (unsigned int k = 0; k < n; ++k)
          {
            tet10_gauss_volumes(mesh_, first + k, x, &gauss_volume_[4 * k]);
            // Split among ranks: the zones this rank counts alone.
            if (share_ && !share_->counts(mesh_.zone_gridpoint[first + k][0]))
              std::fill_n(&gauss_volume_[4 * k], 4, 0.0);
          }
          plastic_stress_work_ +=
              0.5 * stress_power(4 * n, batch.strain_increment, batch.stress, gauss_volume_.data());
        }
        apply_zone_model(mat, batch);
        if (plastic)
          plastic_stress_work_ +=
              0.5 * stress_power(4 * n, batch.strain_increment, batch.stress, gauss_volume_.data());
        // With Rayleigh's viscous stress, both forces in one pass.
        if (viscous)
          tet10_nodal_forces_viscous(mesh_, first, n, stress_.data(), scratch10_,
                                     viscous_moduli(mat, strain_dt), f, force_size_.data(),
                                     damping_force_.data());
        else
          tet10_nodal_forces(mesh_, first, n, stress_.data(), scratch10_, f, force_size_.data());
      }
    }
    return;
  }
  // Zones, one batch of one material at a time: strain increments, the
  // material model once for the batch, nodal forces.
  scratch_.resize(zone_batch);
  for (std::size_t r = 0; r + 1 < batch_start_.size(); ++r)
  {
    const ZoneMaterial& mat = materials_[material_of_zone_[batch_start_[r]]];
    if (excavated(mat))
      continue;
    const bool hex = mat.element == ZoneElement::hex_mixed;
    const unsigned int chunk = zone_chunk(mat);
    for (unsigned int first = batch_start_[r]; first < batch_start_[r + 1]; first += chunk)
    {
      const unsigned int n = std::min(chunk, batch_start_[r + 1] - first);
      tet4_strain_increments(mesh_, first, n, x, v, strain_dt, stress_.data(), scratch_);
      if (hex) // eqs. 60-63
        hex_mixed_average_strain(n, scratch_.strain_increment.data(), scratch_.volume.data());
      StressBatch batch = tet4_batch(first, n, scratch_);
      update_tet4_stresses(mat, batch, scratch_.volume.data(), first);
      if (hex) // each overlay's forces weighted 1/2
        hex_mixed_overlay_weight(n, scratch_.volume.data());
      // With Rayleigh's viscous stress, both forces in one pass.
      if (viscous)
        tet4_nodal_forces_viscous(mesh_, first, n, stress_.data(), scratch_,
                                  viscous_moduli(mat, strain_dt), f, force_size_.data(),
                                  damping_force_.data());
      else
        tet4_nodal_forces(mesh_, first, n, stress_.data(), scratch_, f, force_size_.data());
    }
  }
}

void DeformableSolver::update_tet4_stresses(const ZoneMaterial& mat, StressBatch& batch,
                                            const double* volume, unsigned int first)
{
  // Plastic materials: the stress work of the step, V (s_old + s_new) / 2
  // : d(eps), from which the plastic dissipation follows (elastic ones
  // store all of it, so theirs is not summed). Each of a hexahedron's two
  // overlays fills it once: half weight.
  const bool hex = mat.element == ZoneElement::hex_mixed;
  const bool plastic = mat.model != ZoneModel::elastic;
  const double overlay = hex ? 0.5 : 1.0;
  // Split among ranks, the work of the zones this rank counts alone (each
  // zone once over the ranks): the others' volumes taken as zero.
  const double* work_volume = volume;
  if (plastic && share_)
  {
    counted_volume_.resize(batch.size);
    for (unsigned int k = 0; k < batch.size; ++k)
      counted_volume_[k] = share_->counts(mesh_.zone_gridpoint[first + k][0]) ? volume[k] : 0.0;
    work_volume = counted_volume_.data();
  }
  if (plastic)
    plastic_stress_work_ +=
        0.5 * overlay * stress_power(batch.size, batch.strain_increment, batch.stress, work_volume);
  apply_zone_model(mat, batch);
  if (hex) // eqs. 64-67
    hex_mixed_average_mean_stress(batch.size, batch.stress, volume);
  if (plastic)
    plastic_stress_work_ +=
        0.5 * overlay * stress_power(batch.size, batch.strain_increment, batch.stress, work_volume);
}

StressBatch DeformableSolver::tet4_batch(unsigned int first, unsigned int n, Tet4Scratch& scratch)
{
  StressBatch batch;
  batch.size = n;
  batch.strain_increment = scratch.strain_increment.data();
  batch.stress = stress_.data() + 6 * first;
  batch.state = state_.data() + first;
  return batch;
}

void DeformableSolver::plan_nodal_mixed()
{
  // The batches of the model stage, in order, and for each the last batch
  // whose sums stage must be done first: the last batch of a mixed
  // material that touches one of its gridpoints, where eq. 69's sums are
  // complete; and for each batch the gridpoints whose sums it completes.
  nmd_batches_.clear();
  for (std::size_t r = 0; r + 1 < batch_start_.size(); ++r)
  {
    const ZoneMaterial& mat = materials_[material_of_zone_[batch_start_[r]]];
    // Excavated zones are in no batch: not mixed, they add nothing to the
    // sums, and with no stress they add no force.
    if (excavated(mat))
      continue;
    const unsigned int chunk = zone_chunk(mat);
    for (unsigned int first = batch_start_[r]; first < batch_start_[r + 1]; first += chunk)
      nmd_batches_.push_back(
          {first, std::min(chunk, batch_start_[r + 1] - first), mat.nodal_mixed, 0});
  }
  const unsigned int nb = static_cast<unsigned int>(nmd_batches_.size());
  const unsigned int none = std::numeric_limits<unsigned int>::max();
  // Visits every gridpoint of every zone of batch b.
  const auto for_gridpoints = [&](unsigned int b, auto&& visit)
  {
    const NodalMixedBatch& batch = nmd_batches_[b];
    for (unsigned int z = batch.first; z < batch.first + batch.n; ++z)
      for (unsigned int g : mesh_.zone_gridpoint[z])
        visit(g);
  };
  // Of each gridpoint, the last place in `order` (batches) of a mixed batch
  // around it, or none.
  std::vector<unsigned int> last_place(mesh_.n_gridpoints());
  const auto find_last_places = [&](const auto& order)
  {
    std::fill(last_place.begin(), last_place.end(), none);
    for (unsigned int p = 0; p < nb; ++p)
      if (nmd_batches_[order(p)].mixed)
        for_gridpoints(order(p), [&](unsigned int g) { last_place[g] = p; });
  };
  // Of each batch, the largest of `least` and the last places around it.
  const auto latest_around = [&](unsigned int b, unsigned int least)
  {
    if (nmd_batches_[b].mixed)
      for_gridpoints(b, [&](unsigned int g) { least = std::max(least, last_place[g]); });
    return least;
  };

  find_last_places([](unsigned int p) { return p; });
  unsigned int lag = 0;
  std::vector<unsigned int> ready_after(nb);
  for (unsigned int b = 0; b < nb; ++b)
  {
    ready_after[b] = nmd_batches_[b].ready_after = latest_around(b, b);
    lag = std::max(lag, ready_after[b] - b);
  }
  list_by_key(last_place, nb, completed_start_, completed_gridpoint_);

  // The model order: each batch as soon as its sums are complete, those
  // ready at the same time in their order (on a mesh in slabs, the order
  // of the batches; in columns, a seam batch joins the columns when the
  // last column around it has been summed).
  list_by_key(ready_after, nb, model_start_, model_order_);
  // A plastic average is complete with the last model stage around its
  // gridpoint; the force stage of a batch waits for all of its own.
  find_last_places([&](unsigned int p) { return model_order_[p]; });
  for (unsigned int p = 0; p < nb; ++p)
    nmd_batches_[model_order_[p]].forces_after = latest_around(model_order_[p], p);
  list_by_key(last_place, nb, plastic_start_, plastic_gridpoint_);

  // A batch whose model stage comes at most nmd_ring_limit_ - 1 batches
  // after its sums stage is kept: its sums stage is the strain pass itself,
  // whose scratch waits in the ring (one slot per batch in between, from
  // the third-level cache) for the model stage. The others sum the
  // volumetric increments alone and the model stage takes the strain pass
  // again. On a mesh in slabs every batch waits about one layer of zones;
  // in columns (MeshOrder::columns) only the seam batches wait long.
  // Measured on 2-core Zen 4 EPYC guests (benchmark_zone_cycle, elastic /
  // Mohr-Coulomb cost against plain zones, kept against taken twice):
  // lag 9 batches 1.19 / 1.19 against 1.33 / 1.24, lag 18 1.21 / 1.24
  // against 1.32 / 1.27, lag 32 1.22 / 1.27 against 1.33 / 1.29; lag 40
  // and 50 even (1.24-1.31 against 1.28-1.32), and so was lag 71. The two
  // stages a layer apart without kept scratch cost more than either
  // (1.37 against 1.27 at n = 40): with no batch kept, every sums stage
  // comes first.
  unsigned int slots = 0;
  nmd_kept_ = 0;
  for (unsigned int b = 0; b < nb; ++b)
  {
    NodalMixedBatch& batch = nmd_batches_[b];
    // Split among ranks, every sums stage comes first (the ghosts' averages
    // arrive between the stages): none kept.
    batch.kept = !share_ && batch.ready_after - b + 1 <= nmd_ring_limit_;
    if (batch.kept)
    {
      slots = std::max(slots, batch.ready_after - b + 1);
      ++nmd_kept_;
    }
  }
  nmd_lag_ = lag;
  nmd_ring_.assign(slots, Tet4Scratch());
  for (Tet4Scratch& scratch : nmd_ring_)
    scratch.resize(zone_batch);
}

void DeformableSolver::nodal_mixed_zone_forces(const double* x, const double* v, double* f,
                                               double strain_dt)
{
  // Nodal mixed discretization (eqs. 68-76) for the zones whose material
  // asks for it. One pass over the zones in order, a batch at a time, in
  // two stages that run a few batches apart:
  //   sums stage: every mixed zone's volumetric strain increment and
  //     volume, summed at its gridpoints (eq. 69); a gridpoint's sum is
  //     made its average as soon as its last zone has been added;
  //   model stage, once every gridpoint of the batch has its average: the
  //     strain increments with the volumetric part replaced by the mean of
  //     the gridpoint averages (eqs. 70-71), the zone model, the plastic
  //     pressure of zones that yielded summed at their gridpoints (eqs.
  //     73-75), and the nodal forces unless a mixed zone may yield;
  //   force stage, if one may, once every gridpoint of the batch has its
  //     average plastic pressure (the same wait, on the model stage): each
  //     zone that yielded trades its plastic pressure for the mean of its
  //     gridpoints' (eq. 76), then the nodal forces.
  // A batch whose model stage comes soon after its sums stage (see
  // plan_nodal_mixed) keeps the strain increments of the sums stage for
  // it; the others sum their volumetric increments alone and the model
  // stage takes the strain increments again (bitwise the same numbers);
  // with none kept, every sums stage comes first. Every
  // sum is added up in zone order, as in one sweep over all zones, and the
  // sums stage reads nothing that the model stage writes, so the results
  // do not depend on the distance between the two stages, nor on the mode.
  const unsigned int ng = mesh_.n_gridpoints();
  const bool viscous = !damping_force_.empty() && strain_dt > 0.0; // Rayleigh beta
  bool plastic_pass = nmd_on_ranks_[1]; // on ranks: whether any rank's may yield
  for (const ZoneMaterial& m : materials_)
    plastic_pass |= m.nodal_mixed && m.model != ZoneModel::elastic;
  batch_volumetric_.resize(zone_batch + Tet4Scratch::max_lanes);
  own_volumetric_.resize(zone_batch + Tet4Scratch::max_lanes);
  scratch_.resize(zone_batch);
  strain_sums_.assign(2 * std::size_t(ng), 0.0);
  const unsigned int ring = static_cast<unsigned int>(nmd_ring_.size());
  const auto sums_stage = [&](unsigned int j)
  {
    const NodalMixedBatch& b = nmd_batches_[j];
    if (b.kept)
    {
      Tet4Scratch& scratch = nmd_ring_[j % ring];
      tet4_strain_increments(mesh_, b.first, b.n, x, v, strain_dt, stress_.data(), scratch,
                             b.mixed ? batch_volumetric_.data() : nullptr);
      if (!b.mixed)
        return;
      add_volume_weighted_pairs(mesh_, b.first, b.n, batch_volumetric_.data(),
                                scratch.volume.data(), strain_sums_.data());
    }
    else if (b.mixed)
    {
      tet4_volumetric_increments(mesh_, b.first, b.n, x, v, strain_dt, batch_volumetric_.data(),
                                 scratch_.volume.data());
      add_volume_weighted_pairs(mesh_, b.first, b.n, batch_volumetric_.data(),
                                scratch_.volume.data(), strain_sums_.data());
    }
    average_pairs(completed_gridpoint_.data() + completed_start_[j],
                  completed_start_[j + 1] - completed_start_[j], strain_sums_.data());
  };

  // Nodal forces in the model stage unless a mixed zone may yield; if one
  // may, but none did at the last step, they are taken there all the same
  // and taken again, all of them in the model order, only if one did yield
  // after all (the sums are the same either way).
  // Split among ranks, with a mixed zone that may yield, the forces wait
  // for the force stage: a ghost's plastic average comes from its owner
  // after every model stage.
  const bool split = share_ != nullptr;
  const bool forces_now = !plastic_pass || (!split && !last_step_yielded_);
  if (plastic_pass)
  {
    plastic_average_.assign(ng, 0.0);
    yielded_zone_.clear();
    yielded_volumetric_.clear();
    yielded_taken_.clear();
  }
  // Eqs. 74-76 for batch j, once every gridpoint of it has its average
  // plastic pressure: each zone that yielded trades its own plastic
  // pressure for the mean of its gridpoints' averages; then the nodal
  // forces. Batches in the model order, as the yielded zones were listed.
  std::size_t next = 0;
  const auto force_stage = [&](unsigned int j)
  {
    const NodalMixedBatch& b = nmd_batches_[j];
    for (; next < yielded_zone_.size() && yielded_zone_[next] >= b.first &&
           yielded_zone_[next] < b.first + b.n;
         ++next)
    {
      const unsigned int z = yielded_zone_[next];
      const double shift =
          multiply_add(materials_[material_of_zone_[z]].bulk_modulus, yielded_volumetric_[next],
                       -corner_mean(mesh_, z, plastic_average_.data()));
      for (int c = 0; c < 3; ++c)
        stress_[6 * z + c] += shift;
      // Its share of the stress work, V shift tr(d eps) / 2: the zone's
      // volumetric increment is the mean of its gridpoints' (eq. 71).
      // Split among ranks, each zone's work by the rank that counts it.
      const double volume = split && !share_->counts(mesh_.zone_gridpoint[z][0])
                                ? 0.0
                                : tet_volume(x, mesh_.zone_gridpoint[z]);
      plastic_stress_work_ +=
          0.5 * volume * shift * 3.0 * corner_mean(mesh_, z, strain_sums_.data(), 2);
      // And of the work of its forces beyond it (replaced_strain_work).
      nodal_mixed_work_ += 0.5 * volume * shift * yielded_taken_[next];
    }
    tet4_geometry(mesh_, b.first, b.n, x, scratch_);
    if (materials_[material_of_zone_[b.first]].element == ZoneElement::hex_mixed)
      hex_mixed_overlay_weight(b.n, scratch_.volume.data());
    tet4_nodal_forces(mesh_, b.first, b.n, stress_.data(), scratch_, f, force_size_.data());
  };
  // When zones yielded at the last step, the force stage of each batch
  // follows the model stage it waits for (as the model stage follows the
  // sums stage), while its gridpoints are still in cache; a plastic
  // average is complete, and made an average, with the last model stage
  // around its gridpoint.
  const bool force_stage_follows = !forces_now && !split; // (only in a plastic pass)
  unsigned int forced = 0; // places of the model order through the force stage

  const auto model_stage = [&](unsigned int p)
  {
    const unsigned int j = model_order_[p];
    const NodalMixedBatch& b = nmd_batches_[j];
    const unsigned int first = b.first, n = b.n;
    Tet4Scratch& scratch = b.kept ? nmd_ring_[j % ring] : scratch_;
    const ZoneMaterial& mat = materials_[material_of_zone_[first]];
    const bool hex = mat.element == ZoneElement::hex_mixed;
    // Mixed zones keep their own volumetric increments for the account.
    double* own = mat.nodal_mixed ? own_volumetric_.data() : nullptr;
    if (!b.kept) // the strain pass again, eqs. 70-71 in it
      tet4_strain_increments(mesh_, first, n, x, v, strain_dt, stress_.data(), scratch, own,
                             mat.nodal_mixed ? strain_sums_.data() : nullptr);
    else if (mat.nodal_mixed) // on the kept strain increments
      replace_volumetric_strain(mesh_, first, n, strain_sums_.data(),
                                scratch.strain_increment.data(), own);
    if (hex) // eqs. 60-63
      hex_mixed_average_strain(n, scratch.strain_increment.data(), scratch.volume.data());
    StressBatch batch = tet4_batch(first, n, scratch);
    const bool collect = plastic_pass && mat.nodal_mixed;
    if (collect)
    {
      std::fill(batch_volumetric_.begin(), batch_volumetric_.begin() + n, 0.0);
      batch.plastic_volumetric = batch_volumetric_.data();
    }
    // The plastic pressure traded in the force stage adds its share of the
    // stress work there. The forces' work beyond the stress's: by the
    // midpoint rule, as the stress work (elastic zones in one pass).
    const double* stress = stress_.data() + 6 * std::size_t(first);
    const bool elastic = mat.model == ZoneModel::elastic;
    // Split among ranks, the work of the zones this rank counts alone.
    const double* work_volume = scratch.volume.data();
    if (split && own != nullptr)
    {
      nmd_work_volume_.resize(n);
      for (unsigned int k = 0; k < n; ++k)
        nmd_work_volume_[k] =
            share_->counts(mesh_.zone_gridpoint[first + k][0]) ? scratch.volume[k] : 0.0;
      work_volume = nmd_work_volume_.data();
    }
    const double taken_before =
        own != nullptr && !elastic
            ? replaced_strain_work(n, own, batch.strain_increment, stress, work_volume)
            : 0.0;
    update_tet4_stresses(mat, batch, scratch.volume.data(), first);
    if (own != nullptr)
    {
      const double taken_after =
          replaced_strain_work(n, own, batch.strain_increment, stress, work_volume,
                               elastic ? 0.5 * mat.bulk_modulus : 0.0);
      nodal_mixed_work_ += elastic ? taken_after : 0.5 * (taken_before + taken_after);
    }
    if (collect)
    {
      // Eq. 73: the plastic pressure K e^p (e^p the trace of the plastic
      // strain increment, which lowers the mean stress by K e^p).
      for (unsigned int k = 0; k < n; ++k)
        if (batch_volumetric_[k] != 0.0)
        {
          yielded_zone_.push_back(first + k);
          yielded_volumetric_.push_back(batch_volumetric_[k]);
          const double* de = batch.strain_increment + 6 * k;
          yielded_taken_.push_back(3.0 * own[k] - (de[0] + de[1] + de[2]));
          batch_volumetric_[k] *= mat.bulk_modulus;
        }
      add_volume_weighted(mesh_, first, n, batch_volumetric_.data(), scratch.volume.data(),
                          plastic_average_.data());
    }
    if (hex && (forces_now || viscous)) // each overlay's forces weighted 1/2
      hex_mixed_overlay_weight(n, scratch.volume.data());
    // Rayleigh's viscous stress from the strain increments as they are now,
    // its forces in the pass of the stresses' if they are taken now.
    if (viscous)
      tet4_nodal_forces_viscous(mesh_, first, n, forces_now ? stress_.data() : nullptr, scratch,
                                viscous_moduli(mat, strain_dt), f, force_size_.data(),
                                damping_force_.data());
    else if (forces_now)
      tet4_nodal_forces(mesh_, first, n, stress_.data(), scratch, f, force_size_.data());
    if (force_stage_follows)
    {
      divide_by_pair_volume(plastic_gridpoint_.data() + plastic_start_[p],
                            plastic_start_[p + 1] - plastic_start_[p], plastic_average_.data(),
                            strain_sums_.data());
      for (; forced <= p && nmd_batches_[model_order_[forced]].forces_after <= p; ++forced)
        force_stage(model_order_[forced]);
    }
  };

  const unsigned int nb = static_cast<unsigned int>(nmd_batches_.size());
  if (ring == 0) // nothing kept: every sums stage first
    for (unsigned int j = 0; j < nb; ++j)
      sums_stage(j);
  if (split) // the ghosts' averages, whole, from their owners
    averages_to_ghosts(strain_sums_.data(), 2);
  for (unsigned int j = 0; j < nb; ++j)
  {
    if (ring > 0)
      sums_stage(j);
    for (unsigned int p = model_start_[j]; p < model_start_[j + 1]; ++p)
      model_stage(p);
  }
  if (!plastic_pass)
    return;
  const bool yielded = !yielded_zone_.empty();
  last_step_yielded_ = yielded;
  if (split)
  {
    // Every rank: the plastic averages, the ghosts' from their owners, then
    // every force stage (the model stages took no forces but viscous ones).
    divide_by_pair_volume(plastic_gridpoint_.data(),
                          static_cast<unsigned int>(plastic_gridpoint_.size()),
                          plastic_average_.data(), strain_sums_.data());
    averages_to_ghosts(plastic_average_.data(), 1);
    for (unsigned int p = 0; p < nb; ++p)
      force_stage(model_order_[p]);
    return;
  }
  if (force_stage_follows || !yielded)
    return; // forces done
  // A zone yielded where none did at the last step: the forces taken in
  // the model stage are wrong for it, so all of them again, in order; the
  // viscous forces of Rayleigh damping, kept apart, go back in.
  external_forces(x, f);
  if (viscous)
    for (std::size_t i = 0; i < damping_force_.size(); ++i)
      f[i] += damping_force_[i];
  divide_by_pair_volume(plastic_gridpoint_.data(),
                        static_cast<unsigned int>(plastic_gridpoint_.size()),
                        plastic_average_.data(), strain_sums_.data());
  for (unsigned int p = 0; p < nb; ++p)
    force_stage(model_order_[p]);
}

void DeformableSolver::move_gridpoints()
{
  LocalArray x(petsc_->position), v(petsc_->velocity), f(petsc_->force), m(petsc_->inertial_mass);
  const bool combined = !s_.dynamic && s_.damping == Damping::combined;
  // Velocities at half steps (eq. 57): the first kick is half a step.
  const double h = step_ == 0 ? 0.5 * dt_ : dt_;
  double largest = 0.0, size_sum = 0.0;
  unsigned int n_free = 0;
  // Split among ranks, the ghosts (after n_moved_) are their owners' to move.
  // Energy account (see EnergyAccount): each force works over h (v- + v+) / 2.
  // The kinetic energy is that of the inertial masses m (with any mass of
  // density scaling): the work of the forces changes exactly that, so the
  // account balances; gravity works with the true mass.
  double gravity_work = 0.0, boundary_work = 0.0, damping_work = 0.0, kinetic = 0.0;
  const bool pressed = !pressure_force_.empty();
  // Rayleigh's stiffness-proportional forces (zones and contacts), which
  // act with f and whose work is dissipation.
  const double* fv = damping_force_.empty() ? nullptr : damping_force_.data();
  // Quiet boundaries' dashpots (dynamics): the diagonal of each
  // gridpoint's c taken semi-implicitly, on (v- + v+) / 2 as eq. 49's
  // viscous term (an explicit kick with the mass m + c h / 2: stable for
  // any c), the off-diagonal part of an inclined face on v-.
  const bool quiet = s_.dynamic && !quiet_c_.empty();
  double quiet_work = 0.0;
  // Held velocities in time: each condition's function once per motion, at
  // its middle (velocities live at half steps).
  for (unsigned int c = 0; c < conditions_.size(); ++c)
    motion_scale_[c] = conditions_[c].motion.scale(time_ + 0.5 * dt_);
  if (rest_at_next_motion_) // from dynamics into density-scaled statics
  {
    for (unsigned int g = 0; g < n_moved_; ++g)
      for (int d = 0; d < 3; ++d)
        if (!(held_[g] & (1u << d)))
          v[3 * g + d] = 0.0;
    rest_at_next_motion_ = false;
  }
  for (unsigned int g = 0; g < n_moved_; ++g)
  {
    double f2 = 0.0, size2 = 0.0;
    const std::array<double, 6>* cq =
        quiet && quiet_slot_[g] >= 0 ? &quiet_c_[quiet_slot_[g]] : nullptr;
    const double v0[3] = {v[3 * g], v[3 * g + 1], v[3 * g + 2]};
    for (int d = 0; d < 3; ++d)
    {
      const unsigned int i = 3 * g + d;
      const double weight = true_mass_[g] * s_.gravity[d];
      const double load = gravity_force_[i] - weight + (pressed ? pressure_force_[i] : 0.0);
      if (held_[g] & (1u << d))
      {
        // This motion spans [time_, time_ + dt_]: moved while it ends by
        // the condition's end time (half a step of slack for round-off).
        const double v_before = v[i];
        const double held = held_motion_[i] < 0
                                ? held_velocity_[i]
                                : held_velocity_[i] * motion_scale_[held_motion_[i]];
        v[i] = time_ + 0.5 * dt_ < held_until_[i] ? held : 0.0;
        // The support supplies minus the force on the component, and
        // whatever kinetic energy a change of the held velocity takes.
        const double reach = 0.5 * h * (v_before + v[i]);
        const double viscous = fv != nullptr ? fv[i] : 0.0;
        gravity_work += weight * reach;
        boundary_work +=
            (load - f[i] - viscous) * reach + 0.5 * m[i] * (v[i] * v[i] - v_before * v_before);
        damping_work -= viscous * reach;
        kinetic += 0.5 * m[i] * v[i] * v[i] - 0.5 * (f[i] - weight - load) * v[i] * dt_;
        continue;
      }
      const double viscous = fv != nullptr ? fv[i] : 0.0;
      const double force = f[i] + viscous;
      f2 += force * force;
      size2 += force_size_[i] * force_size_[i];
      // Eq. 57 with the damping chosen (eqs. 77-79, 83; dynamics: eqs. 49,
      // 79 and Rayleigh's).
      const double v_before = v[i];
      double c = 0.0, off = 0.0;
      if (cq != nullptr)
      {
        static constexpr int slot[3][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}};
        c = (*cq)[d];
        for (int e = 0; e < 3; ++e)
          if (e != d)
            off += (*cq)[slot[d][e]] * v0[e];
      }
      const double fd =
          cq == nullptr
              ? damper_.kick(v[i], force, combined ? last_force_[i] : 0.0, m[i], h)
              : damper_.kick(v[i], force - c * v_before - off, 0.0, m[i] + 0.5 * c * h, h);
      if (combined)
        last_force_[i] = f[i];
      const double reach = 0.5 * h * (v_before + v[i]);
      if (cq != nullptr)
        quiet_work += (c * 0.5 * (v_before + v[i]) + off) * reach;
      gravity_work += weight * reach;
      boundary_work += load * reach;
      damping_work += (fd - viscous) * reach;
      kinetic += 0.5 * m[i] * v[i] * v[i] - 0.5 * (f[i] - weight - load) * v[i] * dt_;
    }
    if (held_[g] != 7u)
    {
      if (std::sqrt(f2) > largest)
      {
        largest = std::sqrt(f2);
        ratio_gridpoint_ = g;
      }
      size_sum += std::sqrt(size2);
      ++n_free;
    }
    for (int d = 0; d < 3; ++d)
      x[3 * g + d] += v[3 * g + d] * dt_;
  }
  if (share_)
  {
    // The whole model's ratio: the largest force of any rank (the lowest
    // whole-mesh gridpoint of equal ones) over the mean of all.
    struct
    {
      double value;
      int index;
    } mine{largest, static_cast<int>(share_->whole_gridpoint.empty()
                                         ? ratio_gridpoint_
                                         : share_->whole_gridpoint[ratio_gridpoint_])},
        all{0.0, 0};
    double sums[2] = {size_sum, double(n_free)};
    MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE_INT, MPI_MAXLOC, share_->comm);
    MPI_Allreduce(MPI_IN_PLACE, sums, 2, MPI_DOUBLE, MPI_SUM, share_->comm);
    largest = all.value;
    ratio_whole_gridpoint_ = static_cast<unsigned int>(all.index);
    size_sum = sums[0];
    n_free = static_cast<unsigned int>(sums[1]);
  }
  ratio_ = n_free > 0 && size_sum > 0.0 ? largest / (size_sum / n_free) : 0.0;
  motion_dt_ = dt_;
  gravity_work_ += gravity_work;
  boundary_work_ += boundary_work;
  damping_work_ += damping_work + quiet_work;
  quiet_work_ += quiet_work;
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
  EnergyAccount mine;
  add_own_work(mine);
  add_over_ranks(mine, e);
}

void DeformableSolver::add_energy(EnergyAccount& e) const
{
  EnergyAccount mine;
  add_own_energy(mine);
  add_over_ranks(mine, e);
}

void DeformableSolver::add_over_ranks(const EnergyAccount& mine, EnergyAccount& e) const
{
  double terms[7] = {mine.gravity_work,   mine.boundary_work, mine.damping, mine.kinetic,
                     mine.initial_stored, mine.zone_elastic,  mine.plastic};
  if (share_)
    MPI_Allreduce(MPI_IN_PLACE, terms, 7, MPI_DOUBLE, MPI_SUM, share_->comm);
  e.gravity_work += terms[0];
  e.boundary_work += terms[1];
  e.damping += terms[2];
  e.kinetic += terms[3];
  e.initial_stored += terms[4];
  e.zone_elastic += terms[5];
  e.plastic += terms[6];
}

void DeformableSolver::add_own_work(EnergyAccount& e) const
{
  e.gravity_work += gravity_work_;
  e.boundary_work += boundary_work_;
  e.damping += damping_work_;
  e.kinetic += kinetic_whole_step_;
  e.initial_stored += initial_elastic_;
}

void DeformableSolver::add_own_energy(EnergyAccount& e) const
{
  add_own_work(e);
  LocalArray x(petsc_->position);
  const auto [elastic, plastic_elastic] = elastic_energy(x.data());
  e.zone_elastic += elastic;
  // Plastic dissipation: the stress work of plastic zones less the change
  // of their elastic energy.
  // Nodal mixed discretization stores more than its zones' stresses say.
  e.zone_elastic += nodal_mixed_work_;
  e.plastic += plastic_stress_work_ - (plastic_elastic - initial_plastic_elastic_);
}

std::pair<double, double> DeformableSolver::elastic_energy(const double* x) const
{
  // V / 2 sigma : C^-1 : sigma = V / 2 (p^2 / K + s : s / (2 G)), per
  // stress point: a 10-node zone's Gauss points each with the volume it
  // stands for, and each tetrahedron of a hexahedral zone, which fills the
  // hexahedron once of two overlays, with half its volume.
  const unsigned int points = mesh_.quadratic() ? 4 : 1;
  double all = 0.0, plastic = 0.0;
  for (unsigned int z = 0; z < mesh_.n_zones(); ++z)
  {
    if (zone_removed(z)) // no stress, no stiffness
      continue;
    if (share_ && !share_->counts(mesh_.zone_gridpoint[z][0])) // another rank's to count
      continue;
    const ZoneMaterial& mat = materials_[material_of_zone_[z]];
    double volume[4];
    if (mesh_.quadratic())
      tet10_gauss_volumes(mesh_, z, x, volume);
    else
      volume[0] = (mat.element == ZoneElement::hex_mixed ? 0.5 : 1.0) *
                  tet_volume(x, mesh_.zone_gridpoint[z]);
    double e = 0.0;
    for (unsigned int q = 0; q < points; ++q)
    {
      const double* s = &stress_[6 * (points * z + q)];
      const double p = (s[0] + s[1] + s[2]) / 3.0;
      const double ss = (s[0] - p) * (s[0] - p) + (s[1] - p) * (s[1] - p) +
                        (s[2] - p) * (s[2] - p) + 2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]);
      e += 0.5 * volume[q] * (p * p / mat.bulk_modulus + ss / (2.0 * mat.shear_modulus));
    }
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
  seconds_zones_ += seconds_since(t0);
}

void DeformableSolver::move()
{
  const auto t0 = std::chrono::steady_clock::now();
  move_gridpoints();
  if (share_)
    refresh_ghosts();
  if ((step_ + 1) % Damper::servo_period == 0) // on ranks: the whole model's powers
    damper_.adjust(share_ ? reductions_over(share_->comm).sums
                          : std::function<void(std::vector<ExactSum>&)>());
  time_ += dt_;
  ++step_;
  seconds_gridpoints_ += seconds_since(t0);
}

struct DeformableSolver::View::Forms
{
  Vec x = nullptr, v = nullptr, f = nullptr;
};

DeformableSolver::View::View(DeformableSolver& solver)
    : solver_(solver), forms_(std::make_unique<Forms>())
{
  x = get_local_array(static_cast<const Vec&>(solver_.petsc_->position), forms_->x);
  v = get_local_array(static_cast<const Vec&>(solver_.petsc_->velocity), forms_->v);
  f = get_local_array(static_cast<const Vec&>(solver_.petsc_->force), forms_->f);
  if (!solver_.damping_force_.empty())
    damping = solver_.damping_force_.data();
}

DeformableSolver::View::~View()
{
  restore_local_array(static_cast<const Vec&>(solver_.petsc_->position), forms_->x, x);
  restore_local_array(static_cast<const Vec&>(solver_.petsc_->velocity), forms_->v, v);
  restore_local_array(static_cast<const Vec&>(solver_.petsc_->force), forms_->f, f);
}

void DeformableSolver::share_nodal_mixed()
{
  if (!share_)
    return;
  // Whether any rank has a material of nodal mixed discretization, and one
  // that may yield: each rank has the materials of the zones it holds, and
  // every rank must take part in the exchanges of the averages alike.
  int any[2] = {nmd_on_ranks_[0], nmd_on_ranks_[1]};
  for (const ZoneMaterial& m : materials_)
  {
    any[0] |= m.nodal_mixed;
    any[1] |= m.nodal_mixed && m.model != ZoneModel::elastic;
  }
  MPI_Allreduce(MPI_IN_PLACE, any, 2, MPI_INT, MPI_LOR, share_->comm);
  nmd_on_ranks_ = {{any[0] != 0, any[1] != 0}};
  if (!nmd_on_ranks_[0] || petsc_->strain_pairs.size() > 0)
    return;
  // The layout of the position vector, with k numbers a gridpoint.
  const dealii::IndexSet& owned3 = petsc_->position.locally_owned_elements();
  const std::size_t all = owned3.size() / 3,
                    before = owned3.n_elements() > 0 ? *owned3.begin() / 3 : 0;
  for (const unsigned int k : {2u, 1u})
  {
    dealii::IndexSet owned(k * all), ghosts(k * all);
    owned.add_range(k * before, k * (before + n_moved_));
    for (unsigned int i : share_->ghost_index)
      ghosts.add_range(k * std::size_t(i), k * std::size_t(i) + k);
    (k == 2 ? petsc_->strain_pairs : petsc_->plastic_average).reinit(owned, ghosts, share_->comm);
  }
}

void DeformableSolver::averages_to_ghosts(double* values, unsigned int k)
{
  // The owners' numbers (complete: an owned gridpoint has all its zones
  // here) over the ghosts' (sums of the zones held here only).
  dealii::PETScWrappers::MPI::Vector& vec = k == 2 ? petsc_->strain_pairs : petsc_->plastic_average;
  const std::size_t owned = std::size_t(k) * n_moved_, held = std::size_t(k) * mesh_.n_gridpoints();
  {
    LocalArray a(vec);
    std::copy(values, values + owned, a.data());
  }
  const Vec& raw = static_cast<const Vec&>(vec);
  VecGhostUpdateBegin(raw, INSERT_VALUES, SCATTER_FORWARD);
  VecGhostUpdateEnd(raw, INSERT_VALUES, SCATTER_FORWARD);
  LocalArray a(vec);
  std::copy(a.data() + owned, a.data() + held, values + owned);
}

void DeformableSolver::refresh_ghosts()
{
  // The owners' positions and velocities into the ghost entries (one
  // scatter each, to and from the ranks that share gridpoints).
  for (const auto* vec : {&petsc_->position, &petsc_->velocity})
  {
    const Vec& raw = static_cast<const Vec&>(*vec);
    VecGhostUpdateBegin(raw, INSERT_VALUES, SCATTER_FORWARD);
    VecGhostUpdateEnd(raw, INSERT_VALUES, SCATTER_FORWARD);
  }
}

double DeformableSolver::least_over_ranks(double value) const
{
  if (share_)
    MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_DOUBLE, MPI_MIN, share_->comm);
  return value;
}

void DeformableSolver::use_time_step(double dt, const std::vector<double>& joint_stiffness)
{
  const unsigned int ng = mesh_.n_gridpoints();
  std::vector<double> k = nodal_stiffness_;
  for (unsigned int g = 0; g < ng && g < joint_stiffness.size(); ++g)
    k[g] += joint_stiffness[g];
  const bool scaled = !s_.dynamic && s_.density_scaling;
  const double beta = s_.stiffness_damping();
  if (!scaled && !s_.raises_mass() && dt > step_of(true_mass_, k, beta) * (1.0 + 1e-12))
    throw InputError("the time step " + number(dt) + " s exceeds the stable step of the zones, " +
                     number(step_of(true_mass_, k, beta)) + " s (eq. 84" +
                     (beta > 0.0 ? " with Rayleigh beta" : "") +
                     "); allowed: a smaller 'Time step', or 'Partial density scaling = true'");
  dt_ = dt;
  joint_stiffness_ = joint_stiffness;
  step_from_blocks_ = true;
  set_inertial_masses();
}

double DeformableSolver::inertial_mass_of(unsigned int g, double k) const
{
  double m = !s_.dynamic && s_.density_scaling ? std::max(true_mass_[g], k * dt_ * dt_ / 4.0)
                                               : true_mass_[g];
  // Partial density scaling: eq. 84 for this gridpoint alone (with the
  // Rayleigh term of dynamics) solved for its mass at the given step.
  if (s_.raises_mass() && true_mass_[g] > 0.0)
    m = std::max(m, mass_for_step(k, dt_, s_.stiffness_damping()));
  return m;
}

void DeformableSolver::set_inertial_masses()
{
  const unsigned int ng = mesh_.n_gridpoints();
  LocalArray m(petsc_->inertial_mass);
  added_mass_ = AddedMass();
  for (unsigned int g = 0; g < ng; ++g)
  {
    const double k =
        nodal_stiffness_[g] + (g < joint_stiffness_.size() ? joint_stiffness_[g] : 0.0);
    const double inertial = inertial_mass_of(g, k);
    for (int d = 0; d < 3; ++d)
      m[3 * g + d] = inertial;
    if (!s_.dynamic)
      continue; // static inertia is a device of the solution, not mass added
    if (g >= n_moved_)
      continue; // a ghost: its owner counts it
    added_mass_.total += true_mass_[g];
    if (inertial > true_mass_[g])
    {
      ++added_mass_.gridpoints;
      added_mass_.added += inertial - true_mass_[g];
      added_mass_.largest_factor = std::max(added_mass_.largest_factor, inertial / true_mass_[g]);
    }
  }
  if (share_ && s_.dynamic)
  {
    double sums[3] = {double(added_mass_.gridpoints), added_mass_.added, added_mass_.total};
    MPI_Allreduce(MPI_IN_PLACE, sums, 3, MPI_DOUBLE, MPI_SUM, share_->comm);
    MPI_Allreduce(MPI_IN_PLACE, &added_mass_.largest_factor, 1, MPI_DOUBLE, MPI_MAX, share_->comm);
    added_mass_.gridpoints = static_cast<unsigned int>(sums[0]);
    added_mass_.added = sums[1];
    added_mass_.total = sums[2];
  }
  damper_ = damper_for(s_, dt_);
  if (!s_.dynamic && s_.damping == Damping::combined)
    last_force_.assign(3 * ng, 0.0);
}

DeformableSolver::StepState DeformableSolver::step_state() const
{
  StepState state{dt_, joint_stiffness_, {}, added_mass_};
  LocalArray m(petsc_->inertial_mass);
  state.inertial_mass.assign(m.data(), m.data() + 3 * std::size_t(mesh_.n_gridpoints()));
  return state;
}

void DeformableSolver::set_step_state(const StepState& state)
{
  dt_ = state.dt;
  joint_stiffness_ = state.joint_stiffness;
  added_mass_ = state.added_mass;
  LocalArray m(petsc_->inertial_mass);
  std::copy(state.inertial_mass.begin(), state.inertial_mass.end(), m.data());
}

void DeformableSolver::set_dynamic(bool dynamic)
{
  if (s_.dynamic && !dynamic && s_.density_scaling)
  {
    // Statics with density scaling runs in a time of its own (a unit step,
    // masses to suit): velocities of the dynamics before would carry into
    // it as jumps (1 cm/s moves a gridpoint 1 cm in the first step). Free
    // components start again from rest at the next motion (the zones take
    // the strain of the last one first); the kinetic energy they held
    // leaves the account as damping now. Held components keep theirs.
    LocalArray v(petsc_->velocity), m(petsc_->inertial_mass);
    double kinetic = 0.0; // of the dynamic masses, at the last half step
    for (unsigned int g = 0; g < n_moved_; ++g)
      for (int d = 0; d < 3; ++d)
        if (!(held_[g] & (1u << d)))
          kinetic += 0.5 * m[3 * g + d] * v[3 * g + d] * v[3 * g + d];
    damping_work_ += kinetic;
    kinetic_whole_step_ = 0.0;
    rest_at_next_motion_ = true;
  }
  s_.dynamic = dynamic;
  if (!step_from_blocks_ && s_.time_step <= 0.0)
  {
    // Alone (no block solver sets the step): eq. 84, or the unit step of
    // density scaling.
    std::vector<double> k = nodal_stiffness_;
    dt_ = !dynamic && s_.density_scaling ? 1.0 : step_of(true_mass_, k, s_.stiffness_damping());
  }
  set_inertial_masses();
}

void DeformableSolver::reset_displacements()
{
  reference_ = positions();
}

void DeformableSolver::remove_zones(std::vector<char> gone)
{
  const unsigned int ng = mesh_.n_gridpoints();
  // A hexahedral zone goes whole: its ten tetrahedra share one mean stress.
  for (unsigned int h = 0; h < mesh_.n_hexes(); ++h)
  {
    bool any = false;
    for (unsigned int k = 0; k < TetMesh::tets_per_hex; ++k)
      any |= gone[mesh_.hex_first_zone[h] + k] != 0;
    for (unsigned int k = 0; k < TetMesh::tets_per_hex && any; ++k)
      gone[mesh_.hex_first_zone[h] + k] = 1;
  }
  // The energy the zones hold leaves the account with them.
  EnergyAccount before;
  add_own_energy(before);
  const std::vector<double> mass_before = true_mass_;
  null_zones(gone);
  {
    // A gridpoint of removed zones only is held where it is.
    LocalArray v(petsc_->velocity);
    for (unsigned int g = 0; g < ng; ++g)
      if (true_mass_[g] == 0.0 && mass_before[g] > 0.0)
      {
        held_[g] = 7u;
        for (int d = 0; d < 3; ++d)
        {
          v[3 * g + d] = held_velocity_[3 * g + d] = 0.0;
          held_until_[3 * g + d] = std::numeric_limits<double>::infinity();
          held_motion_[3 * g + d] = -1;
        }
      }
  }
  set_inertial_masses();
  EnergyAccount after;
  add_own_energy(after);
  initial_elastic_ -= after.error() - before.error();
}

void DeformableSolver::null_zones(const std::vector<char>& gone)
{
  const unsigned int nz = mesh_.n_zones();
  if (removed_zone_.empty())
    removed_zone_.assign(nz, 0);
  // One null material per element type: no stiffness, no density, elastic
  // (its stresses stay zero, so its zones add no force).
  std::map<int, unsigned int> null_of_element;
  for (unsigned int z = 0; z < nz; ++z)
  {
    if (!gone[z] || removed_zone_[z])
      continue;
    removed_zone_[z] = 1;
    ZoneMaterial null = materials_[material_of_zone_[z]];
    const auto [it, fresh] =
        null_of_element.emplace(int(null.element), static_cast<unsigned int>(materials_.size()));
    if (fresh)
    {
      null.model = ZoneModel::elastic;
      null.bulk_modulus = null.shear_modulus = 0.0;
      null.density = 0.0;
      null.nodal_mixed = false;
      materials_.push_back(null);
    }
    material_of_zone_[z] = it->second;
    for (unsigned int q = 0; q < points_per_zone_; ++q)
    {
      std::fill_n(&stress_[6 * (points_per_zone_ * z + q)], 6, 0.0);
      state_[points_per_zone_ * z + q] = 0;
    }
  }
  materials_changed();
}

void DeformableSolver::materials_changed()
{
  const unsigned int nz = mesh_.n_zones();
  batch_start_.clear();
  for (unsigned int z = 0; z < nz; ++z)
    if (z == 0 || material_of_zone_[z] != material_of_zone_[z - 1])
      batch_start_.push_back(z);
  batch_start_.push_back(nz);
  // Masses and gravity of what the zones are now.
  std::vector<double> mass, stiffness;
  zone_masses(mass, stiffness);
  true_mass_ = mass;
  nodal_stiffness_ = stiffness;
  set_gravity_and_loads();
  nodal_mixed_ = false;
  for (unsigned int z = 0; z < nz; ++z)
    nodal_mixed_ |= materials_[material_of_zone_[z]].nodal_mixed;
  nodal_mixed_ |= nmd_on_ranks_[0]; // every rank takes part in the exchanges
  if (nodal_mixed_)
    plan_nodal_mixed();
}

void DeformableSolver::change_material(const std::vector<char>& zones, const ZoneMaterial& material,
                                       bool account)
{
  // The energy the zones store changes with their stiffness and mass at
  // the same stresses and velocities: the account's error stays what it
  // was (as for an excavation).
  EnergyAccount before;
  if (account)
    add_own_energy(before);
  const unsigned int index = static_cast<unsigned int>(materials_.size());
  materials_.push_back(material);
  for (unsigned int z = 0; z < mesh_.n_zones(); ++z)
    if (zones[z] && !zone_removed(z))
      material_of_zone_[z] = index;
  share_nodal_mixed(); // on ranks, a collective call (as this one is)
  materials_changed();
  if (!step_from_blocks_ && s_.time_step <= 0.0)
  {
    // Alone (no block solver sets the step): eq. 84, or the unit step of
    // density scaling.
    std::vector<double> k = nodal_stiffness_;
    dt_ = !s_.dynamic && s_.density_scaling ? 1.0 : step_of(true_mass_, k);
  }
  set_inertial_masses();
  if (!account)
    return;
  EnergyAccount after;
  add_own_energy(after);
  initial_elastic_ -= after.error() - before.error();
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

std::array<std::vector<double>, 4> DeformableSolver::local_vectors() const
{
  std::array<std::vector<double>, 4> values;
  const std::array<const dealii::PETScWrappers::MPI::Vector*, 4> vec{
      {&petsc_->position, &petsc_->velocity, &petsc_->force, &petsc_->inertial_mass}};
  for (int k = 0; k < 4; ++k)
  {
    LocalArray a(*vec[k]);
    values[k].assign(a.data(), a.data() + 3 * std::size_t(mesh_.n_gridpoints()));
  }
  return values;
}

void DeformableSolver::set_local_vectors(const std::array<std::vector<double>, 4>& values)
{
  const std::array<const dealii::PETScWrappers::MPI::Vector*, 4> vec{
      {&petsc_->position, &petsc_->velocity, &petsc_->force, &petsc_->inertial_mass}};
  for (int k = 0; k < 4; ++k)
  {
    LocalArray a(*vec[k]);
    std::copy(values[k].begin(), values[k].end(), a.data());
  }
}

std::vector<double> DeformableSolver::displacements() const
{
  std::vector<double> u = positions();
  for (std::size_t i = 0; i < u.size(); ++i)
    u[i] -= reference_[i];
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
  {
    held_velocity_[3 * g + d] = v[d];
    held_until_[3 * g + d] = std::numeric_limits<double>::infinity();
    held_motion_[3 * g + d] = -1;
  }
}

Vec3 DeformableSolver::support_force(const ConvexRegion& region, const bool held[3]) const
{
  // The unbalanced force of the last step at held gridpoints is what the
  // support must supply, reversed.
  // Exact sums: the same on any number of ranks, to the last bit (a
  // component the supports barely take is a sum of round-off).
  LocalArray f(petsc_->force);
  std::vector<ExactSum> sum(3);
  for (unsigned int g = 0; g < n_moved_; ++g) // split: each rank its own
    if (held_[g] != 0 && inside(region, &mesh_.position[3 * g]))
      for (int d = 0; d < 3; ++d)
        if (held[d] && (held_[g] & (1u << d)))
          sum[d] += f[3 * g + d];
  if (share_)
    reductions_over(share_->comm).sums(sum);
  return Vec3(sum[0].value(), sum[1].value(), sum[2].value());
}

Vec3 DeformableSolver::face_load(std::size_t k, const double* x) const
{
  const auto& t = pressed_faces_[k];
  const Vec3 a(x[3 * t[0]], x[3 * t[0] + 1], x[3 * t[0] + 2]);
  const Vec3 b(x[3 * t[1]], x[3 * t[1] + 1], x[3 * t[1] + 2]);
  const Vec3 c(x[3 * t[2]], x[3 * t[2] + 1], x[3 * t[2] + 2]);
  const Vec3 area_normal = 0.5 * (b - a).cross(c - a); // outward, |.| = area
  // -p n A + t A, shared by the gridpoints as face_share_ says.
  const double scale = face_function_[k] < 0 ? 1.0 : pressure_scale_[face_function_[k]];
  return scale * (-face_pressure_[k] * area_normal + face_traction_[k] * area_normal.norm());
}

ImplicitElasticProblem DeformableSolver::implicit_problem() const
{
  ImplicitElasticProblem p;
  p.mesh = &mesh_;
  // The 4-node stiffness for the preconditioner: the tetrahedra of a
  // hexahedral zone at half weight (each overlay fills it once), 10-node
  // zones as their eight sub-tetrahedra on the same gridpoints.
  const std::vector<char> in_hex = zones_in_hexes(mesh_);
  std::shared_ptr<TetMesh> sub;
  if (mesh_.quadratic())
  {
    sub = std::make_shared<TetMesh>();
    sub->position = mesh_.position;
    p.mesh = sub.get();
    p.own_mesh = sub;
  }
  for (unsigned int z = 0; z < mesh_.n_zones(); ++z)
  {
    const ZoneMaterial& mat = materials_[material_of_zone_[z]];
    const double weight = in_hex[z] ? 0.5 : 1.0;
    for (unsigned int c = 0; c < (sub ? 8u : 1u); ++c)
    {
      p.zone_bulk.push_back(weight * mat.bulk_modulus);
      p.zone_shear.push_back(weight * mat.shear_modulus);
      if (!sub)
        continue;
      std::array<unsigned int, 4> t;
      for (int a = 0; a < 4; ++a)
      {
        const unsigned int node = tet10_subcell[c][a];
        t[a] = node < 4 ? mesh_.zone_gridpoint[z][node] : mesh_.zone_edge_gridpoint[z][node - 4];
      }
      sub->zone_gridpoint.push_back(t);
    }
  }
  // Nodal mixed discretization averages the volumetric strain at a
  // gridpoint weighted by zone volume (eq. 69) and each zone's stress takes
  // K times the mean of those averages: the operator is symmetric where the
  // mixed zones around every gridpoint share one bulk modulus, else GMRES
  // must solve.
  std::vector<double> bulk_at(mesh_.n_gridpoints(), -1.0);
  for (unsigned int z = 0; z < mesh_.n_zones(); ++z)
    if (const ZoneMaterial& mat = materials_[material_of_zone_[z]]; mat.nodal_mixed)
      for (unsigned int g : mesh_.zone_gridpoint[z])
      {
        if (bulk_at[g] >= 0.0 && bulk_at[g] != mat.bulk_modulus)
          p.symmetric = false;
        bulk_at[g] = mat.bulk_modulus;
      }
  p.nodal_force = gravity_force_;
  for (std::size_t k = 0; k < pressed_faces_.size(); ++k)
  {
    const Vec3 load = face_load(k, mesh_.position.data());
    for (int a = 0; a < 3; ++a)
      for (int d = 0; d < 3; ++d)
        p.nodal_force[3 * pressed_faces_[k][a] + d] += face_share_[k][a] * load[d];
  }
  water_shares(mesh_.position.data(),
               [&](unsigned int g, const Vec3& share, bool)
               {
                 for (int d = 0; d < 3; ++d)
                   p.nodal_force[3 * g + d] += share[d];
               });
  p.fixed = held_;
  return p;
}

void DeformableSolver::elastic_operator(const double* u, double* Ku)
{
  // The kernels measure a step's motion v dt on the geometry halfway
  // through it (eq. 58) and take the nodal forces on the geometry at its
  // end: from the initial geometry, a motion +s u and one -s u, a small s,
  // give forces whose difference is -2 s K u with the change of geometry
  // cancelled to second order.
  const unsigned int n = 3 * mesh_.n_gridpoints();
  double largest = 0.0, volume = 0.0;
  for (unsigned int i = 0; i < n; ++i)
    largest = std::max(largest, std::abs(u[i]));
  std::fill(Ku, Ku + n, 0.0);
  if (!(largest > 0.0))
    return;
  for (const auto& t : mesh_.zone_gridpoint)
    volume += tet_volume(mesh_.position.data(), t);
  const double s = 1e-6 * std::cbrt(volume / mesh_.n_zones()) / largest; // strains ~1e-6
  // The run's state aside: elastic, unstressed zones.
  std::vector<double> stress(stress_.size(), 0.0), force_size = force_size_;
  std::vector<unsigned char> state(state_.size(), 0);
  std::vector<ZoneMaterial> materials = materials_;
  for (ZoneMaterial& m : materials_)
    m.model = ZoneModel::elastic;
  stress_.swap(stress);
  state_.swap(state);
  const double stress_work = plastic_stress_work_;
  const double mixed_work = nodal_mixed_work_;
  const bool yielded = last_step_yielded_;
  std::vector<double> v(n), f(n);
  for (const double sign : {1.0, -1.0})
  {
    for (unsigned int i = 0; i < n; ++i)
      v[i] = sign * s * u[i];
    std::fill(f.begin(), f.end(), 0.0);
    std::fill(stress_.begin(), stress_.end(), 0.0);
    zone_forces(mesh_.position.data(), v.data(), f.data(), 1.0);
    for (unsigned int i = 0; i < n; ++i)
      Ku[i] -= sign * f[i] / (2.0 * s);
  }
  stress_.swap(stress);
  state_.swap(state);
  materials_.swap(materials);
  force_size_.swap(force_size);
  plastic_stress_work_ = stress_work;
  nodal_mixed_work_ = mixed_work;
  last_step_yielded_ = yielded;
}

void DeformableSolver::save_state(CheckpointWriter& out) const
{
  // What stages changed, first: loading sets the damper's kind from it.
  out.tag("zone stages");
  out.put(removed_zone_);
  out.put(reference_);
  out.put(static_cast<unsigned char>(s_.dynamic));
  out.put(dt_);
  out.tag("zones");
  for (const auto* vec :
       {&petsc_->position, &petsc_->velocity, &petsc_->force, &petsc_->inertial_mass})
  {
    LocalArray a(*vec);
    out.put(std::vector<double>(a.data(), a.data() + 3 * mesh_.n_gridpoints()));
  }
  out.put(stress_);
  out.put(state_);
  out.put(held_);
  out.put(held_velocity_);
  out.put(last_force_);
  damper_.save_state(out);
  out.put(dt_);
  out.put(time_);
  out.put(ratio_);
  out.put(step_);
  out.put(gravity_work_);
  out.put(boundary_work_);
  out.put(damping_work_);
  out.put(kinetic_whole_step_);
  out.put(plastic_stress_work_);
  out.put(nodal_mixed_work_);
  out.put(initial_elastic_);
  out.put(initial_plastic_elastic_);
  growth_watch_.save_state(out);
}

void DeformableSolver::load_state(CheckpointReader& in)
{
  in.tag("zone stages");
  std::vector<char> removed;
  in.get(removed);
  if (!removed.empty() && removed.size() != mesh_.n_zones())
    in.mismatch("removed zones", removed.size(), mesh_.n_zones());
  in.get(reference_, reference_.size(), "gridpoint reference positions");
  unsigned char dynamic = 0;
  in.get(dynamic);
  in.get(dt_);
  s_.dynamic = dynamic != 0;
  damper_ = damper_for(s_, dt_);
  if (!removed.empty())
    null_zones(removed);
  in.tag("zones");
  const std::size_t ng = mesh_.n_gridpoints();
  std::vector<double> values;
  for (auto* vec : {&petsc_->position, &petsc_->velocity, &petsc_->force, &petsc_->inertial_mass})
  {
    in.get(values, 3 * ng, "gridpoint values");
    LocalArray a(*vec);
    std::copy(values.begin(), values.end(), a.data());
  }
  in.get(stress_, stress_.size(), "zone stresses");
  in.get(state_, state_.size(), "zone plastic states");
  in.get(held_, ng, "gridpoint conditions");
  in.get(held_velocity_, 3 * ng, "gridpoint velocities held");
  in.get(last_force_, last_force_.size(), "gridpoint forces of the last step");
  damper_.load_state(in);
  in.get(dt_);
  motion_dt_ = dt_; // checkpoints are written between steps of one mode
  in.get(time_);
  in.get(ratio_);
  in.get(step_);
  in.get(gravity_work_);
  in.get(boundary_work_);
  in.get(damping_work_);
  in.get(kinetic_whole_step_);
  in.get(plastic_stress_work_);
  in.get(nodal_mixed_work_);
  in.get(initial_elastic_);
  in.get(initial_plastic_elastic_);
  growth_watch_.load_state(in);
}

} // namespace talus
