// A column sliding down between two fixed neighbours whose side faces share
// its vertical edges (parameters/verification/sliding_column.prm): pressed
// against the right neighbour by F = 50 kN, it slides with
// a = g - (F / m) tan(phi) (a = g on frictionless joints), without drifting
// sideways, rolling or yawing (it pitches elastically under the moment of
// the friction). Both contact regions are the column's whole side face,
// bounded by edges that both blocks have: four sub-contacts of 0.5 m^2
// each. Before the contact region was made robust to shared edges, the
// frictional run had up to 9 sub-contacts of 0.2 to 0.6 m^2.

#include <cmath>
#include <cstdio>

#include "../tests.h"
#include "rigid_scene.h"

void slide(double phi_degrees)
{
  const double g = 9.81, t = 0.5, force = 50000.0;
  // The column starts pressed into the right neighbour by the closure that
  // carries F, F / (kn A), and as far off the left one: loaded at once from
  // zero closure, it would swing across the gap and back without damping,
  // touch the left neighbour with the corners it pitches by, and meet
  // friction there too.
  const double kn = 1e10, closure = force / (kn * 2.0 /* m^2 */);
  const auto column_of = [](const talus::BlockModel& model)
  {
    for (unsigned int b = 0; b < model.n_blocks(); ++b)
      if (model.group_names[model.group[b]] == "column")
        return b;
    return 0u;
  };
  RigidScene s(
      "verification/sliding_column.prm",
      [&](talus::Scene& scene)
      {
        scene.solver.joint.friction_angle = phi_degrees;
        scene.solver.joint.normal_stiffness = kn;
      },
      [&](talus::BlockModel& model)
      {
        const unsigned int b = column_of(model);
        for (unsigned int v = model.vertex_start[b]; v < model.vertex_start[b + 1]; ++v)
          model.vertex[v].x() += closure;
        model.centroid[b].x() += closure;
      });
  const unsigned int column = column_of(s.model);
  const double m = s.solver->mass[column];
  const talus::ContactSet& c = s.solver->contacts();
  // By symmetry the column may pitch (turn about y) under the moment of the
  // friction on its face, half its width from its axis, never roll (about
  // x) or yaw (about z).
  unsigned int fewest = 1000, most = 0;
  double smallest = 1e300, largest = 0.0, drift = 0.0, off = 0.0, pitch = 0.0, turn = 0.0;
  // The acceleration from the drop at three times equally spaced after the
  // start, (z1 - 2 z2 + z3) / dt^2: from rest the column falls freely until
  // the shear springs have taken up the friction (about 0.4 ms), which puts
  // it a constant velocity ahead of a t^2 / 2 (6e-4 of the drop).
  const unsigned long n1 = std::lround(0.1 * t / s.solver->dt()),
                      n_step = std::lround(0.45 * t / s.solver->dt());
  double z[3] = {0.0, 0.0, 0.0};
  while (s.solver->steps_done() < n1 + 2 * n_step)
  {
    s.solver->step();
    const talus::Vec3& u = s.solver->displacement[column];
    for (int k = 0; k < 3; ++k)
      if (s.solver->steps_done() == n1 + k * n_step)
        z[k] = u.z();
    drift = std::max(drift, std::abs(u.y()));
    off = std::max(off, std::abs(u.x()));
    const talus::Vec3& r = s.solver->rotation[column];
    pitch = std::max(pitch, std::abs(r.y()));
    turn = std::max(turn, std::max(std::abs(r.x()), std::abs(r.z())));
    if (s.solver->steps_done() % 97 != 0)
      continue;
    fewest = std::min(fewest, c.n_subcontacts());
    most = std::max(most, c.n_subcontacts());
    for (unsigned int i = 0; i < c.n_subcontacts(); ++i)
    {
      smallest = std::min(smallest, c.sc_area[i]);
      largest = std::max(largest, c.sc_area[i]);
    }
  }
  const talus::Vec3 u = s.solver->displacement[column];
  const double tan_phi = std::tan(phi_degrees * M_PI / 180.0);
  const double a_exact = g - force / m * tan_phi;
  const double a = -(z[0] - 2.0 * z[1] + z[2]) / std::pow(n_step * s.solver->dt(), 2);
  std::printf("friction angle %.0f deg, %.1f s:\n", phi_degrees, s.solver->time());
  std::fprintf(stderr,
               "  steps %lu, mass %.6g kg, drop %.9g m, drift %.3g m, off the joint %.3g m, "
               "pitch %.3g rad, roll and yaw %.3g rad\n",
               s.solver->steps_done(), m, -u.z(), drift, off, pitch, turn);
  std::fprintf(stderr, "  sub-contacts %u to %u, areas %.6g to %.6g m^2\n", fewest, most, smallest,
               largest);
  talus_test::check_within("  acceleration (m/s^2)", a, a_exact, 1e-5);
  std::printf("  sideways drift and motion across the joints below 1e-6 m: %s\n",
              talus_test::verdict(drift < 1e-6 && off < 1e-6));
  std::printf("  no roll or yaw (below 1e-9 rad), pitch below 1e-5 rad: %s\n",
              talus_test::verdict(turn < 1e-9 && pitch < 1e-5));
  std::printf("  always 8 sub-contacts of 0.5 m^2: %s\n",
              talus_test::verdict(fewest == 8 && most == 8 && std::abs(smallest - 0.5) < 1e-9 &&
                                  std::abs(largest - 0.5) < 1e-9));
}

int main()
{
  slide(0.0);
  slide(20.0);
}
