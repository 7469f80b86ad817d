// Nodal mixed discretization chosen per block ('Nodal mixed groups'): the
// two nearly incompressible cantilevers of
// parameters/verification/two_cantilevers.prm, one with it and one
// without, in one run. The beams do not touch and local damping acts
// gridpoint by gridpoint, so after the same number of steps each beam must
// be exactly where it is in the same scene with nodal mixed discretization
// given to both beams, or to neither. Settled, the tip deflections are
// compared with beam theory with shear (Timoshenko): the mixed beam comes
// closer (as in nodal_mixed_01 at nu = 0.49: errors 0.42 plain, 0.38 mixed).

#include <talus/base/parallel_environment.h>
#include <talus/scene/build_blocks.h>
#include <talus/scene/block_system.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>

#include "../tests.h"

using namespace talus;

namespace
{
/// The scene with nodal mixed discretization in the beam of group "mixed"
/// (as shipped), in "both" beams or in "neither".
struct TwoCantilevers
{
  Scene scene;
  BlockModel model;
  BlockSystem system;

  // (The solvers keep references to the scene, the blocks and the mesh:
  // built in place, never moved.)
  explicit TwoCantilevers(const std::string& which)
      : scene(read(which)), model(blocks(scene)), system(build_block_system(scene, model))
  {
    const unsigned int mixed = system.zones->nodal_mixed_zones();
    std::printf("nodal mixed discretization in %s: %u of %u zones\n",
                which == "mixed"  ? "the 'mixed' beam"
                : which == "both" ? "both beams"
                                  : "neither beam",
                mixed, system.mesh.n_zones());
  }

  static Scene read(const std::string& which)
  {
    Scene scene = read_scene(
        std::string(SOURCE_DIR) + "/../../parameters/verification/two_cantilevers.prm", false);
    if (which == "both")
      scene.deformable.material.nodal_mixed = true;
    if (which == "neither")
      scene.deformable.nodal_mixed_groups.clear();
    return scene;
  }

  static BlockModel blocks(Scene& scene)
  {
    BuildReport built;
    BlockModel model = build_blocks(scene, built);
    resolve_group_names(scene, model);
    return model;
  }

  const std::string& group(unsigned int block) const
  {
    return model.group_names[model.group[block]];
  }

  void run(unsigned long steps)
  {
    for (unsigned long k = 0; k < steps; ++k)
      system.solver->step();
  }

  /// Mean downward displacement (m) of the free end of the beam of `name`.
  double tip(const std::string& name) const
  {
    const std::vector<double> u = system.zones->displacements();
    double sum = 0.0;
    unsigned int n = 0;
    for (unsigned int g = 0; g < system.mesh.n_gridpoints(); ++g)
      if (std::abs(system.mesh.position[3 * g] - 10.0) < 1e-9 &&
          group(system.mesh.gridpoint_block[g]) == name)
      {
        sum -= u[3 * g + 2];
        ++n;
      }
    return sum / n;
  }
};
} // namespace

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  // 5,000 steps: the tips are a tenth of the way to their rest, the beams
  // still ringing; any coupling of the beams or mix-up of their zones' formulations
  // shows.
  const unsigned long steps = 5000;
  TwoCantilevers per_block("mixed");
  per_block.run(steps);
  // Bit for bit: the trajectory's last digits follow the CPU's rounding, so
  // the values go to standard error.
  const auto same = [&](const std::string& beam, double reference, const std::string& run)
  {
    std::cerr << beam << " beam's tip after " << steps << " steps: " << per_block.tip(beam)
              << " m, with nodal mixed discretization in " << run << ": " << reference << " m\n";
    std::printf("after %lu steps the %s beam's tip is where it is with nodal mixed discretization "
                "in %s: %s\n",
                steps, beam.c_str(), run.c_str(),
                talus_test::verdict(per_block.tip(beam) == reference));
  };
  {
    TwoCantilevers both("both");
    both.run(steps);
    same("mixed", both.tip("mixed"), "both beams");
  }
  {
    TwoCantilevers neither("neither");
    neither.run(steps);
    same("plain", neither.tip("plain"), "neither beam");
  }

  RigidSolver& solver = *per_block.system.solver;
  unsigned long more = 0;
  while (solver.unbalanced_ratio() >= 1e-6 && more < 1000000)
  {
    solver.step();
    ++more;
  }
  std::cerr << steps + more << " steps to ratio 1e-6\n";
  std::printf("static run %s\n",
              solver.unbalanced_ratio() < 1e-6 ? "reached ratio 1e-6" : "NOT converged");

  // Beam theory with shear: q L^4 / (8 E I) + q L^2 / (2 k G A), k = 5/6.
  const double E = 1e10, nu = 0.49, G = E / (2.0 * (1.0 + nu)), L = 10.0, A = 1.0, I = 1.0 / 12.0,
               q = 2650.0 * 9.81 * A;
  const double exact = q * std::pow(L, 4) / (8.0 * E * I) + q * L * L / (2.0 * 5.0 / 6.0 * G * A);
  const double mixed = per_block.tip("mixed"), plain = per_block.tip("plain");
  talus_test::check_error("mixed beam's tip deflection", mixed, exact, 0.40);
  talus_test::check_error("plain beam's tip deflection", plain, exact, 0.45);
  std::printf("the mixed beam is closer to beam theory by more than 0.02: %s\n",
              talus_test::verdict(talus_test::relative_error(mixed, exact) <
                                  talus_test::relative_error(plain, exact) - 0.02));
}
