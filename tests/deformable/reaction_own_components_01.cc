// 'Report reaction' counts a boundary's own held components only (issue
// 20, item 8). The smooth footing of parameters/verification/strip_footing.prm
// (Boundary 2, held in z only), made elastic and pushed 2 mm, then settled:
// symmetry and plane-strain rollers (Boundaries 3, 5, 6) hold x and y at
// gridpoints inside the footing's box, and their forces are not the
// footing's. Its reaction must be zero in x and y, and its z reaction
// must balance the base's (no gravity): F_z(footing) + F_z(base) = 0.
// Before the fix the footing reported the rollers' x and y forces as its
// own.

#include <cmath>
#include <cstdio>

#include "../tests.h"
#include "deformable_scene.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  DeformableScene s("verification/strip_footing.prm",
                    [](talus::Scene& scene)
                    {
                      scene.deformable.material.model = talus::ZoneModel::elastic;
                      scene.gridpoint_conditions[1].velocity_until = 400; // 2 mm
                    });
  while (s.solver->time() < 400)
    s.solver->step();
  const unsigned long settling = s.solver->run_to_ratio(1e-7, 200000);
  const talus::ReactionReport& footing = s.scene.reactions[0];
  const talus::GridpointCondition& base = s.scene.gridpoint_conditions[0];
  const talus::Vec3 f = -s.solver->support_force(footing.region, footing.held);
  const talus::Vec3 f_base = -s.solver->support_force(base.region, base.held);
  std::fprintf(stderr,
               "%lu steps (%lu settling); %s reaction on the body %.9g, %.9g, %.9g N; base "
               "%.9g, %.9g, %.9g N\n",
               s.solver->steps_done(), settling, footing.name.c_str(), f[0], f[1], f[2], f_base[0],
               f_base[1], f_base[2]);
  std::printf("%s, held in z: %s\n", footing.name.c_str(),
              s.solver->unbalanced_ratio() < 1e-7 ? "settled to ratio 1e-7" : "NOT settled");
  std::printf("  reaction x and y (N), the rollers' forces left out: %s\n",
              talus_test::verdict(f[0] == 0.0 && f[1] == 0.0));
  std::printf("  reaction z pushes down on the body: %s\n", talus_test::verdict(f[2] < 0.0));
  // Both follow the rounding of a run stopped at a ratio: the verdict only.
  std::printf("  reaction z against minus the base's (1e-4): %s\n",
              talus_test::verdict(talus_test::relative_error(f[2], -f_base[2]) <= 1e-4));
}
