// Contacts of hexahedral zones: the deformable block of
// parameters/verification/deformable_on_incline.prm meshed with
// Element = hex-mixed (2 x 4 x 2 hexahedra, each two overlays of five
// tetrahedra) slides on the incline as the rigid block does,
// x = g (sin a - cos a tan phi) t^2 / 2 after 0.5 s, for the mean
// displacement of its gridpoints. The block's surface for the contacts is
// the first overlay's boundary triangles only (each quadrilateral once).
// Tolerance 5e-3 as for tetrahedral zones (tests/deformable/incline_01).

#include <talus/base/parallel_environment.h>
#include <talus/scene/build_blocks.h>
#include <talus/scene/block_system.h>

#include <cmath>
#include <cstdio>

#include "../tests.h"

using namespace talus;

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  Scene scene = read_scene(
      std::string(SOURCE_DIR) + "/../../parameters/verification/deformable_on_incline.prm", false);
  scene.deformable.material.element = ZoneElement::hex_mixed;
  BuildReport built;
  BlockModel model = build_blocks(scene, built);
  resolve_group_names(scene, model);
  BlockSystem system = build_block_system(scene, model);
  RigidSolver& solver = *system.solver;
  while (solver.time() + 0.5 * solver.dt() < 0.5)
    solver.step();
  const double g = 9.81, a = 40.0 * M_PI / 180.0, phi = 20.0 * M_PI / 180.0;
  const double exact =
      g * (std::sin(a) - std::cos(a) * std::tan(phi)) * solver.time() * solver.time() / 2;
  const std::vector<double> u = system.zones->displacements();
  const unsigned int n = system.mesh.n_gridpoints();
  double x = 0.0, lift = 0.0;
  for (unsigned int gp = 0; gp < n; ++gp)
  {
    x += u[3 * gp] / n;
    lift = std::max(lift, std::abs(u[3 * gp + 2]));
  }
  std::printf("deformable block (%u hexahedra, %u tetrahedra, %u boundary triangles, %u "
              "sub-contacts): ",
              system.mesh.n_hexes(), system.mesh.n_zones(), system.mesh.n_faces(),
              solver.contacts().n_subcontacts());
  talus_test::check_within("slide after 0.5 s (m)", x, exact, 5e-3);
  std::fprintf(stderr, "largest vertical displacement of a gridpoint: %.3g m\n", lift);
}
