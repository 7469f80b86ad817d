// Factor of safety by strength reduction (Mode = factor of safety) of a
// block on an incline, against limit equilibrium.
//
// The incline is a horizontal joint under gravity tilted by the slope angle
// a (as parameters/verification/block_on_incline.prm): g = 9.81 (sin a, 0,
// -cos a). The slider, 1 m along the slope, 2 m across and 0.2 m thick, sits
// on a fixed base 11 m long; its upslope and downslope faces are parallel
// to gravity (cut by two excavations, planes of normal (cos a, 0, sin a)),
// so that its centroid lies on the line of gravity through the centre of
// its base. The normal stress on the base is then uniform: a box-shaped
// slider carries more at its downslope edge (the moment of the shear force
// about its centroid), and with cohesion, which a sub-contact loses when it
// fails (eq. 37), its least-loaded corner fails first and the block goes at
// a lower F (0.2 m box: F = 1.33 where limit equilibrium gives 1.40).
//
// W = rho V g, A = 2 m^2. With tan(phi)/F and c/F the block is at its limit
// when W sin a = (c A + W cos a tan phi) / F, so
//   F = (c A + W cos a tan phi) / (W sin a),
// and without cohesion F = tan(phi) / tan(a).
//   1. a = 30 deg, phi = 35 deg, c = 0:      F = tan 35 / tan 30 = 1.21280
//   2. a = 30 deg, phi = 25 deg, c = 0:      F = tan 25 / tan 30 = 0.80767 (bracket by halving)
//   3. a = 30 deg, phi = 20 deg, c = 2000 Pa: V = 0.4 m^3, W = 10398.6 N,
//      W sin a = 5199.3 N, W cos a tan phi = 9005.5 * 0.36397 = 3277.8 N,
//      c A = 4000 N: F = 7277.8 / 5199.3 = 1.39975.
//   4. a = 30 deg, phi = 35 deg, water of p = 1500 Pa in the joint ('Joint
//      pressures'): the effective normal force is W cos a - p A = 9005.5 -
//      3000 = 6005.5 N, and F = 6005.5 tan 35 / 5199.3 = 0.80878.
// Each within 0.5 % (the search stops at a bracket of 0.5 % of F; its
// middle is within 0.25 % of the limit).

#include <talus/scene/scene.h>
#include <talus/scene/build_blocks.h>
#include <talus/scene/factor_of_safety.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "../tests.h"
#include "slider_scene.h"

double factor_of_safety(double slope, double phi, double cohesion, double pressure = 0.0)
{
  const std::string file = "factor_of_safety_01_scene.prm";
  write_slider_scene(file, slope, "  set Mode = factor of safety\n  set Steps = 5000",
                     "subsection Joint properties\n"
                     "  set Normal stiffness = 1e11\n"
                     "  set Shear stiffness  = 1e11\n"
                     "  set Friction angle = " +
                         std::to_string(phi) + "\n  set Cohesion = " + std::to_string(cohesion) +
                         "\nend\nsubsection Water\n  set Joint pressures = " +
                         (pressure > 0.0 ? "1, " + std::to_string(pressure) : "") + "\nend\n");
  talus::Scene scene = talus::read_scene(file, false);
  talus::BuildReport report;
  talus::BlockModel model = talus::build_blocks(scene, report);
  talus::resolve_group_names(scene, model);
  const talus::StrengthReductionResult r =
      talus::factor_of_safety(scene, model, {},
                              [](const talus::StrengthReductionTrial& t)
                              { std::fprintf(stderr, "  %s\n", talus::trial_line(t).c_str()); });
  std::printf("slider: %u blocks, volume %.6g m^3; found: %s\n", model.n_blocks(), model.volume[1],
              r.found ? "yes" : "no");
  return r.factor();
}

/// What reduce_strengths does to every strength: tan(phi)/F, c/F, T/F on
/// each joint material, the dilation angle capped at the reduced friction
/// angle; Mohr-Coulomb zones only with 'Reduce zone strength'.
void check_reduction()
{
  const double deg = M_PI / 180.0, F = 2.0;
  talus::Scene s;
  s.solver.joint.friction_angle = 40;
  s.solver.joint.cohesion = 1e5;
  s.solver.joint.tensile_strength = 5e4;
  s.solver.joint.dilation_angle = 30;
  talus::JointProperties second;
  second.friction_angle = 20;
  second.cohesion = 3e3;
  s.solver.joint_materials = {second};
  s.deformable.material.model = talus::ZoneModel::mohr_coulomb;
  s.deformable.material.friction_angle = 35;
  s.deformable.material.cohesion = 2e6;
  s.deformable.material.tensile_strength = 1e6;
  s.rock_materials.resize(1);
  s.rock_materials[0].zone = s.deformable.material;
  talus::Scene joints_only = s;
  talus::reduce_strengths(joints_only, F);
  const talus::JointProperties& j = joints_only.solver.joint;
  const bool joints =
      std::abs(std::tan(j.friction_angle * deg) - std::tan(40 * deg) / F) < 1e-12 &&
      j.cohesion == 5e4 && j.tensile_strength == 2.5e4 && j.dilation_angle == j.friction_angle &&
      std::abs(std::tan(joints_only.solver.joint_materials[0].friction_angle * deg) -
               std::tan(20 * deg) / F) < 1e-12 &&
      joints_only.solver.joint_materials[0].cohesion == 1.5e3 &&
      joints_only.solver.joint_materials[0].dilation_angle == 0;
  const bool zones_kept = joints_only.deformable.material.cohesion == 2e6 &&
                          joints_only.rock_materials[0].zone.friction_angle == 35;
  s.strength_reduction.reduce_zone_strength = true;
  talus::reduce_strengths(s, F);
  const talus::ZoneMaterial& z = s.rock_materials[0].zone;
  const bool zones = std::abs(std::tan(z.friction_angle * deg) - std::tan(35 * deg) / F) < 1e-12 &&
                     z.cohesion == 1e6 && z.tensile_strength == 5e5 &&
                     s.deformable.material.cohesion == 1e6;
  std::printf("reduction by F = 2: joint materials %s, zones kept without 'Reduce zone strength' "
              "%s, reduced with it %s\n",
              talus_test::verdict(joints), talus_test::verdict(zones_kept),
              talus_test::verdict(zones));
}

int main()
{
  check_reduction();
  const double deg = M_PI / 180.0, g = 9.81, A = 2.0, W = 2650 * 0.4 * g;
  talus_test::check_within("F, a = 30, phi = 35", factor_of_safety(30, 35, 0),
                           std::tan(35 * deg) / std::tan(30 * deg), 0.005);
  talus_test::check_within("F, a = 30, phi = 25", factor_of_safety(30, 25, 0),
                           std::tan(25 * deg) / std::tan(30 * deg), 0.005);
  const double exact =
      (2000 * A + W * std::cos(30 * deg) * std::tan(20 * deg)) / (W * std::sin(30 * deg));
  talus_test::check_within("F, a = 30, phi = 20, c = 2000 Pa", factor_of_safety(30, 20, 2000),
                           exact, 0.005);
  const double wet = (W * std::cos(30 * deg) - 1500 * A) * std::tan(35 * deg) /
                     (W * std::sin(30 * deg));
  talus_test::check_within("F, a = 30, phi = 35, water of 1500 Pa in the joint",
                           factor_of_safety(30, 35, 0, 1500), wet, 0.005);
}
