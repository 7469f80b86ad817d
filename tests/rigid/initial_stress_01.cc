// Joints that start under the in-situ stress: the column of
// parameters/verification/stack_of_blocks.prm with the initial stress of
// its own weight, sigma_zz = -rho g (6 - z). The joints carry rho g h from
// the first step, so the column does not settle: it stays in equilibrium
// where it was built. Without the initial stress it settles by the joint
// closures, sum of rho g h / kn.

#include <talus/scene/build_blocks.h>
#include <talus/scene/block_system.h>

#include <cmath>
#include <cstdio>

#include "../tests.h"

using namespace talus;

int main()
{
  for (const bool stressed : {true, false})
  {
    Scene scene = read_scene(
        std::string(SOURCE_DIR) + "/../../parameters/verification/stack_of_blocks.prm", false);
    const double rho_g = scene.density * 9.81; // Pa/m
    if (stressed)
    {
      scene.has_initial_stress = true;
      scene.initial_stress.z0 = 6.0;            // top of the column
      scene.initial_stress.gradient[2] = rho_g; // sigma_zz = rho g (z - 6)
    }
    BuildReport built;
    BlockModel model = build_blocks(scene, built);
    resolve_group_names(scene, model);
    BlockSystem system = build_block_system(scene, model);
    RigidSolver& solver = *system.solver;
    const ContactSet& c = solver.contacts();
    double floor = 0.0;
    for (unsigned int i = 0; i < c.n_subcontacts(); ++i)
      if (std::abs(c.sc_position[i].z() - 1.0) < 0.5)
        floor += c.sc_fn[i];
    std::printf("%s: floor reaction at the start ",
                stressed ? "with the initial stress" : "without");
    talus_test::check("(N)", floor, stressed ? 5 * rho_g : 0.0, 1e-9);
    for (int k = 0; k < 200; ++k)
      solver.step();
    const double settle = -solver.displacement[5][2];
    const double closures = (5 + 4 + 3 + 2 + 1) * rho_g / scene.solver.joint.normal_stiffness;
    std::printf("  top block settles by %s of the joint closures (%.3g m) in 200 steps\n",
                settle < 1e-6 * closures ? "less than 1e-6"
                                         : (settle > 0.1 * closures ? "more than a tenth" : "SOME"),
                closures);
  }
}
