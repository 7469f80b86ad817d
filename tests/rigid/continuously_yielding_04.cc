// Factor of safety with a continuously yielding joint. A trial at F
// divides tan(phi) and tan(phi_i) alike (so phi_i >= phi still holds and
// the bounding strength decays between the reduced angles); the rest of
// the material is kept. A block on a 30 degree incline on a continuously
// yielding joint with phi_i = phi = 35 degrees (no softening) then has the
// Coulomb answer F = tan(35) / tan(30): its bounding strength is
// sigma_n tan(phi), which the shear stress approaches but never passes.

#include <talus/scene/build_blocks.h>
#include <talus/scene/factor_of_safety.h>
#include <talus/scene/scene.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "../tests.h"
#include "slider_scene.h"

int main()
{
  const double deg = M_PI / 180.0, F = 2.0;
  {
    talus::Scene s;
    talus::JointProperties cy;
    cy.model = talus::JointModel::continuously_yielding;
    cy.friction_angle = 30;
    cy.initial_friction_angle = 45;
    cy.roughness = 1e-3;
    cy.normal_stiffness_factor = 1e8;
    cy.normal_stiffness_exponent = 0.5;
    cy.maximum_stiffness = 1e11;
    s.solver.joint_materials = {cy};
    talus::reduce_strengths(s, F);
    const talus::JointProperties& j = s.solver.joint_materials[0];
    const bool reduced =
        std::abs(std::tan(j.friction_angle * deg) - std::tan(30 * deg) / F) < 1e-12 &&
        std::abs(std::tan(j.initial_friction_angle * deg) - std::tan(45 * deg) / F) < 1e-12;
    const bool kept = j.model == talus::JointModel::continuously_yielding && j.roughness == 1e-3 &&
                      j.normal_stiffness_factor == 1e8 && j.maximum_stiffness == 1e11;
    std::printf("reduction by F = 2 of a continuously yielding material: tan(phi) and tan(phi_i) "
                "halved %s, the rest kept %s\n",
                talus_test::verdict(reduced), talus_test::verdict(kept));
  }

  const double a = 30 * deg;
  const std::string file = "continuously_yielding_04_scene.prm";
  write_slider_scene(file, 30, "  set Mode = factor of safety\n  set Steps = 5000",
                     R"(subsection Joint properties
  set Model = continuously yielding
  set Normal stiffness = 1e11
  set Shear stiffness  = 1e11
  set Friction angle = 35
  set Initial friction angle = 35
  set Roughness = 0.001
end
)");
  talus::Scene scene = talus::read_scene(file, false);
  talus::BuildReport report;
  talus::BlockModel model = talus::build_blocks(scene, report);
  talus::resolve_group_names(scene, model);
  const talus::StrengthReductionResult r =
      talus::factor_of_safety(scene, model, {},
                              [](const talus::StrengthReductionTrial& t)
                              { std::fprintf(stderr, "  %s\n", talus::trial_line(t).c_str()); });
  std::printf("found: %s\n", r.found ? "yes" : "no");
  talus_test::check_within("F, a = 30, phi = phi_i = 35", r.factor(),
                           std::tan(35 * deg) / std::tan(a), 0.005);
}
