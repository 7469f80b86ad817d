#include <talus/base/exceptions.h>
#include <talus/base/wall_clock.h>
#include <talus/zone/implicit_elastic.h>

#include <deal.II/base/index_set.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <Eigen/Dense>
#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>
#include <mpi.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <memory>
#include <numeric>
#include <sstream>
#include <string>

namespace talus
{

namespace
{

/// Shape-function gradients (m^-1) and volume (m^3) of a 4-node tetrahedron.
double tet_gradients(const std::vector<double>& x, const std::array<unsigned int, 4>& v,
                     double g[4][3])
{
  Eigen::Matrix3d J; // columns: edges from vertex 0
  for (unsigned int a = 0; a < 3; ++a)
    for (unsigned int d = 0; d < 3; ++d)
      J(d, a) = x[3 * v[a + 1] + d] - x[3 * v[0] + d];
  const double det = J.determinant();
  if (!(det > 0.0))
    return det / 6.0;
  // grad N_a (a = 1..3) are the rows of J^-1; N_0 = 1 - N_1 - N_2 - N_3.
  const Eigen::Matrix3d Jinv = J.inverse();
  for (unsigned int d = 0; d < 3; ++d)
  {
    g[0][d] = 0.0;
    for (unsigned int a = 0; a < 3; ++a)
    {
      g[a + 1][d] = Jinv(a, d);
      g[0][d] -= Jinv(a, d);
    }
  }
  return det / 6.0;
}

/// Union-find root with path halving.
unsigned int find_root(std::vector<unsigned int>& parent, unsigned int i)
{
  while (parent[i] != i)
    i = parent[i] = parent[parent[i]];
  return i;
}

/// Rigid-body mode m (0..2 translations, 3..5 rotations about x, y, z) at
/// component d of a point at r (relative to a centre, scaled).
double rigid_mode(unsigned int m, unsigned int d, const double r[3])
{
  if (m < 3)
    return m == d ? 1.0 : 0.0;
  // Rotation about axis a: e_a x r.
  const unsigned int a = m - 3;
  const unsigned int b = (a + 1) % 3, c = (a + 2) % 3;
  if (d == b)
    return -r[c];
  if (d == c)
    return r[b];
  return 0.0;
}

void check_input(const ImplicitElasticProblem& p)
{
  if (p.mesh == nullptr)
    throw SolverError("implicit elastic solve: no mesh given");
  const TetMesh& m = *p.mesh;
  const std::size_t nz = m.n_zones(), ng = m.n_gridpoints();
  const auto size_error = [](const char* what, std::size_t got, const std::string& want)
  {
    throw SolverError(std::string("implicit elastic solve: ") + what + " has " +
                      std::to_string(got) + " entries; expected " + want);
  };
  if (m.position.size() != 3 * ng)
    size_error("mesh.position", m.position.size(), "3 per gridpoint");
  if (p.zone_bulk.size() != nz)
    size_error("zone_bulk", p.zone_bulk.size(), std::to_string(nz) + " (one per zone)");
  if (p.zone_shear.size() != nz)
    size_error("zone_shear", p.zone_shear.size(), std::to_string(nz) + " (one per zone)");
  if (!p.nodal_force.empty() && p.nodal_force.size() != 3 * ng)
    size_error("nodal_force", p.nodal_force.size(), "0 or " + std::to_string(3 * ng));
  if (!p.fixed.empty() && p.fixed.size() != ng)
    size_error("fixed", p.fixed.size(), "0 or " + std::to_string(ng));
  if (!p.prescribed.empty() && p.prescribed.size() != 3 * ng)
    size_error("prescribed", p.prescribed.size(), "0 or " + std::to_string(3 * ng));
  if (!(p.tolerance > 0.0))
    throw SolverError("implicit elastic solve: tolerance must be > 0");
  for (std::size_t z = 0; z < nz; ++z)
  {
    if (!(p.zone_bulk[z] > 0.0 && p.zone_shear[z] > 0.0 && std::isfinite(p.zone_bulk[z]) &&
          std::isfinite(p.zone_shear[z])))
      throw SolverError("implicit elastic solve: zone " + std::to_string(z) +
                        " has K = " + std::to_string(p.zone_bulk[z]) +
                        " Pa, G = " + std::to_string(p.zone_shear[z]) + " Pa; both must be > 0");
    for (unsigned int v : m.zone_gridpoint[z])
      if (v >= ng)
        throw SolverError("implicit elastic solve: zone " + std::to_string(z) +
                          " refers to gridpoint " + std::to_string(v) + " of " +
                          std::to_string(ng));
  }
}

/// Throws unless the prescribed components stop every rigid-body motion of
/// every connected part of the mesh: the stiffness of a part is singular
/// exactly when some rigid motion vanishes on all its prescribed components.
/// Gridpoints in no zone must be prescribed in all three components.
void check_fixity(const ImplicitElasticProblem& p, const std::vector<unsigned int>& zones_at)
{
  const TetMesh& m = *p.mesh;
  const unsigned int ng = m.n_gridpoints();
  std::vector<unsigned int> parent(ng);
  std::iota(parent.begin(), parent.end(), 0u);
  for (const auto& zone : m.zone_gridpoint)
    for (unsigned int a = 1; a < 4; ++a)
    {
      const unsigned int r0 = find_root(parent, zone[0]), r = find_root(parent, zone[a]);
      if (r0 != r)
        parent[r] = r0;
    }
  // Centre and size of each part, so that the rotation modes are O(1).
  std::vector<unsigned int> root(ng), count(ng, 0);
  std::vector<double> centre(3 * ng, 0.0), radius(ng, 0.0);
  for (unsigned int i = 0; i < ng; ++i)
  {
    if (zones_at[i] == 0)
    {
      if (p.fixed.empty() || (p.fixed[i] & 7) != 7)
        throw SolverError("implicit elastic solve: gridpoint " + std::to_string(i) +
                          " belongs to no zone and is not prescribed in all three components "
                          "(singular system)");
      continue;
    }
    root[i] = find_root(parent, i);
    ++count[root[i]];
    for (unsigned int d = 0; d < 3; ++d)
      centre[3 * root[i] + d] += m.position[3 * i + d];
  }
  for (unsigned int i = 0; i < ng; ++i)
    if (count[i] > 0)
      for (unsigned int d = 0; d < 3; ++d)
        centre[3 * i + d] /= count[i];
  for (unsigned int i = 0; i < ng; ++i)
    if (zones_at[i] > 0)
    {
      double r2 = 0.0;
      for (unsigned int d = 0; d < 3; ++d)
        r2 += std::pow(m.position[3 * i + d] - centre[3 * root[i] + d], 2);
      radius[root[i]] = std::max(radius[root[i]], std::sqrt(r2));
    }
  // Gram matrix of the rigid modes restricted to the prescribed components.
  std::vector<Eigen::Matrix<double, 6, 6>> gram(ng);
  for (unsigned int i = 0; i < ng; ++i)
    if (count[i] > 0)
      gram[i].setZero();
  for (unsigned int i = 0; i < ng; ++i)
  {
    if (zones_at[i] == 0 || p.fixed.empty() || p.fixed[i] == 0)
      continue;
    const unsigned int c = root[i];
    double r[3];
    for (unsigned int d = 0; d < 3; ++d)
      r[d] = (m.position[3 * i + d] - centre[3 * c + d]) / radius[c];
    for (unsigned int d = 0; d < 3; ++d)
      if (p.fixed[i] & (1u << d))
      {
        Eigen::Matrix<double, 6, 1> row;
        for (unsigned int k = 0; k < 6; ++k)
          row[k] = rigid_mode(k, d, r);
        gram[c] += row * row.transpose();
      }
  }
  for (unsigned int c = 0; c < ng; ++c)
  {
    if (count[c] == 0)
      continue;
    // Singular values of the symmetric Gram matrix are its eigenvalues,
    // largest first. (JacobiSVD rather than SelfAdjointEigenSolver, whose
    // AVX-512 code trips a false -Wmaybe-uninitialized in GCC 12.)
    const Eigen::JacobiSVD<Eigen::Matrix<double, 6, 6>> svd(gram[c], Eigen::ComputeFullV);
    const double largest = std::max(svd.singularValues()[0], 1.0);
    if (svd.singularValues()[5] > 1e-12 * largest)
      continue;
    // Name the free motion: the singular vector of the smallest value.
    const auto v = svd.matrixV().col(5);
    std::ostringstream free;
    free.precision(2);
    free << "translation (" << v[0] << ", " << v[1] << ", " << v[2] << ") + rotation (" << v[3]
         << ", " << v[4] << ", " << v[5] << ") about (" << centre[3 * c] << ", "
         << centre[3 * c + 1] << ", " << centre[3 * c + 2] << ")";
    throw SolverError("implicit elastic solve: singular system: the prescribed displacements "
                      "leave a rigid-body motion free in the connected part of the mesh "
                      "containing gridpoint " +
                      std::to_string(c) + " (" + std::to_string(count[c]) +
                      " gridpoints); free motion: " + free.str() +
                      "; prescribe components at three or more non-collinear gridpoints");
  }
}

/// The operator of ImplicitElasticProblem::apply with the prescribed
/// components eliminated as in the assembled matrix: K P u on the free rows
/// (P zeroes the prescribed components), the assembled diagonal times u on
/// the prescribed ones. Symmetric when K is.
class MatrixFreeOperator
{
public:
  MatrixFreeOperator(const std::function<void(const double*, double*)>& apply,
                     const std::vector<char>& fixed, const std::vector<double>& fixed_diagonal)
      : apply_(apply), fixed_(fixed), diagonal_(fixed_diagonal), in_(fixed.size()),
        out_(fixed.size())
  {
  }
  void vmult(dealii::TrilinosWrappers::MPI::Vector& dst,
             const dealii::TrilinosWrappers::MPI::Vector& src) const
  {
    const double* u = src.begin();
    for (std::size_t i = 0; i < in_.size(); ++i)
      in_[i] = fixed_[i] ? 0.0 : u[i];
    std::fill(out_.begin(), out_.end(), 0.0);
    apply_(in_.data(), out_.data());
    double* y = dst.begin();
    for (std::size_t i = 0; i < out_.size(); ++i)
      y[i] = fixed_[i] ? diagonal_[i] * in_[i] + diagonal_[i] * u[i] : out_[i];
  }

private:
  const std::function<void(const double*, double*)>& apply_;
  const std::vector<char>& fixed_;
  const std::vector<double>& diagonal_;
  mutable std::vector<double> in_, out_;
};

} // namespace

ImplicitElasticResult solve_implicit_elastic(const ImplicitElasticProblem& p)
{
  using namespace dealii;
  const auto start = std::chrono::steady_clock::now();

  int mpi_initialized = 0, mpi_finalized = 0;
  MPI_Initialized(&mpi_initialized);
  MPI_Finalized(&mpi_finalized);
  if (!mpi_initialized || mpi_finalized)
    throw SolverError("implicit elastic solve: MPI is not initialised; create a "
                      "dealii::Utilities::MPI::MPI_InitFinalize object at the start of main");

  check_input(p);
  const TetMesh& m = *p.mesh;
  const unsigned int ng = m.n_gridpoints(), nz = m.n_zones();
  const types::global_dof_index n_dofs = 3 * static_cast<types::global_dof_index>(ng);
  const auto is_fixed = [&](unsigned int dof)
  { return !p.fixed.empty() && (p.fixed[dof / 3] & (1u << (dof % 3))); };
  const auto prescribed = [&](unsigned int dof)
  { return p.prescribed.empty() ? 0.0 : p.prescribed[dof]; };

  // Gridpoint neighbours (CSR), for the sparsity and the fixity check.
  std::vector<unsigned int> zones_at(ng, 0);
  for (const auto& zone : m.zone_gridpoint)
    for (unsigned int v : zone)
      ++zones_at[v];
  check_fixity(p, zones_at);
  std::vector<std::vector<unsigned int>> neighbours(ng);
  for (const auto& zone : m.zone_gridpoint)
    for (unsigned int a : zone)
      for (unsigned int b : zone)
        neighbours[a].push_back(b);

  // Sparsity: prescribed rows and columns keep only their diagonal, since
  // they are eliminated.
  DynamicSparsityPattern dsp(n_dofs, n_dofs);
  {
    std::vector<types::global_dof_index> cols;
    for (unsigned int i = 0; i < ng; ++i)
    {
      auto& nb = neighbours[i];
      std::sort(nb.begin(), nb.end());
      nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
      for (unsigned int d = 0; d < 3; ++d)
      {
        const unsigned int row = 3 * i + d;
        cols.clear();
        if (is_fixed(row))
          cols.push_back(row);
        else
          for (unsigned int j : nb)
            for (unsigned int e = 0; e < 3; ++e)
              if (!is_fixed(3 * j + e))
                cols.push_back(3 * j + e);
        dsp.add_entries(row, cols.begin(), cols.end(), true);
      }
      std::vector<unsigned int>().swap(nb);
    }
  }
  // MPI_COMM_SELF: the solve is serial; under mpirun every rank solves alone.
  const MPI_Comm comm = MPI_COMM_SELF;
  const IndexSet all = complete_index_set(n_dofs);
  TrilinosWrappers::SparseMatrix matrix;
  matrix.reinit(all, all, dsp, comm);
  dsp.reinit(0, 0);

  // Right-hand side of the free rows: forces minus the prescribed columns.
  std::vector<double> rhs(n_dofs, 0.0), fixed_diagonal(n_dofs, 0.0);
  if (!p.nodal_force.empty())
    for (unsigned int i = 0; i < n_dofs; ++i)
      if (!is_fixed(i))
        rhs[i] = p.nodal_force[i];

  {
    double g[4][3];
    double ke[12][12];
    types::global_dof_index cols[12];
    double vals[12];
    for (unsigned int z = 0; z < nz; ++z)
    {
      const auto& v = m.zone_gridpoint[z];
      const double volume = tet_gradients(m.position, v, g);
      if (!(volume > 0.0))
        throw SolverError("implicit elastic solve: zone " + std::to_string(z) + " has volume " +
                          std::to_string(volume) + " m^3; zones must be positively oriented");
      // K_(a i)(b j) = V [lambda g_ai g_bj + G (g_aj g_bi + delta_ij g_a . g_b)],
      // i.e. V B^T D B for isotropic D with lambda = K - 2G/3 (eq. 59).
      const double G = p.zone_shear[z], lambda = p.zone_bulk[z] - 2.0 * G / 3.0;
      for (unsigned int a = 0; a < 4; ++a)
        for (unsigned int b = 0; b < 4; ++b)
        {
          const double gab = g[a][0] * g[b][0] + g[a][1] * g[b][1] + g[a][2] * g[b][2];
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              ke[3 * a + i][3 * b + j] = volume * (lambda * g[a][i] * g[b][j] +
                                                   G * (g[a][j] * g[b][i] + (i == j ? gab : 0.0)));
        }
      for (unsigned int r = 0; r < 12; ++r)
      {
        const unsigned int row = 3 * v[r / 3] + r % 3;
        if (is_fixed(row))
        {
          fixed_diagonal[row] += ke[r][r];
          continue;
        }
        unsigned int n = 0;
        for (unsigned int c = 0; c < 12; ++c)
        {
          const unsigned int col = 3 * v[c / 3] + c % 3;
          if (is_fixed(col))
            rhs[row] -= ke[r][c] * prescribed(col);
          else
          {
            cols[n] = col;
            vals[n++] = ke[r][c];
          }
        }
        matrix.add(row, n, cols, vals, false, false);
      }
    }
  }
  // The operator given: forces less its columns of the prescribed values.
  std::vector<char> fixed_dof(p.apply ? n_dofs : 0);
  if (p.apply)
  {
    std::vector<double> lifted(n_dofs, 0.0), reaction(n_dofs, 0.0);
    bool any = false;
    for (unsigned int i = 0; i < n_dofs; ++i)
      if ((fixed_dof[i] = is_fixed(i)))
        any |= (lifted[i] = prescribed(i)) != 0.0;
    if (any)
      p.apply(lifted.data(), reaction.data());
    for (unsigned int i = 0; i < n_dofs; ++i)
      if (!is_fixed(i))
        rhs[i] = (p.nodal_force.empty() ? 0.0 : p.nodal_force[i]) - reaction[i];
  }
  // Prescribed rows: their own diagonal (keeps the scaling of the rest)
  // with a right-hand side that makes the prescribed value the answer.
  double free_norm2 = 0.0;
  for (unsigned int i = 0; i < n_dofs; ++i)
    if (is_fixed(i))
    {
      matrix.add(i, i, fixed_diagonal[i]);
      rhs[i] = fixed_diagonal[i] * prescribed(i);
    }
    else
      free_norm2 += rhs[i] * rhs[i];
  matrix.compress(VectorOperation::add);

  ImplicitElasticResult result;
  result.displacement.assign(n_dofs, 0.0);
  for (unsigned int i = 0; i < n_dofs; ++i)
    if (is_fixed(i))
      result.displacement[i] = prescribed(i);

  if (free_norm2 > 0.0)
  {
    TrilinosWrappers::MPI::Vector b(all, comm), x(all, comm);
    std::copy(rhs.begin(), rhs.end(), b.begin());
    std::copy(result.displacement.begin(), result.displacement.end(), x.begin());
    std::vector<double>().swap(rhs);

    // ML smoothed aggregation with the six rigid-body modes as near null
    // space (3 dofs per gridpoint, gridpoint-major numbering).
    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic = true;
    data.higher_order_elements = false;
    data.smoother_sweeps = 2;
    data.aggregation_threshold = 1e-4;
    data.constant_modes.assign(3, std::vector<bool>(n_dofs, false));
    for (unsigned int i = 0; i < n_dofs; ++i)
      data.constant_modes[i % 3][i] = true;
    Teuchos::ParameterList parameters;
    std::unique_ptr<Epetra_MultiVector> constant_modes;
    data.set_parameters(parameters, constant_modes, matrix);
    double centre[3] = {0.0, 0.0, 0.0}, radius = 0.0;
    for (unsigned int i = 0; i < ng; ++i)
      for (unsigned int d = 0; d < 3; ++d)
        centre[d] += m.position[3 * i + d] / ng;
    for (unsigned int i = 0; i < ng; ++i)
    {
      double r2 = 0.0;
      for (unsigned int d = 0; d < 3; ++d)
        r2 += std::pow(m.position[3 * i + d] - centre[d], 2);
      radius = std::max(radius, std::sqrt(r2));
    }
    if (!(radius > 0.0))
      radius = 1.0;
    std::vector<double> rigid_modes(6 * n_dofs);
    for (unsigned int i = 0; i < ng; ++i)
    {
      double r[3];
      for (unsigned int d = 0; d < 3; ++d)
        r[d] = (m.position[3 * i + d] - centre[d]) / radius;
      for (unsigned int k = 0; k < 6; ++k)
        for (unsigned int d = 0; d < 3; ++d)
          rigid_modes[k * n_dofs + 3 * i + d] = rigid_mode(k, d, r);
    }
    parameters.set("PDE equations", 3);
    parameters.set("null space: type", "pre-computed");
    parameters.set("null space: add default vectors", false);
    parameters.set("null space: dimension", 6);
    parameters.set("null space: vectors", rigid_modes.data());
    TrilinosWrappers::PreconditionAMG amg;
    amg.initialize(matrix, parameters);

    SolverControl control(p.max_iterations, p.tolerance * std::sqrt(free_norm2), false, false);
    using Vector = TrilinosWrappers::MPI::Vector;
    result.method = p.apply && !p.symmetric ? "GMRES" : "CG";
    try
    {
      if (!p.apply)
        SolverCG<Vector>(control).solve(matrix, x, b, amg);
      else if (p.symmetric)
        SolverCG<Vector>(control).solve(MatrixFreeOperator(p.apply, fixed_dof, fixed_diagonal), x,
                                        b, amg);
      else // right preconditioning: the tolerance is on the true residual
        SolverGMRES<Vector>(control, SolverGMRES<Vector>::AdditionalData(100, true))
            .solve(MatrixFreeOperator(p.apply, fixed_dof, fixed_diagonal), x, b, amg);
    }
    catch (const SolverControl::NoConvergence& e)
    {
      std::ostringstream what;
      what << "implicit elastic solve: " << result.method << " did not converge: relative residual "
           << e.last_residual / std::sqrt(free_norm2) << " after " << e.last_step
           << " iterations (tolerance " << p.tolerance << ", max_iterations " << p.max_iterations
           << ")";
      throw SolverError(what.str());
    }
    result.iterations = control.last_step();
    std::copy(x.begin(), x.end(), result.displacement.begin());
    // Prescribed components exactly as given (CG leaves them within tolerance).
    for (unsigned int i = 0; i < n_dofs; ++i)
      if (is_fixed(i))
        result.displacement[i] = prescribed(i);
  }
  result.seconds = seconds_since(start);
  return result;
}

} // namespace talus
