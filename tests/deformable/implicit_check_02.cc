// The implicit check (check_implicitly, 'Implicit check' of a scene) must
// solve the explicit kernels' own discrete problem for every zone
// formulation: the cantilever of parameters/verification/cantilever.prm
// (10 m x 1 m x 1 m under its own weight, clamped at x = 0) with 4-node
// zones, nodal mixed discretization (eqs. 68-76), hexahedral zones of two
// overlays (eqs. 60-67) and 10-node zones, each settled to a ratio of 1e-7.
// E = 1e12 Pa keeps the tip rotation at 4e-5, so that the explicit run's
// update of the geometry (which the linear implicit problem leaves out)
// moves the answer by about 1e-5 only. For each: the operator applied
// matrix-free is symmetric, the largest difference between the two
// answers over the largest displacement component is below 1e-3, and the
// check leaves the run's state as it was. Before
// the check used the kernels' operator it assembled plain 4-node
// stiffness: 0.11 for nodal mixed discretization, 1.3 for hexahedral zones
// (both overlays at full stiffness), no check for 10-node zones. For
// 4-node zones the kernels' operator must give the assembled stiffness's
// answer.

#include <talus/solver/implicit_check.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <random>

#include "../tests.h"
#include "deformable_scene.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  const char* names[] = {"4-node zones", "nodal mixed discretization", "hexahedral zones",
                         "10-node zones"};
  for (int kind = 0; kind < 4; ++kind)
  {
    DeformableScene s("verification/cantilever.prm",
                      [&](talus::Scene& scene)
                      {
                        scene.deformable.edge_length = kind == 3 ? 1.0 : 0.5;
                        scene.deformable.material.set_young_poisson(1e12, 0.25);
                        scene.deformable.material.nodal_mixed = kind == 1;
                        if (kind == 2)
                          scene.deformable.material.element = talus::ZoneElement::hex_mixed;
                        if (kind == 3)
                          scene.deformable.material.element = talus::ZoneElement::tet10;
                        scene.solver.damping = talus::Damping::adaptive_global;
                      });
    const char* name = names[kind];
    const double target = 1e-7;
    const unsigned long steps = s.solver->run_to_ratio(target, 200000);
    std::cerr << name << ": " << s.mesh.n_zones() << " zones, " << steps << " steps, ratio "
              << s.solver->unbalanced_ratio() << "\n";
    std::printf("%s: explicit run settled below a ratio of 1e-7: %s\n", name,
                talus_test::verdict(s.solver->unbalanced_ratio() < target));

    // Symmetry of the operator on random displacements (held components
    // zero, as the solver eliminates them).
    const unsigned int n = 3 * s.mesh.n_gridpoints();
    const talus::ImplicitElasticProblem problem = s.solver->implicit_problem();
    std::mt19937 random(7);
    std::uniform_real_distribution<double> uniform(-1e-4, 1e-4);
    std::vector<double> u(n), w(n), Ku(n), Kw(n);
    for (unsigned int i = 0; i < n; ++i)
    {
      const bool held = problem.fixed[i / 3] & (1u << (i % 3));
      u[i] = held ? 0.0 : uniform(random);
      w[i] = held ? 0.0 : uniform(random);
    }
    s.solver->elastic_operator(u.data(), Ku.data());
    s.solver->elastic_operator(w.data(), Kw.data());
    double uKw = 0.0, wKu = 0.0, uKu = 0.0, norm_u = 0.0, norm_Kw = 0.0;
    for (unsigned int i = 0; i < n; ++i)
    {
      uKw += u[i] * Kw[i];
      wKu += w[i] * Ku[i];
      uKu += u[i] * Ku[i];
      norm_u += u[i] * u[i];
      norm_Kw += Kw[i] * Kw[i];
    }
    const double asymmetry = std::abs(uKw - wKu) / std::sqrt(norm_u * norm_Kw);
    std::cerr << name << ": |u.Kw - w.Ku| / (|u| |Kw|) = " << asymmetry << ", u.Ku = " << uKu
              << " J\n";
    std::printf("%s: operator symmetric (to 1e-10) and positive: %s\n", name,
                talus_test::verdict(asymmetry < 1e-10 && uKu > 0.0));

    const talus::Vec3 tip(10.0, 0.5, 0.5);
    const std::vector<double> positions = s.solver->positions(),
                              velocities = s.solver->velocities(), stress = s.solver->stress();
    const talus::ImplicitCheck check = talus::check_implicitly(*s.solver, {tip});
    std::printf("%s: the run's state unchanged by the check: %s\n", name,
                talus_test::verdict(positions == s.solver->positions() &&
                                    velocities == s.solver->velocities() &&
                                    stress == s.solver->stress()));
    const talus::ImplicitCheckPoint& p = check.points[0];
    std::cerr << name << ": " << check.implicit.method << " " << check.implicit.iterations
              << " iterations; at (" << p.position.transpose() << ") explicit ("
              << p.explicit_displacement.transpose() << ") m, implicit ("
              << p.implicit_displacement.transpose() << ") m; largest component " << check.largest
              << " m, largest difference " << check.difference << " m, "
              << check.difference / check.largest << " of it\n";
    std::printf("%s: %s; gridpoint at the tip (10, 0.5, 0.5): %s; largest difference over "
                "largest displacement component below 1e-3: %s\n",
                name, check.implicit.method, talus_test::verdict((p.position - tip).norm() < 1e-9),
                talus_test::verdict(check.difference < 1e-3 * check.largest));
    if (kind == 0)
    {
      // The kernels' operator of 4-node zones is the assembled stiffness.
      const talus::ImplicitElasticResult assembled = talus::solve_implicit_elastic(problem);
      double difference = 0.0;
      for (unsigned int i = 0; i < n; ++i)
        difference = std::max(difference,
                              std::abs(assembled.displacement[i] - check.implicit.displacement[i]));
      std::cerr << name << ": kernels' operator against the assembled stiffness: "
                << difference / check.largest << "\n";
      std::printf("%s: the kernels' operator gives the assembled stiffness's answer to 1e-8: %s\n",
                  name, talus_test::verdict(difference < 1e-8 * check.largest));
    }
  }
}
