#pragma once

// A reference solver, not part of the calculation cycle: the static
// linear-elastic answer of a TetMesh computed implicitly (CG with algebraic
// multigrid), to check the explicit solver's static answer against. By
// itself it assembles constant-strain 4-node tetrahedra, small strain,
// isotropic elasticity (eq. 59): the explicit kernel in its plain form.
// Given the explicit kernels' own operator (ImplicitElasticProblem::apply),
// it solves their discrete problem instead (nodal mixed discretization,
// hexahedral zones, 10-node zones), with the assembled 4-node stiffness as
// the preconditioner only. Kept free of deal.II/Trilinos headers.

#include <functional>
#include <memory>
#include <vector>

#include <talus/zone/tet_mesh.h>

namespace talus
{

/// The static problem K u = f with some displacement components prescribed.
/// SI units throughout.
struct ImplicitElasticProblem
{
  const TetMesh* mesh = nullptr;
  /// Bulk modulus K and shear modulus G of every zone, Pa (both > 0).
  std::vector<double> zone_bulk, zone_shear;
  /// Applied forces, 3 per gridpoint, N (lumped gravity, loads, tractions);
  /// empty means none. Ignored on prescribed components.
  std::vector<double> nodal_force;
  /// Per gridpoint: bit d set = displacement component d is prescribed.
  /// Empty means nothing prescribed (then the problem is singular).
  std::vector<unsigned char> fixed;
  /// Prescribed displacements, 3 per gridpoint, m, read where `fixed` says
  /// so; empty means zero.
  std::vector<double> prescribed;
  /// Relative residual ||b - K u|| / ||b|| at which CG stops.
  double tolerance = 1e-10;
  /// CG gives up (and the solver throws) after this many iterations.
  unsigned int max_iterations = 10000;
  /// When set, the operator of the problem, applied matrix-free: Ku = K u,
  /// 3 numbers per gridpoint each, every component (the solver zeroes the
  /// prescribed components of u before it calls, and replaces those of
  /// Ku). The 4-node stiffness of `mesh` (with `zone_bulk`, `zone_shear`)
  /// then only builds the AMG preconditioner, so `mesh` need only have the
  /// same gridpoints, e.g. the sub-tetrahedra of 10-node zones.
  std::function<void(const double* u, double* Ku)> apply;
  /// Whether `apply` is symmetric (CG); if not, GMRES solves.
  bool symmetric = true;
  /// Keeps a mesh made for the problem alive (then `mesh` points to it).
  std::shared_ptr<const TetMesh> own_mesh;
};

struct ImplicitElasticResult
{
  /// Displacements, 3 per gridpoint, m; prescribed components hold exactly
  /// the prescribed values.
  std::vector<double> displacement;
  /// Iterations of the Krylov method ("CG", or "GMRES" for an operator
  /// that is not symmetric).
  unsigned int iterations = 0;
  const char* method = "CG";
  /// Wall time of the whole call (checks, assembly, AMG setup, CG), s.
  double seconds = 0.0;
};

/// Assembles the constant-strain tetrahedron stiffness into a Trilinos
/// matrix, eliminates the prescribed components symmetrically (their
/// columns move to the right-hand side, their rows keep only the diagonal)
/// and solves with CG preconditioned by ML algebraic multigrid, which is
/// given the six rigid-body modes as its near null space. With
/// `problem.apply`, the same elimination on that operator (its rows of the
/// prescribed components are the assembled matrix's), CG or GMRES on it,
/// the AMG of the assembled matrix as preconditioner.
///
/// Serial: the system lives on MPI_COMM_SELF, so under mpirun every rank
/// solves the whole problem by itself. MPI must have been initialised by the
/// caller (a dealii::Utilities::MPI::MPI_InitFinalize object in main, which
/// the explicit solver's PETSc vectors need anyway); the library does not
/// initialise MPI itself because it could not finalise it at the right time.
///
/// Throws SolverError (talus/base/exceptions.h) when MPI is not initialised,
/// the input is inconsistent (array sizes, moduli <= 0, a zone of
/// non-positive volume), the prescribed components leave a rigid-body motion
/// free in some connected part of the mesh (singular system), or CG does not
/// reach the tolerance within max_iterations.
ImplicitElasticResult solve_implicit_elastic(const ImplicitElasticProblem& problem);

} // namespace talus
