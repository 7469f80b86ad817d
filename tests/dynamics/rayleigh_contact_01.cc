// Rayleigh damping at the sub-contacts of a deformable block (issue 23): a
// deformable 1 m cube (E = 1e9 Pa, nu = 0.25, rho = 2650 kg/m^3, zones of
// 0.5 m) released at rest on a fixed rigid 1 m cube, joined by a joint of
// kn = ks = 1e9 Pa/m, under gravity: it bounces on the joint's springs
// (omega = sqrt(kn A / m) = 614 rad/s, with the zones' own give).
// Rayleigh damping with xi_min = 0.05 at that frequency: the sub-contacts'
// stiffness-proportional forces act on the cube's gridpoints, the zones'
// viscous stresses within it. Over 0.1 s (about ten periods) the energy
// account closes with the damping as one of its terms: its largest error
// within 1e-5 of its largest term (2e-6), while the damping takes 0.47 of
// the work of gravity; the kinetic energy of the last 0.02 s is below a
// thirtieth of that of the first (0.014, about exp(-2 xi omega 0.07);
// undamped: 1.0). tet4 and tet10 zones.
// Before issue 23 talus refused 'Rayleigh damping ratio'.

#include <talus/base/parallel_environment.h>
#include <talus/scene/block_system.h>
#include <talus/scene/build_blocks.h>
#include <talus/solver/deformable_solver.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "../tests.h"

namespace
{
void run(const std::string& element, double xi)
{
  const double omega = std::sqrt(1e9 / 2650.0);
  const std::string file = "rayleigh_contact.prm";
  std::FILE* f = std::fopen(file.c_str(), "w");
  std::fprintf(f,
               "subsection Model\n  set Brick min = 0, 0, 0\n  set Brick max = 1, 1, 2\nend\n"
               "subsection Material\n  set Density = 2650\nend\n"
               "subsection Joint 1\n  set Dip = 0\n  set Origin = 0, 0, 1\nend\n"
               "subsection Group 1\n  set Name = floor\n  set Corner min = 0, 0, 0\n"
               "  set Corner max = 1, 1, 1\nend\n"
               "subsection Group 2\n  set Name = cube\n  set Corner min = 0, 0, 1\n"
               "  set Corner max = 1, 1, 2\nend\n"
               "subsection Deformable\n  set Groups = cube\n  set Edge length = 0.5\n"
               "  set Element = %s\n  set Young's modulus = 1e9\n  set Poisson's ratio = 0.25\n"
               "end\n"
               "subsection Joint properties\n  set Normal stiffness = 1e9\n"
               "  set Shear stiffness = 1e9\nend\n"
               "subsection Solver\n  set Mode = dynamic\n  set Fixed groups = floor\n"
               "  set Rayleigh damping ratio = %.17g\n  set Rayleigh frequency = %.17g\nend\n",
               element.c_str(), xi, omega / (2.0 * M_PI));
  std::fclose(f);
  talus::Scene scene = talus::read_scene(file, false);
  talus::BuildReport built;
  talus::BlockModel model = talus::build_blocks(scene, built);
  talus::resolve_group_names(scene, model);
  talus::BlockSystem system = talus::build_block_system(scene, model);
  talus::RigidSolver& solver = *system.solver;
  double worst_error = 0.0, scale = 0.0, early = 0.0, late = 0.0, damping = 0.0, gravity = 0.0;
  while (solver.time() < 0.1)
  {
    solver.step();
    const talus::EnergyAccount e = solver.energy_account();
    worst_error = std::max(worst_error, std::abs(e.error()));
    scale = std::max(scale, e.scale());
    if (solver.time() < 0.02)
      early = std::max(early, e.kinetic);
    if (solver.time() > 0.08)
      late = std::max(late, e.kinetic);
    damping = e.damping;
    gravity = e.gravity_work;
  }
  std::fprintf(stderr,
               "%s, xi %g: %lu steps of %.3g s, %u sub-contacts; energy error at most %.2e of "
               "the largest term; damping %.3g of the work of gravity; kinetic energy late over "
               "early %.3g\n",
               element.c_str(), xi, solver.steps_done(), solver.dt(),
               solver.contacts().n_subcontacts(), worst_error / scale, damping / gravity,
               late / early);
  std::printf("%s, xi %g: energy account within 1e-5 of its largest term: %s; kinetic energy "
              "down thirtyfold: %s\n",
              element.c_str(), xi, talus_test::verdict(worst_error <= 1e-5 * scale),
              late < early / 30.0 ? "yes" : "no");
}
} // namespace

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  for (const char* element : {"tet4", "tet10"})
  {
    run(element, 0.0);
    run(element, 0.05);
  }
}
