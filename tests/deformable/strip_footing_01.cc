// Verification: a rigid, smooth strip footing (B = 2 m) pushed into a
// weightless cohesive layer (Tresca: Mohr-Coulomb with phi = psi = 0, c =
// 10 kPa), plane strain (parameters/verification/strip_footing.prm, the
// coarsest mesh of the accuracy study, 0.5 m zones). The footing is the
// surface gridpoints under it moving down at a prescribed velocity ('Velocity
// until': 20 mm, then held); the run then settles to the unbalanced-force
// ratio 1e-5, and the footing pressure is the vertical reaction of those
// gridpoints over the area they stand for: out to midway between the last
// footing gridpoint (x = B/2) and the first free one, B/2 + h/2 for these
// zones (over B/2 alone every error would be larger by about h/B, 25 % on
// this mesh). Prandtl: collapse pressure (2 + pi) c.
//
// Plastic flow at phi = psi = 0 keeps the volume; constant-strain
// tetrahedra cannot follow such a mechanism (too few volume-free modes), so
// they lock and overestimate the collapse pressure, by a margin that falls
// only slowly with the zone size. Nodal mixed discretization (eqs. 68-76)
// averages the volumetric strain and plastic pressure at the gridpoints and
// frees the mechanism. Also checked: the footing moved exactly 20 mm (the
// velocity stopped at 'Velocity until').

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <vector>

#include "../tests.h"
#include "deformable_scene.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  const double collapse = (2.0 + M_PI) * 1e4; // Pa
  for (const bool mixed : {false, true})
  {
    DeformableScene s("verification/strip_footing.prm",
                      [&](talus::Scene& scene) { scene.deformable.material.nodal_mixed = mixed; });
    const talus::GridpointCondition& footing = s.scene.gridpoint_conditions[1];
    const double until = footing.velocity_until;
    while (s.solver->time() < until)
      s.solver->step();
    const unsigned long settling = s.solver->run_to_ratio(1e-5, 200000);
    std::cerr << (mixed ? "mixed" : "plain") << ": " << s.solver->steps_done() << " steps ("
              << settling << " settling)\n";
    // The footing's gridpoints end at x = B/2 = 1 m; the nodal force of the
    // last one stands for the surface out to midway to the first free
    // gridpoint, so the loaded half-width is 1 m plus half a zone.
    double first_free = 1e300;
    for (unsigned int g = 0; g < s.mesh.n_gridpoints(); ++g)
      if (std::abs(s.mesh.position[3 * g + 2]) < 1e-9 && s.mesh.position[3 * g] > 1.0 + 1e-9)
        first_free = std::min(first_free, s.mesh.position[3 * g]);
    const double thickness = s.scene.brick.hi.y() - s.scene.brick.lo.y();
    const talus::ReactionReport& reaction = s.scene.reactions[0];
    const double force = s.solver->support_force(reaction.region, reaction.held)[2]; // N, upward
    const double pressure = force / (0.5 * (1.0 + first_free) * thickness);
    std::printf("%s, %u zones: %s\n", mixed ? "nodal mixed discretization" : "plain 4-node zones",
                s.mesh_report.zones,
                s.solver->unbalanced_ratio() < 1e-5 ? "settled to ratio 1e-5" : "NOT settled");
    // Settlement: the mean vertical displacement of the footing's gridpoints.
    const std::vector<double> u = s.solver->displacements();
    double settlement = 0.0;
    unsigned int n = 0;
    for (unsigned int g = 0; g < s.mesh.n_gridpoints(); ++g)
      if (std::abs(s.mesh.position[3 * g + 2]) < 1e-9 && s.mesh.position[3 * g] < 1.0 + 1e-9)
      {
        settlement -= u[3 * g + 2];
        ++n;
      }
    talus_test::check("  footing settlement (m)", settlement / n, 0.02, 1e-9);
    const double error = pressure / collapse - 1.0;
    // The pressure's last digits follow the CPU's rounding (by 5e-5 without
    // fused multiply-adds): the figures to standard error, the error to two
    // digits, which that does not move, to standard output.
    std::fprintf(stderr,
                 "  footing pressure over the half-width %.4g m: %.6g Pa (over 1 m: %.6g Pa), "
                 "(2 + pi) c = %.6g Pa, relative error %+.4f\n",
                 0.5 * (1.0 + first_free), pressure, force / thickness, collapse, error);
    std::printf("  footing pressure against (2 + pi) c: relative error %+.1e %s\n", error,
                mixed ? (std::abs(error) < 0.05 ? "(within 5 %)" : "(NOT WITHIN 5 %)")
                      : (error > 0.05 ? "(plain zones lock: above by more than 5 %)"
                                      : "(NOT ABOVE: locking gone?)"));
  }
}
