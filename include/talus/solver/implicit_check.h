#pragma once

// The implicit check of a static elastic run of deformable blocks: the
// static answer of the explicit kernels' own discrete problem, solved
// implicitly, against the explicit run's displacements.

#include <talus/geometry/plane.h>
#include <talus/solver/deformable_solver.h>
#include <talus/zone/implicit_elastic.h>

#include <vector>

namespace talus
{

/// Explicit and implicit displacements (m) at one gridpoint.
struct ImplicitCheckPoint
{
  unsigned int gridpoint = 0;
  Vec3 position = Vec3::Zero(); ///< initial, m
  Vec3 explicit_displacement = Vec3::Zero(), implicit_displacement = Vec3::Zero();
};

struct ImplicitCheck
{
  ImplicitElasticResult implicit; ///< displacements, iterations, method
  /// The largest displacement component of the implicit answer and the
  /// largest difference of a component between the two answers (m).
  double largest = 0.0, difference = 0.0;
  /// At the gridpoint nearest each point asked for, or, with none asked
  /// for, at the gridpoint of the largest implicit displacement.
  std::vector<ImplicitCheckPoint> points;
};

/// Solves K u = f for the solver's zones as its kernels have them (nodal
/// mixed discretization, hexahedral zones, 10-node zones alike), K applied
/// matrix-free by DeformableSolver::elastic_operator inside CG (GMRES if
/// it is not symmetric) preconditioned by AMG of the 4-node stiffness;
/// f: gravity, gridpoint loads and face loads as the run applies them on
/// the initial geometry; held components fixed at zero. The caller checks
/// that this is the run's problem (static, elastic zones, no initial
/// stress, boundaries at rest). Throws SolverError as
/// solve_implicit_elastic does.
/// `explicit_u` (m, 3 per gridpoint), when given, is the explicit answer in
/// place of the solver's own displacements: a body split among ranks
/// gathers its own into a solver of the whole mesh made for the check.
ImplicitCheck check_implicitly(DeformableSolver& solver, const std::vector<Vec3>& points,
                               double tolerance = 1e-10,
                               const std::vector<double>* explicit_u = nullptr);

} // namespace talus
