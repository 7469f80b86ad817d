#include <talus/base/exceptions.h>
#include <talus/solver/implicit_check.h>

#include <algorithm>
#include <cmath>

namespace talus
{

ImplicitCheck check_implicitly(DeformableSolver& solver, const std::vector<Vec3>& points,
                               double tolerance, const std::vector<double>* explicit_u)
{
  ImplicitElasticProblem problem = solver.implicit_problem();
  problem.tolerance = tolerance;
  problem.apply = [&solver](const double* u, double* Ku) { solver.elastic_operator(u, Ku); };
  ImplicitCheck check;
  check.implicit = solve_implicit_elastic(problem);
  const std::vector<double>& implicit = check.implicit.displacement;
  const std::vector<double> u = explicit_u ? *explicit_u : solver.displacements();
  if (u.size() != implicit.size())
    throw SolverError("internal: the explicit displacements are not of the solver's mesh");
  for (std::size_t i = 0; i < u.size(); ++i)
  {
    check.largest = std::max(check.largest, std::abs(implicit[i]));
    check.difference = std::max(check.difference, std::abs(u[i] - implicit[i]));
  }
  const TetMesh& mesh = solver.mesh();
  const auto at = [&](const std::vector<double>& a, unsigned int g)
  { return Vec3(a[3 * g], a[3 * g + 1], a[3 * g + 2]); };
  std::vector<unsigned int> gridpoints;
  for (const Vec3& p : points)
  {
    unsigned int best = 0;
    for (unsigned int g = 1; g < mesh.n_gridpoints(); ++g)
      if ((at(mesh.position, g) - p).squaredNorm() < (at(mesh.position, best) - p).squaredNorm())
        best = g;
    gridpoints.push_back(best);
  }
  if (points.empty() && mesh.n_gridpoints() > 0)
  {
    unsigned int best = 0;
    for (unsigned int g = 1; g < mesh.n_gridpoints(); ++g)
      if (at(implicit, g).norm() > at(implicit, best).norm())
        best = g;
    gridpoints.push_back(best);
  }
  for (unsigned int g : gridpoints)
    check.points.push_back({g, at(mesh.position, g), at(u, g), at(implicit, g)});
  return check;
}

} // namespace talus
