// The shipped scene parameters/cavern_in_jointed_rock.prm, as talus builds
// and runs it (without output): a cavern in rock cut by three joint sets,
// deformable Mohr-Coulomb blocks near it, rigid beyond, in-situ stress.
// 1. The zone count lies within 0.5-2 of the count of regular tetrahedra
//    at the graded edge length (issue 21's band), and the mesh is sound.
// 2. The static run reaches the scene's target ratio within its steps
//    (before the contact areas were cut at the support's edge, a gridpoint
//    where a face met two blocks carried its area twice and rattled, and
//    the ratio stayed near 0.3).
// 3. The energy account closes to 2 % of its largest term.
// 4. The rock moves into the cavern: the roof down, the walls inwards.

#include <talus/base/parallel_environment.h>
#include <talus/io/scene_checks.h>
#include <talus/scene/build_blocks.h>
#include <talus/scene/block_system.h>
#include <talus/solver/deformable_solver.h>

#include <cmath>
#include <cstdio>

#include "../tests.h"

using namespace talus;

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  Scene scene = read_scene(
      std::string(SOURCE_DIR) + "/../../parameters/cavern_in_jointed_rock.prm", false);
  BuildReport built;
  BlockModel model = build_blocks(scene, built);
  resolve_group_names(scene, model);
  const ZoneEstimate estimate = estimate_zones(scene, model);
  BlockSystem system = build_block_system(scene, model);
  RigidSolver& solver = *system.solver;
  const DeformableSolver& zones = *system.zones;
  const double ratio = double(system.mesh.n_zones()) / estimate.zones;
  std::fprintf(stderr, "%u zones in %u blocks, %.3g of the estimate\n", system.mesh.n_zones(),
               system.mesh_report.blocks, ratio);
  std::printf("1. zone count within 0.5-2 of the regular count: %s; median radius ratio at "
              "least 0.6: %s\n",
              talus_test::verdict(ratio >= 0.5 && ratio <= 2.0),
              talus_test::verdict(system.mesh_report.quality_median >= 0.6));

  unsigned long steps = 0;
  while ((steps < 20 || solver.unbalanced_ratio() >= scene.solver.target_ratio) &&
         steps < scene.solver.steps)
  {
    solver.step();
    ++steps;
  }
  std::fprintf(stderr, "%lu steps, ratio %.3g\n", steps, solver.unbalanced_ratio());
  std::printf("2. static run %s\n", solver.unbalanced_ratio() < scene.solver.target_ratio
                                        ? "reached the target ratio within its steps"
                                        : "did NOT reach the target ratio");
  const EnergyAccount e = solver.energy_account();
  std::fprintf(stderr, "energy balance error %.3g of %.4g J\n", e.error() / e.scale(), e.scale());
  std::printf("3. energy balance error within 0.02 of the largest term: %s\n",
              talus_test::verdict(std::abs(e.error()) <= 0.02 * e.scale()));

  // Mean displacement of the gridpoints on the roof (z = 6), on each wall
  // (x = -8, 8), away from the held ends.
  const std::vector<double> u = zones.displacements();
  double roof = 0.0, west = 0.0, east = 0.0;
  unsigned int n_roof = 0, n_west = 0, n_east = 0;
  for (unsigned int g = 0; g < system.mesh.n_gridpoints(); ++g)
  {
    const double* x = &system.mesh.position[3 * g];
    if (std::abs(x[1]) > 8.0 || std::abs(x[0]) > 8.0 + 1e-9 || std::abs(x[2]) > 6.0 + 1e-9)
      continue;
    if (std::abs(x[2] - 6.0) < 1e-9)
      roof += u[3 * g + 2], ++n_roof;
    else if (std::abs(x[0] + 8.0) < 1e-9)
      west += u[3 * g], ++n_west;
    else if (std::abs(x[0] - 8.0) < 1e-9)
      east += u[3 * g], ++n_east;
  }
  roof /= n_roof, west /= n_west, east /= n_east;
  std::fprintf(stderr, "mean displacement: roof %.3g m down (%u gridpoints), west wall %.3g m, "
               "east wall %.3g m\n",
               -roof, n_roof, west, east);
  std::printf("4. roof moves down: %s; walls move inwards: %s\n", talus_test::verdict(roof < 0.0),
              talus_test::verdict(west > 0.0 && east < 0.0));
}
