// Verification of the implicit elastic reference solver on a box of
// constant-strain tetrahedra against closed-form answers. Every field below
// is linear in x, which constant-strain tetrahedra represent exactly, so
// errors are those of the CG tolerance and round-off only:
//  - uniaxial compression of a homogeneous box: u_z = -p z / E on top,
//    lateral expansion nu p x / E, free of constraint;
//  - the same for two layers with E2 = 2 E1, nu2 = 2 nu1 (equal lateral
//    strain, so the layers stay compatible): per-zone moduli are read;
//  - patch test: a linear field prescribed on the boundary of a distorted
//    mesh is reproduced at the interior gridpoints;
//  - a singular system (no fixity; only u_z fixed on the base) is refused,
//    and so is a CG run stopped before the tolerance;
//  - an operator given matrix-free (ImplicitElasticProblem::apply): the
//    layered box and the patch test (prescribed values lifted through the
//    operator) with the stiffness of the layered moduli applied element by
//    element and the preconditioner assembled with other moduli (one
//    layer, three times as stiff): the answer is the operator's, by CG and
//    by GMRES (as for an operator that is not symmetric).
// With an argument n, instead times the uniaxial case on n^3 x 6 tets.

#include <talus/base/exceptions.h>
#include <talus/zone/implicit_elastic.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <stdexcept>
#include <string>

#include "../tests.h"

namespace
{

/// Box [0,Lx]x[0,Ly]x[0,Lz] (m) with n cells per side, each hex split into
/// the 6 tetrahedra around its main diagonal (conforming between cells).
/// `distort` (fraction of a cell) moves interior gridpoints by a fixed
/// smooth pattern, so that the patch test runs on irregular zones.
talus::TetMesh box(unsigned int n, double Lx, double Ly, double Lz, double distort = 0.0)
{
  talus::TetMesh m;
  const unsigned int np = n + 1;
  const auto id = [np](unsigned int i, unsigned int j, unsigned int k)
  { return i + np * (j + np * k); };
  for (unsigned int k = 0; k < np; ++k)
    for (unsigned int j = 0; j < np; ++j)
      for (unsigned int i = 0; i < np; ++i)
      {
        double x[3] = {Lx * i / n, Ly * j / n, Lz * k / n};
        const bool interior = i > 0 && j > 0 && k > 0 && i < n && j < n && k < n;
        if (interior && distort > 0.0)
        {
          x[0] += distort * Lx / n * std::sin(1.7 * i + 2.3 * j + 0.7 * k);
          x[1] += distort * Ly / n * std::sin(0.9 * i + 1.3 * j + 2.9 * k);
          x[2] += distort * Lz / n * std::sin(2.1 * i + 0.4 * j + 1.1 * k);
        }
        m.position.insert(m.position.end(), x, x + 3);
      }
  const unsigned int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                    {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (unsigned int k = 0; k < n; ++k)
    for (unsigned int j = 0; j < n; ++j)
      for (unsigned int i = 0; i < n; ++i)
        for (const auto& p : perms)
        {
          // Walk from corner (i,j,k) to (i+1,j+1,k+1) one axis at a time.
          std::array<unsigned int, 4> t;
          unsigned int c[3] = {i, j, k};
          t[0] = id(c[0], c[1], c[2]);
          for (unsigned int s = 0; s < 3; ++s)
          {
            ++c[p[s]];
            t[s + 1] = id(c[0], c[1], c[2]);
          }
          // Positive orientation: swap two vertices if the volume is negative.
          const auto X = [&](unsigned int v, unsigned int d) { return m.position[3 * v + d]; };
          double e[3][3];
          for (unsigned int a = 0; a < 3; ++a)
            for (unsigned int d = 0; d < 3; ++d)
              e[a][d] = X(t[a + 1], d) - X(t[0], d);
          const double det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                             e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                             e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
          if (det < 0.0)
            std::swap(t[2], t[3]);
          m.zone_gridpoint.push_back(t);
          m.zone_block.push_back(0);
        }
  m.gridpoint_block.assign(m.n_gridpoints(), 0);
  return m;
}

/// Uniform pressure p (Pa) on the face z = Lz as consistent (= lumped) nodal
/// forces: a third of each boundary triangle's force to each of its corners.
std::vector<double> top_pressure(const talus::TetMesh& m, double Lz, double p)
{
  std::vector<double> f(m.position.size(), 0.0);
  const auto on_top = [&](unsigned int v) { return std::abs(m.position[3 * v + 2] - Lz) < 1e-12; };
  for (const auto& t : m.zone_gridpoint)
  {
    std::vector<unsigned int> top;
    for (unsigned int v : t)
      if (on_top(v))
        top.push_back(v);
    if (top.size() != 3)
      continue;
    double a[3], b[3];
    for (unsigned int d = 0; d < 3; ++d)
    {
      a[d] = m.position[3 * top[1] + d] - m.position[3 * top[0] + d];
      b[d] = m.position[3 * top[2] + d] - m.position[3 * top[0] + d];
    }
    const double area = 0.5 * std::abs(a[0] * b[1] - a[1] * b[0]); // face lies in z = Lz
    for (unsigned int v : top)
      f[3 * v + 2] -= p * area / 3.0;
  }
  return f;
}

unsigned int nearest(const talus::TetMesh& m, double x, double y, double z)
{
  unsigned int best = 0;
  double best_d = 1e300;
  for (unsigned int i = 0; i < m.n_gridpoints(); ++i)
  {
    const double d = std::pow(m.position[3 * i] - x, 2) + std::pow(m.position[3 * i + 1] - y, 2) +
                     std::pow(m.position[3 * i + 2] - z, 2);
    if (d < best_d)
      best = i, best_d = d;
  }
  return best;
}

/// Uniaxial compression of an n^3 x 6 box, Lx x Ly x Lz = 1 x 1.5 x 2 m,
/// pressure p = 1 MPa on top. Bottom: u_z = 0; origin: u_x = u_y = 0;
/// (0, Ly, 0): u_x = 0 (stops the rotation about z, leaves the Poisson
/// expansion free). `layered`: zones above z = Lz/2 have E2 = 2 E1, nu2 = 2 nu1.
void uniaxial(unsigned int n, bool layered, bool print)
{
  const double Lx = 1.0, Ly = 1.5, Lz = 2.0, p = 1e6;
  const double E1 = 1e10, nu1 = 0.15, E2 = 2 * E1, nu2 = 2 * nu1;
  const talus::TetMesh m = box(n, Lx, Ly, Lz);
  talus::ImplicitElasticProblem prob;
  prob.mesh = &m;
  // Tight for the check; the timing run keeps the default.
  if (print)
    prob.tolerance = 1e-13;
  for (const auto& t : m.zone_gridpoint)
  {
    double zc = 0.0;
    for (unsigned int v : t)
      zc += 0.25 * m.position[3 * v + 2];
    const bool upper = layered && zc > 0.5 * Lz;
    const double E = upper ? E2 : E1, nu = upper ? nu2 : nu1;
    prob.zone_bulk.push_back(E / (3 * (1 - 2 * nu)));
    prob.zone_shear.push_back(E / (2 * (1 + nu)));
  }
  prob.nodal_force = top_pressure(m, Lz, p);
  prob.fixed.assign(m.n_gridpoints(), 0);
  for (unsigned int i = 0; i < m.n_gridpoints(); ++i)
    if (m.position[3 * i + 2] == 0.0)
      prob.fixed[i] |= 4;
  prob.fixed[nearest(m, 0, 0, 0)] |= 1 | 2;
  prob.fixed[nearest(m, 0, Ly, 0)] |= 1;
  const talus::ImplicitElasticResult r = talus::solve_implicit_elastic(prob);
  // Exact: sigma_zz = -p in both layers; strain -p/E axially, nu p/E laterally.
  const auto exact = [&](const double* x, unsigned int d)
  {
    if (d < 2)
      return nu1 * p / E1 * x[d];
    if (!layered || x[2] <= 0.5 * Lz)
      return -p / E1 * x[2];
    return -p / E1 * 0.5 * Lz - p / E2 * (x[2] - 0.5 * Lz);
  };
  double max_error = 0.0;
  for (unsigned int i = 0; i < m.n_gridpoints(); ++i)
    for (unsigned int d = 0; d < 3; ++d)
      max_error =
          std::max(max_error, std::abs(r.displacement[3 * i + d] - exact(&m.position[3 * i], d)));
  if (!print)
  {
    std::printf("uniaxial %u^3 x 6 tets (%u gridpoints), tolerance %g: %.3f s, %u CG iterations, "
                "max |u - exact| / (p Lz / E1) = %.1e\n",
                n, m.n_gridpoints(), prob.tolerance, r.seconds, r.iterations,
                max_error / (p * Lz / E1));
    return;
  }
  const char* what = layered ? "layered" : "uniaxial";
  const unsigned int corner = nearest(m, Lx, Ly, Lz);
  const double* xc = &m.position[3 * corner];
  std::printf("%s, %u^3 x 6 tets: ", what, n);
  talus_test::check("u_z at (Lx, Ly, Lz) (m)", r.displacement[3 * corner + 2], exact(xc, 2), 1e-9);
  std::printf("%s, %u^3 x 6 tets: ", what, n);
  talus_test::check("u_x at (Lx, Ly, Lz) (m)", r.displacement[3 * corner], exact(xc, 0), 1e-9);
  std::printf("%s, %u^3 x 6 tets: ", what, n);
  talus_test::check("u_y at (Lx, Ly, Lz) (m)", r.displacement[3 * corner + 1], exact(xc, 1), 1e-9);
  std::printf("%s, %u^3 x 6 tets: ", what, n);
  talus_test::check("max |u - exact| / (p Lz / E1) over all gridpoints", max_error / (p * Lz / E1),
                    0.0, 1e-9);
}

/// Patch test on a distorted 10^3 x 6 box: u = u0 + A x (m) on every boundary
/// gridpoint, no forces; the interior must follow the same field.
void patch()
{
  const unsigned int n = 10;
  const talus::TetMesh m = box(n, 1.0, 1.0, 1.0, 0.25);
  const double u0[3] = {1e-3, -2e-3, 0.5e-3};
  const double A[3][3] = {{1e-3, 2e-4, -3e-4}, {-1e-4, -5e-4, 4e-4}, {3e-4, 1e-4, 2e-3}};
  const auto exact = [&](const double* x, unsigned int d)
  { return u0[d] + A[d][0] * x[0] + A[d][1] * x[1] + A[d][2] * x[2]; };
  talus::ImplicitElasticProblem prob;
  prob.mesh = &m;
  prob.tolerance = 1e-13;
  prob.zone_bulk.assign(m.n_zones(), 3.333e10);
  prob.zone_shear.assign(m.n_zones(), 2.5e10);
  prob.fixed.assign(m.n_gridpoints(), 0);
  prob.prescribed.assign(3 * m.n_gridpoints(), 0.0);
  unsigned int n_interior = 0;
  for (unsigned int i = 0; i < m.n_gridpoints(); ++i)
  {
    const double* x = &m.position[3 * i];
    bool boundary = false;
    for (unsigned int d = 0; d < 3; ++d)
      boundary = boundary || x[d] == 0.0 || x[d] == 1.0;
    if (!boundary)
    {
      ++n_interior;
      continue;
    }
    prob.fixed[i] = 7;
    for (unsigned int d = 0; d < 3; ++d)
      prob.prescribed[3 * i + d] = exact(x, d);
  }
  const talus::ImplicitElasticResult r = talus::solve_implicit_elastic(prob);
  double max_error = 0.0, scale = 0.0;
  for (unsigned int i = 0; i < m.n_gridpoints(); ++i)
    if (prob.fixed[i] == 0)
      for (unsigned int d = 0; d < 3; ++d)
      {
        const double e = exact(&m.position[3 * i], d);
        max_error = std::max(max_error, std::abs(r.displacement[3 * i + d] - e));
        scale = std::max(scale, std::abs(e));
      }
  const unsigned int centre = nearest(m, 0.5, 0.5, 0.5);
  const double* xc = &m.position[3 * centre];
  std::printf("patch test, distorted %u^3 x 6 tets, %u interior gridpoints\n", n, n_interior);
  for (unsigned int d = 0; d < 3; ++d)
  {
    std::printf("patch test: ");
    talus_test::check(std::string("u_") + "xyz"[d] + " at the gridpoint nearest the centre (m)",
                      r.displacement[3 * centre + d], exact(xc, d), 1e-9);
  }
  std::printf("patch test: ");
  talus_test::check("max |u - exact| / max |u| over interior gridpoints", max_error / scale, 0.0,
                    1e-9);
}

/// K u of constant-strain tetrahedra (eq. 59), element by element, with
/// per-zone moduli: a matrix-free operator for ImplicitElasticProblem.
std::function<void(const double*, double*)>
tet4_operator(const talus::TetMesh& m, std::vector<double> bulk, std::vector<double> shear)
{
  return [&m, bulk, shear](const double* u, double* Ku)
  {
    std::fill(Ku, Ku + m.position.size(), 0.0);
    for (unsigned int z = 0; z < m.n_zones(); ++z)
    {
      const auto& t = m.zone_gridpoint[z];
      double e[3][3], g[4][3];
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int d = 0; d < 3; ++d)
          e[a][d] = m.position[3 * t[a + 1] + d] - m.position[3 * t[0] + d];
      // Gradients of the barycentric coordinates: rows of the inverse of
      // the matrix whose columns are the edges.
      const double det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                         e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                         e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int d = 0; d < 3; ++d)
        {
          const unsigned int b = (a + 1) % 3, c = (a + 2) % 3, d1 = (d + 1) % 3, d2 = (d + 2) % 3;
          g[a + 1][d] = (e[b][d1] * e[c][d2] - e[b][d2] * e[c][d1]) / det;
        }
      for (unsigned int d = 0; d < 3; ++d)
        g[0][d] = -(g[1][d] + g[2][d] + g[3][d]);
      double strain[3][3] = {}, trace = 0.0;
      for (unsigned int a = 0; a < 4; ++a)
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            strain[i][j] += 0.5 * (u[3 * t[a] + i] * g[a][j] + u[3 * t[a] + j] * g[a][i]);
      for (unsigned int i = 0; i < 3; ++i)
        trace += strain[i][i];
      const double G = shear[z], lambda = bulk[z] - 2.0 * G / 3.0, V = det / 6.0;
      for (unsigned int a = 0; a < 4; ++a)
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            Ku[3 * t[a] + i] +=
                V * (2.0 * G * strain[i][j] + (i == j ? lambda * trace : 0.0)) * g[a][j];
    }
  };
}

/// The layered box of uniaxial() and the patch test with the operator
/// given matrix-free and the preconditioner of other moduli.
void matrix_free(bool symmetric)
{
  const char* method = symmetric ? "matrix-free, CG" : "matrix-free, GMRES";
  const double Lx = 1.0, Ly = 1.5, Lz = 2.0, p = 1e6;
  const double E1 = 1e10, nu1 = 0.15, E2 = 2 * E1, nu2 = 2 * nu1;
  {
    const talus::TetMesh m = box(10, Lx, Ly, Lz);
    talus::ImplicitElasticProblem prob;
    prob.mesh = &m;
    prob.tolerance = 1e-13;
    prob.symmetric = symmetric;
    std::vector<double> bulk, shear;
    for (const auto& t : m.zone_gridpoint)
    {
      double zc = 0.0;
      for (unsigned int v : t)
        zc += 0.25 * m.position[3 * v + 2];
      const double E = zc > 0.5 * Lz ? E2 : E1, nu = zc > 0.5 * Lz ? nu2 : nu1;
      bulk.push_back(E / (3 * (1 - 2 * nu)));
      shear.push_back(E / (2 * (1 + nu)));
    }
    prob.apply = tet4_operator(m, bulk, shear);
    prob.zone_bulk.assign(m.n_zones(), 3.0 * E1 / (3 * (1 - 2 * nu1)));
    prob.zone_shear.assign(m.n_zones(), 3.0 * E1 / (2 * (1 + nu1)));
    prob.nodal_force = top_pressure(m, Lz, p);
    prob.fixed.assign(m.n_gridpoints(), 0);
    for (unsigned int i = 0; i < m.n_gridpoints(); ++i)
      if (m.position[3 * i + 2] == 0.0)
        prob.fixed[i] |= 4;
    prob.fixed[nearest(m, 0, 0, 0)] |= 1 | 2;
    prob.fixed[nearest(m, 0, Ly, 0)] |= 1;
    const talus::ImplicitElasticResult r = talus::solve_implicit_elastic(prob);
    std::cerr << method << ", layered: " << r.iterations << " iterations\n";
    double max_error = 0.0;
    for (unsigned int i = 0; i < m.n_gridpoints(); ++i)
    {
      const double* x = &m.position[3 * i];
      const double exact[3] = {nu1 * p / E1 * x[0], nu1 * p / E1 * x[1],
                               x[2] <= 0.5 * Lz ? -p / E1 * x[2]
                                                : -p / E1 * 0.5 * Lz - p / E2 * (x[2] - 0.5 * Lz)};
      for (unsigned int d = 0; d < 3; ++d)
        max_error = std::max(max_error, std::abs(r.displacement[3 * i + d] - exact[d]));
    }
    std::printf("layered, %s (%s): ", method, r.method);
    talus_test::check("max |u - exact| / (p Lz / E1) over all gridpoints",
                      max_error / (p * Lz / E1), 0.0, 1e-9);
  }
  {
    const talus::TetMesh m = box(6, 1.0, 1.0, 1.0, 0.25);
    const double u0[3] = {1e-3, -2e-3, 0.5e-3};
    const double A[3][3] = {{1e-3, 2e-4, -3e-4}, {-1e-4, -5e-4, 4e-4}, {3e-4, 1e-4, 2e-3}};
    const auto exact = [&](const double* x, unsigned int d)
    { return u0[d] + A[d][0] * x[0] + A[d][1] * x[1] + A[d][2] * x[2]; };
    talus::ImplicitElasticProblem prob;
    prob.mesh = &m;
    prob.tolerance = 1e-13;
    prob.symmetric = symmetric;
    prob.apply = tet4_operator(m, std::vector<double>(m.n_zones(), 3.333e10),
                               std::vector<double>(m.n_zones(), 2.5e10));
    prob.zone_bulk.assign(m.n_zones(), 1e10);
    prob.zone_shear.assign(m.n_zones(), 1e10);
    prob.fixed.assign(m.n_gridpoints(), 0);
    prob.prescribed.assign(3 * m.n_gridpoints(), 0.0);
    for (unsigned int i = 0; i < m.n_gridpoints(); ++i)
    {
      const double* x = &m.position[3 * i];
      for (unsigned int d = 0; d < 3; ++d)
        if (x[d] == 0.0 || x[d] == 1.0)
          prob.fixed[i] = 7;
      for (unsigned int d = 0; d < 3 && prob.fixed[i]; ++d)
        prob.prescribed[3 * i + d] = exact(x, d);
    }
    const talus::ImplicitElasticResult r = talus::solve_implicit_elastic(prob);
    double max_error = 0.0, scale = 0.0;
    for (unsigned int i = 0; i < 3 * m.n_gridpoints(); ++i)
    {
      max_error =
          std::max(max_error, std::abs(r.displacement[i] - exact(&m.position[i - i % 3], i % 3)));
      scale = std::max(scale, std::abs(exact(&m.position[i - i % 3], i % 3)));
    }
    std::printf("patch test, %s (%s): ", method, r.method);
    talus_test::check("max |u - exact| / max |u| over all gridpoints", max_error / scale, 0.0,
                      1e-9);
  }
}

/// A singular system must be refused with SolverError, not solved.
void singular(const char* what, bool fix_base_z)
{
  const talus::TetMesh m = box(2, 1.0, 1.0, 1.0);
  talus::ImplicitElasticProblem prob;
  prob.mesh = &m;
  prob.zone_bulk.assign(m.n_zones(), 3.333e10);
  prob.zone_shear.assign(m.n_zones(), 2.5e10);
  prob.nodal_force = top_pressure(m, 1.0, 1e6);
  if (fix_base_z)
  {
    prob.fixed.assign(m.n_gridpoints(), 0);
    for (unsigned int i = 0; i < m.n_gridpoints(); ++i)
      if (m.position[3 * i + 2] == 0.0)
        prob.fixed[i] = 4;
  }
  try
  {
    talus::solve_implicit_elastic(prob);
    std::printf("%s: solved (WRONG: singular system accepted)\n", what);
  }
  catch (const talus::SolverError& e)
  {
    // The message up to the description of the free motion (whose signs are
    // not unique).
    const std::string message = e.what();
    std::printf("%s: SolverError: %s\n", what,
                message.substr(0, message.find("; free motion")).c_str());
  }
}

/// CG stopped short of the tolerance must throw, not return a rough answer.
void no_convergence()
{
  const talus::TetMesh m = box(10, 1.0, 1.0, 1.0);
  talus::ImplicitElasticProblem prob;
  prob.mesh = &m;
  prob.zone_bulk.assign(m.n_zones(), 3.333e10);
  prob.zone_shear.assign(m.n_zones(), 2.5e10);
  prob.nodal_force = top_pressure(m, 1.0, 1e6);
  prob.fixed.assign(m.n_gridpoints(), 0);
  for (unsigned int i = 0; i < m.n_gridpoints(); ++i)
    if (m.position[3 * i + 2] == 0.0)
      prob.fixed[i] = 7;
  prob.tolerance = 1e-13;
  prob.max_iterations = 2;
  try
  {
    talus::solve_implicit_elastic(prob);
    std::printf("2 CG iterations: solved (WRONG: no error)\n");
  }
  catch (const talus::SolverError& e)
  {
    const std::string message = e.what();
    std::printf("2 CG iterations: SolverError: %s\n",
                message.substr(0, message.find(": relative residual")).c_str());
  }
}

} // namespace

int main(int argc, char** argv)
{
  // The solver needs MPI initialised (Trilinos); one thread: shared cores.
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (argc > 1)
  {
    uniaxial(static_cast<unsigned int>(std::atoi(argv[1])), false, false);
    return 0;
  }
  // 10^3 cells: more than the 2000 unknowns that ML solves directly on its
  // coarsest level, so the multigrid hierarchy is exercised.
  uniaxial(10, false, true);
  uniaxial(10, true, true);
  patch();
  singular("no fixity", false);
  singular("only u_z fixed on the base", true);
  no_convergence();
  matrix_free(true);
  matrix_free(false);
}
