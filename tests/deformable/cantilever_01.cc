// Verification 3: a cantilever under its own weight
// (parameters/verification/cantilever.prm), 10 m x 1 m x 1 m, clamped at
// x = 0, for three zone sizes. The mean vertical displacement of the tip
// face is compared with beam theory including shear (Timoshenko):
//   q L^4 / (8 E I) + q L^2 / (2 k G A), q = rho g A, k = 5/6.
// Constant-strain tetrahedra are too stiff in bending; the error must fall
// as the zones get smaller (the 10-node tetrahedra of the accuracy study
// remove most of it).

#include <cmath>
#include <cstdio>
#include <iostream>

#include "../tests.h"
#include "deformable_scene.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  double last_error = 1.0;
  for (const double edge : {0.5, 1.0 / 3.0, 0.25})
  {
    DeformableScene s("verification/cantilever.prm",
                      [&](talus::Scene& scene)
                      {
                        scene.deformable.edge_length = edge;
                        scene.solver.damping = talus::Damping::adaptive_global;
                      });
    const unsigned long steps = s.solver->run_to_ratio(1e-5, 200000);
    std::cerr << "edge " << edge << ": " << s.mesh_report.zones << " zones, " << steps
              << " steps\n";
    const talus::ZoneMaterial& m = s.scene.deformable.material;
    const double L = 10.0, A = 1.0, I = 1.0 / 12.0, q = s.scene.density * 9.81 * A;
    const double exact = q * std::pow(L, 4) / (8.0 * m.young() * I) +
                         q * L * L / (2.0 * 5.0 / 6.0 * m.shear_modulus * A);
    const double tip = -s.mean_displacement(2, 0, L);
    const double error = std::abs(tip - exact) / exact;
    std::printf("edge %.3g m (%u zones): %s; tip deflection %.4g m, beam theory %.4g m, relative "
                "error %.2f "
                "%s\n",
                edge, s.mesh_report.zones,
                s.solver->unbalanced_ratio() < 1e-5 ? "converged" : "NOT converged", tip, exact,
                error, error < last_error ? "(smaller than the coarser mesh)" : "(NOT SMALLER)");
    last_error = error;
  }
}
