// A gravity dam (tests/rigid/gravity_dam.prm): a rigid trapezoidal dam,
// 12 m high, crest 3 m, downstream face 0.7 : 1, base B = 11.4 m, a slice
// L = 2 m long, concrete 2400 kg/m^3, on a fixed foundation; the reservoir
// H = 10 m deep on the vertical upstream face, no tailwater, and the
// phreatic surface falling linearly across the base from H at the heel to
// 0 at the toe (a table).
//
// Closed form (per slice): W = rho_c g L (3 x 12 + 0.7 x 12^2 / 2) = rho_c g
// L 86.4 m^2, the reservoir's thrust H = rho_w g L H^2 / 2 on the upstream
// face, the uplift U = rho_w g L H B / 2 (a triangle from rho_w g H at the
// heel to 0 at the toe); the downstream face lies above the surface and
// stays dry. Sliding factor SF = (W - U) tan(phi) / H; the dam slides for
// tan(phi) < H / (W - U), phi < 18.39 deg.
//
// Checks: at phi = 20 deg, the horizontal and vertical water forces the
// code applied against H and U; the sliding factor from them and from the
// joint's own forces at equilibrium (the sum of the base's sub-contact
// normal and shear forces, N tan(phi) / S) against the closed form within
// 1 %; then static runs at phi_limit + 0.5 deg (stands) and - 0.5 deg
// (slides), and, for the before figure, - 0.5 deg without water (stands).
// The contacts' VTU (binary, read back) holds at each sub-contact the
// pore pressure rho_w g H (1 - x / B) of the base.

#include <cmath>
#include <cstdio>

#include <talus/io/contact_vtu_writer.h>

#include "../io/vtu_reading.h"
#include "../tests.h"
#include "rigid_scene.h"

using namespace talus;

namespace
{
const double g = 9.81, deg = M_PI / 180.0, L = 2.0, B = 11.4, H = 10.0;
const double W = 2400.0 * g * L * 86.4;
const double thrust = 1000.0 * g * L * H * H / 2, uplift = 1000.0 * g * L * H * B / 2;

struct Dam
{
  RigidScene s;
  bool settled;
  Dam(double phi_degrees, bool water)
      : s("../tests/rigid/gravity_dam.prm",
          [&](Scene& scene)
          {
            scene.solver.joint.friction_angle = phi_degrees;
            if (!water)
              scene.solver.water = WaterSpec();
          })
  {
    const unsigned long steps = s.run_to_ratio(1e-7, 20000);
    settled = s.solver->unbalanced_ratio() < 1e-7;
    std::fprintf(stderr, "phi %.3f deg, water %d: %lu steps, ratio %.3g, dam moved %.3g m\n",
                 phi_degrees, int(water), steps, s.solver->unbalanced_ratio(),
                 s.solver->displacement[1].x());
  }
  double moved() const { return s.solver->displacement[1].x(); }
};
} // namespace

int main()
{
  const double tan_limit = thrust / (W - uplift);
  const double phi_limit = std::atan(tan_limit) / deg;
  std::printf("limit friction angle: %.2f deg\n", phi_limit);
  {
    Dam d(20.0, true);
    const double tan_phi = std::tan(20.0 * deg);
    const double exact = (W - uplift) * tan_phi / thrust;
    std::printf("closed form sliding factor at phi = 20 deg: %.4f\n", exact);
    const Vec3 water = d.s.solver->water_loads().total_force();
    std::printf(
        "dam weight from the model: %s\n",
        talus_test::verdict(talus_test::relative_error(d.s.solver->mass[1] * g, W) < 1e-12));
    talus_test::check_within("horizontal water force (thrust)", water.x(), thrust, 1e-3);
    talus_test::check_within("vertical water force (uplift)", water.z(), uplift, 1e-3);
    talus_test::check_within("sliding factor from the applied water forces",
                             (d.s.solver->mass[1] * g - water.z()) * tan_phi / water.x(), exact,
                             0.01);
    // The joint's own forces: every sub-contact is on the dam's base.
    const ContactSet& cs = d.s.solver->contacts();
    double normal = 0.0;
    Vec3 shear = Vec3::Zero();
    for (unsigned int i = 0; i < cs.n_subcontacts(); ++i)
    {
      normal += cs.sc_fn[i];
      shear += Vec3(cs.sc_fs[3 * i], cs.sc_fs[3 * i + 1], cs.sc_fs[3 * i + 2]);
    }
    talus_test::check_within("base normal force N = W - U", normal, W - uplift, 0.01);
    talus_test::check_within("sliding factor from the joint's forces, N tan(phi) / S",
                             normal * tan_phi / shear.norm(), exact, 0.01);
    std::printf("stands: %s\n", talus_test::verdict(d.settled && std::abs(d.moved()) < 1e-3));
    // The pore pressure in the contacts' file, against the closed form.
    write_contacts_vtu("dam_contacts.vtu", cs, d.s.model, JointNumbers{{}, {1}},
                       VtuEncoding::binary, &d.s.scene.solver.water, g);
    const std::vector<vtu_reading::Array> arrays =
        vtu_reading::read_arrays(vtu_reading::read_text("dam_contacts.vtu"));
    const vtu_reading::Array p = vtu_reading::find(arrays, "pore_pressure");
    double worst = p.values.size() == cs.n_subcontacts() ? 0.0 : 1e300;
    for (std::size_t i = 0; i < p.values.size() && i < cs.n_subcontacts(); ++i)
    {
      const double x = cs.sc_position[i].x();
      worst = std::max(worst, std::abs(p.values[i] - 1000.0 * g * H * (1 - x / B)));
    }
    std::fprintf(stderr, "pore_pressure: %zu values, largest error %.3g Pa\n", p.values.size(),
                 worst);
    std::printf("pore_pressure of the %u sub-contacts in the contacts' VTU, rho_w g H (1 - x / B), "
                "within 1e-4 of rho_w g H: %s\n",
                cs.n_subcontacts(), talus_test::verdict(worst < 1e-4 * 1000.0 * g * H));
  }
  const Dam above(phi_limit + 0.5, true), below(phi_limit - 0.5, true), dry(phi_limit - 0.5, false);
  std::printf("at phi_limit + 0.5 deg: %s (expected: stands)\n",
              above.settled && std::abs(above.moved()) < 1e-3 ? "stands" : "SLIDES");
  std::printf("at phi_limit - 0.5 deg: %s (expected: slides)\n",
              !below.settled && below.moved() > 1e-3 ? "slides" : "STANDS");
  std::printf("at phi_limit - 0.5 deg without water: %s (expected: stands)\n",
              dry.settled && std::abs(dry.moved()) < 1e-3 ? "stands" : "SLIDES");
}
