// Verification 6: a key block released in the roof of an opening, held by
// frictionless vertical joints only, falls as z = g t^2 / 2
// (parameters/verification/key_block_fall.prm).

#include <cmath>
#include <cstdio>

#include "rigid_scene.h"

int main()
{
  RigidScene s("verification/key_block_fall.prm");
  unsigned int key = 0;
  for (unsigned int b = 0; b < s.model.n_blocks(); ++b)
    if (s.model.group_names[s.model.group[b]] == "key")
      key = b;
  std::printf("blocks: %u, contacts of the key block at the start: ", s.model.n_blocks());
  unsigned int n = 0;
  for (unsigned int c = 0; c < s.solver->contacts().n_slots(); ++c)
    n += s.solver->contacts().alive[c] &&
         (s.solver->contacts().block_a[c] == key || s.solver->contacts().block_b[c] == key);
  std::printf("%u\n", n);
  for (double t : {0.05, 0.1, 0.2})
  {
    s.run_until(t);
    const double drop = -s.solver->displacement[key][2];
    const double exact = 9.81 * s.solver->time() * s.solver->time() / 2;
    std::printf("t = %.2f s: drop %.6g m, g t^2/2 = %.6g m, relative error %.1e %s; sideways %.1e m\n",
                t, drop, exact, std::abs(drop - exact) / exact,
                std::abs(drop - exact) / exact < 1e-4 ? "(< 1e-4)" : "(TOO LARGE)",
                std::hypot(s.solver->displacement[key][0], s.solver->displacement[key][1]));
  }
}
