// Mohr-Coulomb 10-node zones in a drained triaxial test: a 1 m cube of
// tet10 zones (c = 1 MPa, phi = psi = 30 degrees, E = 10 GPa, nu = 0.25),
// starting at the confining stress -p (p = 1 MPa) everywhere, with p on its
// faces x = 1 and y = 1, rollers on x = 0, y = 0, z = 0, and its top pushed
// down slowly past yield. The field stays uniform, so while the cube flows
// every Gauss point must sit at the closed-form strength
// sigma_1 = K_p p + 2 c sqrt(K_p) (compression), K_p = (1 + sin phi) /
// (1 - sin phi), with sigma_xx = sigma_yy = -p, and be flagged as yielding
// in shear: the model runs at every Gauss point. (With psi = 0 the
// non-associated flow lets the uniform state split into bands, for 4-node
// zones as well, so the check uses associated flow.)

#include <talus/base/parallel_environment.h>
#include <talus/solver/deformable_solver.h>
#include <talus/zone/block_mesher.h>
#include <talus/zone/stress_batch.h>
#include <talus/zone/tet10_mesh.h>

#include <cmath>
#include <cstdio>

#include "../tests.h"

using namespace talus;

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  BlockModel blocks;
  blocks.add_block(ConvexPolyhedron::box(Vec3::Zero(), Vec3(1, 1, 1)), 0);
  MeshReport report;
  TetMesh mesh = mesh_blocks(blocks, {0}, 0.5, report);
  make_quadratic(mesh);
  ZoneMaterial rock;
  rock.set_young_poisson(1e10, 0.25);
  rock.element = ZoneElement::tet10;
  rock.model = ZoneModel::mohr_coulomb;
  rock.friction_angle = 30.0;
  rock.dilation_angle = 30.0;
  rock.cohesion = 1e6;
  rock.tensile_strength = 0.0;
  const double p = 1e6;
  SolverSettings settings;
  settings.gravity = Vec3::Zero();
  const double eps = 1e-9;
  GridpointCondition x0, y0, z0, top;
  x0.region = Box{Vec3(-eps, -1, -1), Vec3(eps, 2, 2)};
  x0.held[1] = x0.held[2] = false;
  y0.region = Box{Vec3(-1, -eps, -1), Vec3(2, eps, 2)};
  y0.held[0] = y0.held[2] = false;
  z0.region = Box{Vec3(-1, -1, -eps), Vec3(2, 2, eps)};
  z0.held[0] = z0.held[1] = false;
  top.region = Box{Vec3(-1, -1, 1 - eps), Vec3(2, 2, 1 + eps)};
  top.held[0] = top.held[1] = false;
  top.velocity = Vec3(0, 0, -2e-7); // m per step (unit step of density scaling)
  FacePressure x1{Box{Vec3(1 - eps, -1, -1), Vec3(1 + eps, 2, 2)}, p, Vec3::Zero()};
  FacePressure y1{Box{Vec3(-1, 1 - eps, -1), Vec3(2, 1 + eps, 2)}, p, Vec3::Zero()};
  InitialStress initial;
  initial.base[0] = initial.base[1] = initial.base[2] = -p;
  DeformableSolver solver(mesh, {rock}, std::vector<unsigned int>(mesh.n_zones(), 0), settings,
                          {x0, y0, z0, top}, {x1, y1}, &initial);
  // 1.5e-3 of axial strain (yield is near 5e-4), slowly (a tenth of the
  // yield strain per 250 steps): the stress is read while the cube flows.
  for (int k = 0; k < 7500; ++k)
    solver.step();
  std::fprintf(stderr, "unbalanced ratio at the end %g\n", solver.unbalanced_ratio());
  std::printf("%u 10-node zones, %zu Gauss points, after 7500 steps of loading:\n", mesh.n_zones(),
              solver.stress().size() / 6);
  const double s = std::sin(rock.friction_angle * M_PI / 180.0), Kp = (1 + s) / (1 - s);
  const double strength = Kp * p + 2.0 * rock.cohesion * std::sqrt(Kp);
  const std::size_t points = solver.stress().size() / 6;
  double szz = 0.0, sxx = 0.0, spread = 0.0;
  unsigned int yielded = 0;
  for (std::size_t q = 0; q < points; ++q)
  {
    szz += solver.stress()[6 * q + 2] / points;
    sxx += solver.stress()[6 * q] / points;
    spread = std::max(spread, std::abs(solver.stress()[6 * q + 2] - solver.stress()[2]));
    yielded += (solver.plastic_state()[q] & shear_now) != 0;
  }
  talus_test::check_within("mean Gauss-point sigma_zz (Pa)", szz, -strength, 1e-3);
  talus_test::check_within("mean Gauss-point sigma_xx (Pa)", sxx, -p, 1e-3);
  std::fprintf(stderr, "largest difference of sigma_zz between Gauss points over the strength %g\n",
               spread / strength);
  std::printf("largest difference of sigma_zz between Gauss points over the strength: %s\n",
              spread / strength < 1e-2 ? "below 1e-2" : "TOO LARGE");
  std::printf("Gauss points at the shear yield surface in the last step: %u of %zu\n", yielded,
              points);
}
