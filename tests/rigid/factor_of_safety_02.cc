// Factor of safety by strength reduction of a tetrahedral wedge on two
// joints, against limit equilibrium (Hoek & Bray, Rock Slope Engineering:
// the wedge slides along the line of intersection of its two planes, the
// normal reactions R_A, R_B from resolving its weight on the planes).
//
// Geometry (x east, y north, z up; a brick 12 x 12 x 8 m, top at z = 8):
//   plane A ('Joint 1'): dip 50, dip direction 135, friction 35 deg
//     (joint material plane_a), through P = (0, 8, 8) on the top;
//   plane B ('Joint 2'): dip 60, dip direction 220, friction 45 deg
//     (joint material plane_b), through P too;
//   slope face (a half-space excavation): dip 70, dip direction 180,
//     through (0, 4, 8), the crest at y = 4.
// The wedge (group 'wedge', the region above both planes and behind the
// face) is the tetrahedron of the top, the face and the two planes; the
// rest of the rock is fixed.
//
// Upward unit normals (sin d sin a, sin d cos a, cos d):
//   n_A = (0.54168, -0.54168, 0.64279),  n_B = (-0.55667, -0.66341, 0.5).
// Line of intersection i = n_A x n_B / |n_A x n_B|, downward:
//   i = (0.16816, -0.67940, -0.71424): plunge psi_i = asin(0.71424) = 45.581
//   deg towards azimuth 166.1 (it daylights in the 70 deg face, whose
//   apparent dip along 166.1 is atan(tan 70 cos 13.9) = 69.3 deg).
// Weight W (vertical, down). Along i: W sin psi_i = 0.71424 W. Across i the
// reactions balance the rest of W: R_A n_A + R_B n_B = W (e_z - (e_z.i) i);
// dotted with n_A and n_B (both normal to i), with c = n_A.n_B = 0.37921:
//   R_A + c R_B = W n_Az = 0.64279 W,  c R_A + R_B = W n_Bz = 0.5 W,
//   R_A = W (n_Az - c n_Bz) / (1 - c^2) = 0.52929 W,
//   R_B = W (n_Bz - c n_Az) / (1 - c^2) = 0.29928 W.
// With tan(phi)/F on both planes the wedge is at its limit when
//   F = (R_A tan phi_A + R_B tan phi_B) / (W sin psi_i)
//     = (0.52929 * 0.70021 + 0.29928 * 1) / 0.71424 = 0.93792.
// Within 1 %; the mechanism (the last unstable trial's wedge displacement)
// along i within 1 deg.

#include <talus/scene/scene.h>
#include <talus/scene/build_blocks.h>
#include <talus/scene/factor_of_safety.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "../tests.h"

using talus::Vec3;

Vec3 upward_normal(double dip, double dip_direction)
{
  const double d = dip * M_PI / 180.0, a = dip_direction * M_PI / 180.0;
  return Vec3(std::sin(d) * std::sin(a), std::sin(d) * std::cos(a), std::cos(d));
}

int main()
{
  const double deg = M_PI / 180.0;
  const Vec3 nA = upward_normal(50, 135), nB = upward_normal(60, 220), nS = upward_normal(70, 180);
  const std::string file = "factor_of_safety_02_scene.prm";
  {
    std::ofstream prm(file);
    char text[3000];
    std::snprintf(text, sizeof text, R"(
subsection Model
  set Brick min = -6, 0, 0
  set Brick max = 6, 12, 8
end
subsection Material
  set Density = 2650
end
subsection Joint material 1
  set Name = plane_a
  set Friction angle = 35
end
subsection Joint material 2
  set Name = plane_b
  set Friction angle = 45
end
subsection Joint 1
  set Dip = 50
  set Dip direction = 135
  set Origin = 0, 8, 8
  set Material = plane_a
end
subsection Joint 2
  set Dip = 60
  set Dip direction = 220
  set Origin = 0, 8, 8
  set Material = plane_b
end
subsection Excavation 1
  set Shape = half-space
  set Point = 0, 4, 8
  set Normal = %.17g, %.17g, %.17g
end
subsection Group 1
  set Name = wedge
  set Shape = polyhedron
  set Planes = 0, 8, 8, %.17g, %.17g, %.17g; 0, 8, 8, %.17g, %.17g, %.17g; 0, 4, 8, %.17g, %.17g, %.17g
end
subsection Joint properties
  set Normal stiffness = 1e10
  set Shear stiffness  = 1e10
  set Friction angle = 30
end
subsection Solver
  set Mode = factor of safety
  set Steps = 5000
  set Fixed groups = rock
end
)",
                  nS[0], nS[1], nS[2], -nA[0], -nA[1], -nA[2], -nB[0], -nB[1], -nB[2], nS[0], nS[1],
                  nS[2]);
    prm << text;
  }
  talus::Scene scene = talus::read_scene(file, false);
  talus::BuildReport report;
  talus::BlockModel model = talus::build_blocks(scene, report);
  talus::resolve_group_names(scene, model);
  unsigned int wedge = 0, wedges = 0;
  for (unsigned int b = 0; b < model.n_blocks(); ++b)
    if (model.group_names[model.group[b]] == "wedge")
    {
      wedge = b;
      ++wedges;
    }
  std::printf("blocks: %u, wedges: %u\n", model.n_blocks(), wedges);

  // The mechanism: the wedge's displacement in the last unstable trial.
  Vec3 slide = Vec3::Zero();
  talus::TrialHooks hooks;
  hooks.finished = [&](const talus::TrialView& view, const talus::StrengthReductionTrial& t)
  {
    if (!t.stable)
      slide = view.system.solver->displacement[wedge] - view.start_displacement[wedge];
  };
  const talus::StrengthReductionResult r =
      talus::factor_of_safety(scene, model, hooks,
                              [](const talus::StrengthReductionTrial& t)
                              { std::fprintf(stderr, "  %s\n", talus::trial_line(t).c_str()); });
  std::printf("found: %s\n", r.found ? "yes" : "no");

  Vec3 i = nA.cross(nB).normalized();
  if (i[2] > 0)
    i = -i;
  const double c = nA.dot(nB);
  const double RA = (nA[2] - c * nB[2]) / (1 - c * c), RB = (nB[2] - c * nA[2]) / (1 - c * c);
  const double exact = (RA * std::tan(35 * deg) + RB * std::tan(45 * deg)) / -i[2];
  std::fprintf(stderr, "plunge %.5g deg, R_A %.5g W, R_B %.5g W\n", std::asin(-i[2]) / deg, RA, RB);
  talus_test::check_within("F of the wedge", r.factor(), exact, 0.01);
  const double angle = std::acos(std::min(1.0, slide.normalized().dot(i))) / deg;
  std::fprintf(stderr, "mechanism: slide %.3g m at %.3g deg from the line of intersection\n",
               slide.norm(), angle);
  std::printf("mechanism along the line of intersection (within 1 deg): %s\n",
              talus_test::verdict(slide.norm() > 0.0 && angle < 1.0));
}
