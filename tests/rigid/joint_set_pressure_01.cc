// A joint set's own water pressure ('Joint set pressures' of 'Water'): the
// stack of parameters/verification/stack_of_blocks.prm (five 1 m cubes of
// 2650 kg/m^3 on a fixed floor, every joint made by 'Joint set 1') with
// p = 20 kPa in the joint set. Each joint's two faces carry p A (A = 1
// m^2), pushing the blocks apart; the column's top is the brick's face and
// carries none. So every joint's springs carry the effective normal force
// N' = rho g h A - p A (h the height of rock above it), and the floor's
// reaction drops by p A. Without the pressure (the before figure) each
// joint carries rho g h A. The contacts' VTU gives pore_pressure = p.

#include <talus/io/contact_vtu_writer.h>

#include <cmath>
#include <cstdio>

#include "../io/vtu_reading.h"
#include "../tests.h"
#include "rigid_scene.h"

using namespace talus;

void run(double p)
{
  RigidScene s("verification/stack_of_blocks.prm",
               [&](Scene& scene)
               {
                 if (p > 0.0)
                   scene.solver.water.joint_set_pressure = {p};
               });
  s.run_to_ratio(1e-7, 50000);
  std::printf("joint set pressure %.0f kPa: static run %s\n", p / 1000,
              s.solver->unbalanced_ratio() < 1e-7 ? "reached ratio 1e-7" : "NOT converged");
  const ContactSet& c = s.solver->contacts();
  const double rho_g = s.scene.density * 9.81;
  for (unsigned int slot = 0; slot < c.n_slots(); ++slot)
  {
    if (!c.alive[slot])
      continue;
    double fn = 0.0, z = 0.0, area = 0.0;
    for (unsigned int i = 0; i < c.n_subcontacts(); ++i)
      if (c.sc_contact[i] == slot)
      {
        fn += c.sc_fn[i];
        z += c.sc_position[i].z() * c.sc_area[i];
        area += c.sc_area[i];
      }
    z /= area;
    std::printf("  joint at z = %.0f: ", std::round(z));
    talus_test::check_within("normal force (N), rho g h A - p A", fn,
                             rho_g * std::round(6.0 - z) - p, 1e-6);
  }
  if (p > 0.0)
  {
    write_contacts_vtu("stack_contacts.vtu", c, s.model, JointNumbers{{1}, {}}, VtuEncoding::binary,
                       &s.scene.solver.water, 9.81);
    const vtu_reading::Array a = vtu_reading::find(
        vtu_reading::read_arrays(vtu_reading::read_text("stack_contacts.vtu")), "pore_pressure");
    bool all = a.values.size() == c.n_subcontacts();
    for (double v : a.values)
      all &= v == p;
    std::printf("  pore_pressure of every sub-contact in the contacts' VTU is p: %s\n",
                talus_test::verdict(all));
  }
}

int main()
{
  run(0.0);
  run(20000.0);
}
