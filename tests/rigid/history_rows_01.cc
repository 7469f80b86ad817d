// The history gets one row per 'History interval' steps and one at the end
// of the run, never two rows for the same step: a run whose step count is
// a multiple of the interval wrote its last row twice (issue 20, item 11).

#include "../tests.h"
#include "rigid_scene.h"

#include <cstdio>
#include <vector>

int main()
{
  for (const unsigned long steps : {20ul, 25ul})
  {
    RigidScene s("verification/block_on_incline.prm",
                 [&](talus::Scene& scene)
                 {
                   scene.solver.steps = steps;
                   scene.solver.history_interval = 10;
                   scene.solver.output_interval = 0;
                 });
    std::vector<unsigned long> rows;
    unsigned int outputs = 0;
    s.solver->run([&](unsigned long, double) { ++outputs; },
                  [&](unsigned long step, double) { rows.push_back(step); });
    std::printf("Steps %lu, history interval 10: rows at steps", steps);
    bool distinct = true;
    for (std::size_t k = 0; k < rows.size(); ++k)
    {
      std::printf(" %lu", rows[k]);
      distinct &= k == 0 || rows[k] > rows[k - 1];
    }
    std::printf("; each step once: %s; outputs %u\n", talus_test::verdict(distinct), outputs);
  }
}
