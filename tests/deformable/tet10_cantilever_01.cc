// The cantilever of verification 3 (parameters/verification/cantilever.prm,
// 10 m x 1 m x 1 m under its own weight, clamped at x = 0) with 10-node
// zones, for three zone sizes, against beam theory with shear
// (Timoshenko): q L^4 / (8 E I) + q L^2 / (2 k G A), q = rho g A, k = 5/6.
// The 4-node zones of cantilever_01 are 33, 18 and 11 % too stiff at
// 0.5, 0.33 and 0.25 m; the quadratic zones bend.

#include <cmath>
#include <cstdio>
#include <iostream>

#include "../tests.h"
#include "deformable_scene.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  for (const double edge : {1.0, 0.5, 1.0 / 3.0})
  {
    DeformableScene s("verification/cantilever.prm",
                      [&](talus::Scene& scene)
                      {
                        scene.deformable.edge_length = edge;
                        scene.deformable.material.element = talus::ZoneElement::tet10;
                        scene.solver.damping = talus::Damping::adaptive_global;
                      });
    const unsigned long steps = s.solver->run_to_ratio(1e-5, 400000);
    std::cerr << "edge " << edge << ": " << s.mesh.n_zones() << " zones, " << steps << " steps\n";
    const talus::ZoneMaterial& m = s.scene.deformable.material;
    const double L = 10.0, A = 1.0, I = 1.0 / 12.0, q = s.scene.density * 9.81 * A;
    const double exact = q * std::pow(L, 4) / (8.0 * m.young() * I) +
                         q * L * L / (2.0 * 5.0 / 6.0 * m.shear_modulus * A);
    const double tip = -s.mean_displacement(2, 0, L);
    std::printf("edge %.3g m (%u 10-node zones, %u gridpoints): %s; ", edge, s.mesh.n_zones(),
                s.mesh.n_gridpoints(),
                s.solver->unbalanced_ratio() < 1e-5 ? "converged" : "NOT converged");
    talus_test::check("tip deflection (m)", tip, exact, 0.03);
  }
}
