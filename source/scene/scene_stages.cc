#include <talus/scene/scene.h>

namespace talus
{

std::vector<StageSpec> stages_to_run(const Scene& scene)
{
  if (!scene.stages.empty())
    return scene.stages;
  StageSpec one;
  one.section = "Solver";
  one.name = "run";
  one.dynamic = scene.solver.dynamic;
  one.steps = scene.solver.steps;
  one.target_ratio = scene.solver.target_ratio;
  return {one};
}

unsigned long steps_to_run(const Scene& scene)
{
  if (scene.stages.empty())
    return scene.solver.steps;
  unsigned long steps = 0;
  for (const StageSpec& stage : scene.stages)
    steps += stage.steps;
  return steps;
}

} // namespace talus
