// Verification 6: a deformable block slides on an incline as the rigid one
// does (parameters/verification/deformable_on_incline.prm against
// block_on_incline.prm): x = g (sin a - cos a tan phi) t^2 / 2 after 0.5 s,
// for the mean displacement of the block's gridpoints.
//
// Undamped, an elastic block sliding with Coulomb friction slowly picks up
// vibration (friction feeds the interface modes from the work of gravity,
// a known instability of frictional sliding); the tolerance, 5e-3, covers
// it over 0.5 s, and the vibration's size is printed.

#include <talus/base/parallel_environment.h>
#include <talus/scene/build_blocks.h>
#include <talus/scene/block_system.h>

#include <cmath>
#include <cstdio>

#include "../tests.h"

using namespace talus;

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  double rigid_x = 0.0;
  for (const char* name : {"block_on_incline.prm", "deformable_on_incline.prm"})
  {
    Scene scene =
        read_scene(std::string(SOURCE_DIR) + "/../../parameters/verification/" + name, false);
    BuildReport built;
    BlockModel model = build_blocks(scene, built);
    resolve_group_names(scene, model);
    BlockSystem system = build_block_system(scene, model);
    RigidSolver& solver = *system.solver;
    while (solver.time() + 0.5 * solver.dt() < 0.5)
      solver.step();
    const double g = 9.81, a = 40.0 * M_PI / 180.0, phi = 20.0 * M_PI / 180.0;
    const double exact =
        g * (std::sin(a) - std::cos(a) * std::tan(phi)) * solver.time() * solver.time() / 2;
    if (!system.zones)
    {
      rigid_x = solver.displacement[1][0];
      std::printf("rigid block: ");
      talus_test::check("slide after 0.5 s (m)", rigid_x, exact, 1e-4);
      continue;
    }
    const std::vector<double> u = system.zones->displacements(), v = system.zones->velocities();
    const unsigned int n = system.mesh.n_gridpoints();
    double x = 0.0, lift = 0.0;
    for (unsigned int gp = 0; gp < n; ++gp)
    {
      x += u[3 * gp] / n;
      lift = std::max(lift, std::abs(u[3 * gp + 2]));
    }
    std::printf("deformable block (%u zones, %u sub-contacts): ", system.mesh.n_zones(),
                solver.contacts().n_subcontacts());
    talus_test::check_within("slide after 0.5 s (m)", x, exact, 5e-3);
    std::printf("  against the rigid block: relative difference %s\n",
                std::abs(x - rigid_x) / rigid_x < 5e-3 ? "below 5e-3" : "TOO LARGE");
    std::fprintf(stderr, "largest vertical displacement of a gridpoint: %.3g m\n", lift);
  }
}
