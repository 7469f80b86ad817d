// Factor of safety decided by the strength of Mohr-Coulomb zones
// ('Reduce zone strength'), tests/deformable/mc_column_fos.prm: a column
// of c = 100 kPa, phi = 30 deg under a uniaxial p = 200 kPa, no gravity.
// With c / F and tan(phi) / F its uniaxial strength 2 c_F cos phi_F /
// (1 - sin phi_F) falls to p at F = 1.46789 (bisected here); the search
// finds it within 0.5 % with 4-node zones (nodal mixed discretization),
// 10-node and hexahedral zones. Without 'Reduce zone strength' nothing can
// fail (the joint carries no shear), and the search says so.

#include <talus/base/parallel_environment.h>
#include <talus/scene/build_blocks.h>
#include <talus/scene/factor_of_safety.h>

#include <cmath>
#include <cstdio>
#include <tuple>

#include "../tests.h"

using namespace talus;

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  const double deg = M_PI / 180.0, c = 1e5, phi = 30 * deg, p = 2e5;
  const auto strength = [&](double F)
  {
    const double phi_F = std::atan(std::tan(phi) / F);
    return 2 * c / F * std::cos(phi_F) / (1 - std::sin(phi_F));
  };
  double lo = 0.5, hi = 5.0; // strength falls with F
  for (int i = 0; i < 100; ++i)
    (strength(0.5 * (lo + hi)) > p ? lo : hi) = 0.5 * (lo + hi);
  const double exact = 0.5 * (lo + hi);
  for (const auto& [element, nodal_mixed, name] :
       {std::tuple{ZoneElement::tet4, true, "nmd"}, std::tuple{ZoneElement::tet10, false, "tet10"},
        std::tuple{ZoneElement::hex_mixed, false, "hex-mixed"}})
  {
    for (const bool zones : {true, false})
    {
      if (!zones && element != ZoneElement::tet4)
        continue;
      Scene scene = read_scene(std::string(SOURCE_DIR) + "/mc_column_fos.prm", false);
      scene.deformable.material.element = element;
      scene.deformable.material.nodal_mixed = nodal_mixed;
      scene.strength_reduction.reduce_zone_strength = zones;
      BuildReport built;
      BlockModel model = build_blocks(scene, built);
      resolve_group_names(scene, model);
      const StrengthReductionResult r =
          factor_of_safety(scene, model, {},
                           [](const StrengthReductionTrial& t)
                           { std::fprintf(stderr, "  %s\n", trial_line(t).c_str()); });
      if (zones)
        talus_test::check_within(std::string(name) + ": F of the column", r.factor(), exact,
                                 0.005);
      else
        std::printf("%s: without 'Reduce zone strength' no F is found: %s\n", name,
                    talus_test::verdict(!r.found));
    }
  }
}
