// Water in a joint: a block on an incline under a water table
// (parameters/verification/block_on_incline.prm: a 1 x 2 x 1 m block of
// 2650 kg/m^3 on a fixed 10 x 2 x 1 m base, friction 20 deg, no cohesion),
// the model turned about y so that the slope dips a towards +x under
// vertical gravity. The phreatic surface is a plane parallel to the slope,
// 1.5 m above the joint (over the whole block), as for seepage parallel to
// a slope.
//
// Closed form. p = rho_w g (z_w - z): the base carries U = rho_w g h A (h
// its vertical depth), the top face rho_w g (h - t / cos a) A (t = 1 m the
// block's thickness), and the faces across and along the slope carry
// pressures that cancel in pairs (the surface is parallel to the slope).
// The net water force is normal to the slope, U' = rho_w g V / cos a (V the
// block's volume), pushing the block off the joint; the joint keeps
// N' = W cos a - U' and the block slides when
//   W sin a > (W cos a - rho_w g V / cos a) tan(phi),
// i.e. rho sin a = (rho cos a - rho_w / cos a) tan(phi): a = 12.52 deg
// for rho = 2650, rho_w = 1000, phi = 20 deg (dry: a = phi = 20 deg).
//
// Checks: the water force the code applies against U' (exact); static runs
// from rest at threshold - 0.2 deg (settles: stable) and + 0.2 deg (does
// not settle, creeps down the slope); and, for the before figure, the same
// +0.2 deg slope without water (stable).

#include <talus/model/water_table.h>

#include <cmath>
#include <cstdio>

#include "../tests.h"
#include "rigid_scene.h"

using namespace talus;

namespace
{
const double g = 9.81, deg = M_PI / 180.0, rho = 2650.0, rho_w = 1000.0, phi = 20.0 * deg;

/// Turns a vector about y by `a` (radians): +x goes down for a > 0.
Vec3 turn(const Vec3& v, double a)
{
  return Vec3(v.x() * std::cos(a) + v.z() * std::sin(a), v.y(),
              -v.x() * std::sin(a) + v.z() * std::cos(a));
}

/// The slope at which the block starts to slide (bisection of the closed form).
double threshold()
{
  const auto margin = [](double a)
  { return rho * std::sin(a) - (rho * std::cos(a) - rho_w / std::cos(a)) * std::tan(phi); };
  double lo = 1.0 * deg, hi = phi;
  for (int k = 0; k < 100; ++k)
    (margin(0.5 * (lo + hi)) > 0.0 ? hi : lo) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

struct Outcome
{
  bool settled;
  double slid; ///< m, down the slope
  Vec3 water;  ///< N, the water force on the block at the start
};

Outcome run(double a, bool water)
{
  RigidScene s(
      "verification/block_on_incline.prm",
      [&](Scene& scene)
      {
        scene.solver.gravity = Vec3(0, 0, -g);
        scene.solver.dynamic = false;
        scene.solver.local_damping = 0.8;
        if (water) // 1.5 m above the joint (z = 1 before the turn), parallel to it
          scene.solver.water.table =
              WaterTable::plane(turn(Vec3(0, 0, 2.5), a), turn(Vec3(0, 0, 1), a));
      },
      [&](BlockModel& m)
      {
        for (Vec3& x : m.vertex)
          x = turn(x, a);
        for (Vec3& n : m.face_normal)
          n = turn(n, a);
        for (Vec3& c : m.centroid)
          c = turn(c, a);
      });
  s.solver->step();
  Outcome o;
  o.water = s.solver->water_loads().empty() ? Vec3::Zero() : s.solver->water_loads().total_force();
  const unsigned long steps = s.run_to_ratio(1e-6, 20000);
  o.settled = s.solver->unbalanced_ratio() < 1e-6;
  o.slid = s.solver->displacement[1].dot(turn(Vec3(1, 0, 0), a));
  std::fprintf(stderr, "slope %.4f deg, water %d: %lu steps, ratio %.3g, slid %.3g m\n", a / deg,
               int(water), steps, s.solver->unbalanced_ratio(), o.slid);
  return o;
}
} // namespace

int main()
{
  const double a = threshold();
  std::printf("threshold slope: %.2f deg (dry: %.0f deg)\n", a / deg, phi / deg);
  // The water force, normal to the slope: rho_w g V / cos a with V = 2 m^3.
  const Outcome below = run(a - 0.2 * deg, true);
  const double a_below = a - 0.2 * deg;
  const Vec3 normal = turn(Vec3(0, 0, 1), a_below);
  const double exact = rho_w * g * 2.0 / std::cos(a_below);
  talus_test::print_value(stderr, "water force normal to the slope (N)", below.water.dot(normal),
                          exact, "\n");
  std::printf(
      "water force normal to the slope, rho_w g V / cos a: relative error below 1e-12: %s\n",
      talus_test::verdict(talus_test::relative_error(below.water.dot(normal), exact) < 1e-12));
  std::printf("water force along the slope: %s\n",
              talus_test::verdict(std::abs(below.water.cross(normal).norm()) < 1e-9 * exact));
  std::printf("at threshold - 0.2 deg: %s (expected: stable)\n",
              below.settled && std::abs(below.slid) < 1e-5 ? "stable" : "SLIDES");
  const Outcome above = run(a + 0.2 * deg, true);
  std::printf("at threshold + 0.2 deg: %s (expected: slides)\n",
              !above.settled && above.slid > 1e-4 ? "slides" : "STABLE");
  const Outcome dry = run(a + 0.2 * deg, false);
  std::printf("at threshold + 0.2 deg without water: %s (expected: stable)\n",
              dry.settled && std::abs(dry.slid) < 1e-5 ? "stable" : "SLIDES");
}
