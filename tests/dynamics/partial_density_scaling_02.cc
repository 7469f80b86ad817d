// Partial density scaling of rigid blocks (issue 23, eq. 89). A brick
// 3 m x 1 m x 2.02 m (rho = 2650 kg/m^3) cut into a fixed floor (z < 1)
// and, above it, three blocks side by side: cubes 1 and 2 (1 m x 1 m x
// 1.02 m) and cube 3 (1 m x 1 m x 1 m) with a sliver 1 m x 1 m x 0.02 m on
// it; bonded joints (kn = 1e10 Pa/m, ks = 4e9 Pa/m), gravity, dynamic. The
// sliver's eq. 87 step, frac 2 sqrt(m / (k A)) with its largest face A = 1
// m^2 and k = kn, is sqrt(0.02) of the cubes': it sets the automatic step.
// With partial density scaling at 5 times that step only the sliver gets
// mass, (5)^2 = 25 times its own. Judged:
// - the scaled run takes the step asked for;
// - the summary's figures against the hand calculation: one block scaled,
//   the mass added (24 m_sliver) over the free mass (3.06 m_cube), the
//   largest factor 25, and the sliver's rotational inertia scaled alike;
// - cube 1 (two joints away from the sliver) settles under its weight as
//   in the unscaled run: its largest settlement within 1 %. The scaled
//   step samples the oscillation (period 2 pi / sqrt(kn A / m), 45 steps)
//   near its peak to within 1 - cos(pi / 45) = 0.25 %, and the sliver's
//   extra inertia reaches cube 1 only through cube 2's vertical joints.
// And with Rayleigh beta = 2e-5 s, eq. 87 (lowered by the stiffness
// term) of the scaled model is the step asked for.
// Before: talus refused 'Partial density scaling' (an unknown entry), and
// refuses a 'Time step' above eq. 87 without it.

#include <talus/base/exceptions.h>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include "../stability/scene_text.h"
#include "../tests.h"

namespace
{
constexpr double rho = 2650.0, kn = 1e10, ks = 4e9, frac = 0.1;

std::string scene(double time_step, double beta = 0.0)
{
  std::ostringstream s;
  s.precision(17);
  s << "subsection Model\n  set Brick min = 0, 0, 0\n  set Brick max = 3, 1, 2.02\nend\n"
    << "subsection Material\n  set Density = " << rho << "\nend\n"
    << "subsection Joint 1\n  set Dip = 0\n  set Origin = 0, 0, 1\nend\n";
  // Vertical joints x = 1 and x = 2 through the upper layer; the plane z =
  // 2 through cube 3 alone.
  for (int x = 1; x <= 2; ++x)
    s << "subsection Joint " << x + 1 << "\n  set Dip = 90\n  set Dip direction = 90\n"
      << "  set Origin = " << x << ", 0, 0\n  set Limit to extent = true\n"
      << "  set Extent min = -1, -1, 1\n  set Extent max = 4, 2, 3\nend\n";
  s << "subsection Joint 4\n  set Dip = 0\n  set Origin = 0, 0, 2\n"
    << "  set Limit to extent = true\n  set Extent min = 2, -1, 1\n"
    << "  set Extent max = 4, 2, 3\nend\n"
    << "subsection Group 1\n  set Name = floor\n  set Corner min = -1, -1, -1\n"
    << "  set Corner max = 4, 2, 1\nend\n"
    << "subsection Joint properties\n  set Normal stiffness = " << kn
    << "\n  set Shear stiffness = " << ks
    << "\n  set Cohesion = 1e9\n  set Tensile strength = 1e9\n  set Friction angle = 30\nend\n"
    << "subsection Solver\n  set Mode = dynamic\n  set Fixed groups = floor\n"
    << "  set Time step fraction = " << frac << "\n  set Rayleigh beta = " << beta << "\n";
  if (time_step > 0.0)
    s << "  set Time step = " << time_step << "\n  set Partial density scaling = true\n"
      << "  set Added mass limit = 0.2\n";
  s << "end\n";
  return s.str();
}

unsigned int block_at(const talus::BlockModel& model, double x, double z)
{
  for (unsigned int b = 0; b < model.n_blocks(); ++b)
    if (std::abs(model.centroid[b][0] - x) < 1e-6 && std::abs(model.centroid[b][2] - z) < 1e-6)
      return b;
  std::fprintf(stderr, "no block with its centroid at x = %g, z = %g\n", x, z);
  std::exit(1);
}

/// The largest settlement of cube 1 (m) over 1.5 periods of its vertical
/// oscillation on the floor joint.
double settlement(TextScene& s)
{
  const unsigned int cube = block_at(s.model, 0.5, 1.51);
  const double omega = std::sqrt(kn * 1.0 / (rho * 1.02));
  double largest = 0.0;
  while (s.solver->time() < 1.5 * 2.0 * M_PI / omega)
  {
    s.solver->step();
    largest = std::max(largest, -s.solver->displacement[cube][2]);
  }
  return largest;
}
} // namespace

int main()
{
  TextScene plain("partial_density_scaling_02.prm", scene(0.0));
  const double auto_dt = plain.solver->dt();
  const double m_sliver = rho * 0.02, m_cube = rho;
  std::fprintf(stderr, "%u blocks; automatic step %.6g s (the sliver's eq. 87: %.6g s)\n",
               plain.model.n_blocks(), auto_dt, frac * 2.0 * std::sqrt(m_sliver / kn));
  const double asked = 5.0 * auto_dt;
  try
  {
    TextScene scaled("partial_density_scaling_02.prm", scene(asked));
    const unsigned int sliver = block_at(scaled.model, 2.5, 2.01);
    const talus::AddedMass a = scaled.solver->added_mass();
    // By hand: the sliver's mass for the step, k A (dt / frac)^2 / 4.
    const double needed = kn * 1.0 * (asked / frac) * (asked / frac) / 4.0;
    const double factor = needed / m_sliver;
    const double fraction = (needed - m_sliver) / (m_cube * (1.02 + 1.02 + 1.0) + m_sliver);
    std::fprintf(stderr,
                 "scaled: step %.6g s; %u blocks and %u gridpoints scaled, added %.6g of the "
                 "mass (by hand %.6g), largest factor %.6g (by hand %.6g)\n",
                 scaled.solver->dt(), a.blocks, a.gridpoints, a.fraction(), fraction,
                 a.largest_factor, factor);
    std::printf("the scaled run takes 5 times the automatic step: %s\n",
                talus_test::verdict(std::abs(scaled.solver->dt() / asked - 1.0) < 1e-12));
    std::printf("one block scaled, no gridpoint: %s\n",
                talus_test::verdict(a.blocks == 1 && a.gridpoints == 0));
    talus_test::check_within("largest factor (25)", a.largest_factor, factor, 1e-9);
    talus_test::check_within("mass added over the free mass", a.fraction(), fraction, 1e-9);
    talus_test::check_within("the sliver's scaled mass over its true mass",
                             scaled.solver->inertial_mass[sliver] / scaled.solver->mass[sliver],
                             factor, 1e-9);
    talus_test::check_within("the sliver's scaled inertia over its true inertia",
                             scaled.solver->inertia[sliver] /
                                 plain.solver->inertia[block_at(plain.model, 2.5, 2.01)],
                             factor, 1e-9);
    const double u_plain = settlement(plain), u_scaled = settlement(scaled);
    std::fprintf(stderr,
                 "cube 1 settles at most %.6g m unscaled, %.6g m scaled (2 m g / (kn A) "
                 "= %.6g m)\n",
                 u_plain, u_scaled, 2.0 * 9.81 * rho * 1.02 / kn);
    std::printf("cube 1's largest settlement within 1 %% of the unscaled run: %s\n",
                talus_test::verdict(std::abs(u_scaled / u_plain - 1.0) <= 0.01));
    // With Rayleigh's beta the sliver's mass for the step is k A (T^2 + 2 T
    // beta) / 4: its own eq. 87 step, lowered by the stiffness term, is
    // then the step asked for (it sets the model's, the cubes' being
    // longer).
    TextScene damped("partial_density_scaling_02.prm", scene(asked, 2e-5));
    talus_test::check_within("with Rayleigh beta 2e-5 s, eq. 87 after scaling over the step",
                             damped.solver->stable_time_step() / asked, 1.0, 1e-9);
  }
  catch (const talus::InputError& e)
  {
    std::printf("refused: %s\n", e.what());
  }
}
