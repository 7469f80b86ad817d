// Nodal mixed discretization (eqs. 68-76): the cantilever of
// parameters/verification/cantilever.prm with 0.5 m zones, nearly
// incompressible (nu = 0.49) and at nu = 0.25. Averaging the volumetric
// strain at the gridpoints frees the zones of part of their volume
// constraint, so the tip deflection must come closer to beam theory with
// shear (Timoshenko) than with plain constant-strain tetrahedra. Most of
// the plain error here is bending stiffness of the constant-strain element
// (two zones through the depth), which only higher-order elements remove;
// the test holds the gain from the averaging, not the whole error.

#include <cmath>
#include <cstdio>
#include <iostream>

#include "../tests.h"
#include "deformable_scene.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  for (const double nu : {0.49, 0.25})
  {
    double error_plain = 0.0;
    for (const bool mixed : {false, true})
    {
      DeformableScene s("verification/cantilever.prm",
                        [&](talus::Scene& scene)
                        {
                          scene.deformable.edge_length = 0.5;
                          scene.deformable.material.set_young_poisson(1e10, nu);
                          scene.deformable.material.nodal_mixed = mixed;
                          scene.solver.damping = talus::Damping::adaptive_global;
                        });
      const unsigned long steps = s.solver->run_to_ratio(1e-5, 400000);
      std::cerr << "nu " << nu << (mixed ? " mixed" : " plain") << ": " << steps << " steps\n";
      const talus::ZoneMaterial& m = s.scene.deformable.material;
      const double L = 10.0, A = 1.0, I = 1.0 / 12.0, q = s.scene.density * 9.81 * A;
      const double exact = q * std::pow(L, 4) / (8.0 * m.young() * I) +
                           q * L * L / (2.0 * 5.0 / 6.0 * m.shear_modulus * A);
      const double tip = -s.mean_displacement(2, 0, L);
      const double error = std::abs(tip - exact) / exact;
      std::printf("nu %.2f, %s: %s; tip deflection %.4g m, beam theory %.4g m, relative error %.2f",
                  nu, mixed ? "nodal mixed" : "plain",
                  s.solver->unbalanced_ratio() < 1e-5 ? "converged" : "NOT converged", tip, exact,
                  error);
      if (!mixed)
        error_plain = error;
      else
        std::printf(" %s", error < error_plain - 0.02 ? "(better than plain)" : "(NOT BETTER)");
      std::printf("\n");
    }
  }
}
