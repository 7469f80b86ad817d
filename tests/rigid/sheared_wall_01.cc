// A brick wall sheared along a bedding joint (parameters/verification/
// sheared_wall.prm): two courses in running bond on a fixed foundation,
// every bed face sharing its front and back edges with the faces below and
// above it. The upper course, pushed along at its end, slides on the upper
// bedding joint, whose shear must then be the normal load (the course's
// weight W = rho g V) times tan(phi); the lower course must stay put, and
// no brick may rock: the only turn is the elastic pitch under the moment of
// the push (of the order of 1e-6 rad). Before the contact region was made
// robust to shared edges, bed contacts had up to 6 sub-contacts for their
// rectangles and the bricks rolled by 2.2e-8 rad.

#include <talus/joint/coulomb_slip.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "../tests.h"
#include "rigid_scene.h"

int main()
{
  RigidScene s("verification/sheared_wall.prm");
  const talus::BlockModel& m = s.model;
  const auto in = [&](unsigned int b, const char* name)
  { return m.group_names[m.group[b]] == name; };
  const double g = 9.81, rho = s.scene.density, weight = rho * g * 4.0 * 0.5 * 0.5;
  const double tan_phi = std::tan(s.scene.solver.joint.friction_angle * M_PI / 180.0);
  const double distance = 0.1, velocity = 0.01; // m, m/s
  const talus::ContactSet& c = s.solver->contacts();
  // The force the upper bedding joint applies to the upper course, and the
  // number of sub-contacts of its contacts (one per block pair), which must
  // stay four: the bed faces overlap in rectangles.
  std::vector<unsigned int> per_contact;
  unsigned int most = 0, slipping = 0, bed_subcontacts = 0;
  const auto bed_force = [&]()
  {
    talus::Vec3 force = talus::Vec3::Zero();
    per_contact.assign(c.n_slots(), 0);
    slipping = bed_subcontacts = 0;
    for (unsigned int i = 0; i < c.n_subcontacts(); ++i)
    {
      const unsigned int k = c.sc_contact[i];
      const unsigned int a = c.block_a[k], b = c.block_b[k];
      const bool a_lower = in(a, "lower"), b_lower = in(b, "lower");
      if (a_lower == b_lower || in(a, "foundation") || in(b, "foundation"))
        continue;
      const talus::Vec3 f = c.sc_fn[i] * c.plane[k].normal +
                            talus::Vec3(c.sc_fs[3 * i], c.sc_fs[3 * i + 1], c.sc_fs[3 * i + 2]);
      force += a_lower ? f : talus::Vec3(-f);
      most = std::max(most, ++per_contact[k]);
      ++bed_subcontacts;
      slipping += (c.sc_state[i] & talus::slipping) != 0;
    }
    return force;
  };
  // Along the run: the largest turns of a free brick, the largest motion of
  // a lower brick, the largest rise of an upper one; over its last fifth,
  // the mean force on the joint. The wall is symmetric about its middle
  // plane y = 0.25: a brick may pitch (turn about y) under the moment of the
  // push, never roll (about x) or yaw (about z).
  double pitch = 0.0, turn = 0.0, lower_motion = 0.0, rise = 0.0;
  talus::Vec3 force = talus::Vec3::Zero();
  unsigned long n_mean = 0;
  const double end = distance / velocity;
  while (s.solver->time() < end)
  {
    s.solver->step();
    for (unsigned int b = 0; b < m.n_blocks(); ++b)
    {
      if (in(b, "lower") || in(b, "upper"))
      {
        const talus::Vec3& r = s.solver->rotation[b];
        pitch = std::max(pitch, std::abs(r.y()));
        turn = std::max(turn, std::max(std::abs(r.x()), std::abs(r.z())));
      }
      if (in(b, "lower"))
        lower_motion = std::max(lower_motion, s.solver->displacement[b].norm());
      if (in(b, "upper") || in(b, "pusher"))
        rise = std::max(rise, s.solver->displacement[b].z());
    }
    const talus::Vec3 f = bed_force();
    if (s.solver->time() > 0.8 * end)
    {
      force += f;
      ++n_mean;
    }
  }
  force /= static_cast<double>(n_mean);
  double slide = 0.0, spread = 0.0;
  unsigned int n_upper = 0;
  for (unsigned int b = 0; b < m.n_blocks(); ++b)
    if (in(b, "upper"))
    {
      slide += s.solver->displacement[b].x();
      ++n_upper;
    }
  slide /= n_upper;
  for (unsigned int b = 0; b < m.n_blocks(); ++b)
    if (in(b, "upper"))
      spread = std::max(spread, std::abs(s.solver->displacement[b].x() - slide));
  std::fprintf(stderr,
               "steps %lu, upper course slid %.6g m (spread %.3g m), %u of %u bed "
               "sub-contacts slipping, at most %u per contact\n",
               s.solver->steps_done(), slide, spread, slipping, bed_subcontacts, most);
  std::fprintf(stderr,
               "largest pitch %.3g rad, roll and yaw %.3g rad, lower course moved %.3g m, upper "
               "rose %.3g m\n",
               pitch, turn, lower_motion, rise);
  std::printf("upper course pushed %.2f m along the upper bedding joint:\n", distance);
  talus_test::check_within("  normal load on the joint (N), W", force.z(), weight, 1e-4);
  talus_test::check_within("  shear force of the joint (N), W tan(phi)", -force.x(),
                           weight * tan_phi, 1e-4);
  std::printf("  every bed sub-contact slipping: %s\n",
              talus_test::verdict(slipping == bed_subcontacts && bed_subcontacts > 0));
  std::printf("  each bed contact always four sub-contacts (its rectangle's corners): %s\n",
              talus_test::verdict(most == 4 && bed_subcontacts == 32));
  std::printf("  the upper course slid together: %s\n",
              talus_test::verdict(std::abs(slide - distance) < 1e-3 && spread < 1e-4));
  std::printf("  lower course stays put (moved below 1e-5 m): %s\n",
              talus_test::verdict(lower_motion < 1e-5));
  std::printf("  no brick rocks (no roll or yaw above 1e-9 rad, pitch below 1e-5 rad, no rise "
              "above 1e-6 m): %s\n",
              talus_test::verdict(turn < 1e-9 && pitch < 1e-5 && rise < 1e-6));
}
