// Verification 4: a column of six 1 m cubes on a fixed one, settled by the
// static solver (parameters/verification/stack_of_blocks.prm). The joint
// under k cubes carries rho g k and closes by rho g k / kn; the floor
// carries the weight of all five free cubes.

#include <cmath>
#include <cstdio>

#include "../tests.h"
#include "rigid_scene.h"

int main()
{
  RigidScene s("verification/stack_of_blocks.prm");
  const unsigned long steps = s.run_to_ratio(1e-7, 50000);
  std::printf("static run: %s\n",
              s.solver->unbalanced_ratio() < 1e-7 ? "reached ratio 1e-7" : "NOT converged");
  (void)steps;
  const talus::ContactSet& c = s.solver->contacts();
  const double rho_g = s.scene.density * 9.81, kn = s.scene.solver.joint.normal_stiffness;
  std::printf("contacts: %u, sub-contacts: %u\n", c.n_contacts(), c.n_subcontacts());
  for (unsigned int slot = 0; slot < c.n_slots(); ++slot)
  {
    if (!c.alive[slot])
      continue;
    // Joint height: the top of the lower block; blocks above it: 6 - z.
    double fn = 0.0, closure = 0.0, area = 0.0, z = 0.0;
    for (unsigned int i = 0; i < c.n_subcontacts(); ++i)
      if (c.sc_contact[i] == slot)
      {
        fn += c.sc_fn[i];
        closure -= c.sc_un[i] * c.sc_area[i];
        area += c.sc_area[i];
        z += c.sc_position[i].z() * c.sc_area[i];
      }
    closure /= area;
    z /= area;
    const double above = std::round(6.0 - z);
    const double stress = rho_g * above;
    // Values and errors to standard error (their last digits follow the
    // rounding of a run stopped at a ratio), the checks to standard output.
    std::printf("joint at z = %.0f: area %.6g m^2\n", std::round(z), area);
    std::printf("  ");
    talus_test::check_within("normal stress (Pa), against rho g h", fn / area, stress, 1e-6);
    std::printf("  ");
    talus_test::check_within("closure (m), against sigma / kn", closure, stress / kn, 1e-6);
    if (std::round(z) == 1.0)
    {
      std::printf("  ");
      talus_test::check_within("floor reaction (N), against the weight of the free blocks", fn,
                               5 * rho_g, 1e-6);
    }
  }
}
