// Verification 2: toppling against sliding of a block on a 30 deg incline
// with 40 deg friction (parameters/verification/toppling.prm). It cannot
// slide; it topples when its width over height is below tan 30 = 0.577.
// Run for 0.6 s from rest: a slender block (b/h = 0.42 and 0.5) has turned
// far over, a stocky one (b/h = 0.7 and 1) only rocks by a hair.

#include <cmath>
#include <cstdio>

#include "rigid_scene.h"

int main()
{
  for (double width : {0.5, 0.6, 0.84, 1.2})
  {
    const double height = 1.2;
    RigidScene s("verification/toppling.prm", [&](talus::Scene& scene) {
      scene.excavations[1].region = talus::ConvexRegion::box(
          {talus::Vec3(width, 0, 1), talus::Vec3(3, 1, 1 + height)});
      // The step this test was written at: eq. 87 then took the fixed base's
      // 6 m^2 face. At the automatic step of the block's own face (about
      // 2.4 times larger) the stocky blocks, loaded at once and undamped,
      // rock by 0.2-0.5 deg, gaining about 2 % of the work of gravity as
      // their heels lift and land part way through steps.
      scene.solver.time_step_fraction = 0.1 / std::sqrt(6.0);
    });
    unsigned int block = 0;
    for (unsigned int b = 0; b < s.model.n_blocks(); ++b)
      if (s.model.group_names[s.model.group[b]] == "block")
        block = b;
    s.run_until(0.6);
    const double turned = std::abs(s.solver->rotation[block][1]) * 180.0 / M_PI;
    const bool topples = width / height < std::tan(30.0 * M_PI / 180.0);
    std::printf("b/h = %.2f: turned %s; expected: %s -> %s\n", width / height,
                turned > 5.0 ? "more than 5 deg" : (turned < 0.1 ? "less than 0.1 deg" : "a little"),
                topples ? "topples" : "stands",
                (turned > 5.0) == topples && (topples || turned < 0.1) ? "OK" : "WRONG");
  }
}
