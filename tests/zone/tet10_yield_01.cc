// Mohr-Coulomb 10-node zones in a drained triaxial test: a 1 m cube of
// tet10 zones (c = 1 MPa, phi = 30 degrees, psi = 0, E = 10 GPa,
// nu = 0.25), starting at the confining stress -p (p = 1 MPa) everywhere,
// with p on its faces x = 1 and y = 1, rollers on x = 0, y = 0, z = 0, and
// its top pushed down at a constant rate past yield, then held and
// settled. The field stays uniform, so every Gauss point must reach the
// closed-form strength sigma_1 = K_p p + 2 c sqrt(K_p) (compression),
// K_p = (1 + sin phi) / (1 - sin phi), with sigma_xx = sigma_yy = -p, and be
// flagged as yielding in shear: the model runs at every Gauss point.

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
  rock.dilation_angle = 0.0;
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
  top.velocity = Vec3(0, 0, -1e-6); // m per step (unit step of density scaling)
  FacePressure x1{Box{Vec3(1 - eps, -1, -1), Vec3(1 + eps, 2, 2)}, p, Vec3::Zero()};
  FacePressure y1{Box{Vec3(-1, 1 - eps, -1), Vec3(2, 1 + eps, 2)}, p, Vec3::Zero()};
  InitialStress initial;
  initial.base[0] = initial.base[1] = initial.base[2] = -p;
  DeformableSolver solver(mesh, {rock}, std::vector<unsigned int>(mesh.n_zones(), 0), settings,
                          {x0, y0, z0, top}, {x1, y1}, &initial);
  // 1.5e-3 of axial strain (yield is near 5e-4), then the top held.
  for (int k = 0; k < 1500; ++k)
    solver.step();
  for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
    if (std::abs(mesh.position[3 * g + 2] - 1.0) < eps)
      solver.hold_gridpoint(g, Vec3::Zero());
  const unsigned long steps = solver.run_to_ratio(1e-8, 100000);
  std::fprintf(stderr, "%lu steps to settle\n", steps);
  std::printf("%u 10-node zones, %zu Gauss points: settled %s\n", mesh.n_zones(),
              solver.stress().size() / 6,
              solver.unbalanced_ratio() < 1e-8 ? "to ratio 1e-8" : "NOT");
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
    yielded += (solver.plastic_state()[q] & shear_past) != 0;
  }
  talus_test::check("mean Gauss-point sigma_zz (Pa)", szz, -strength, 1e-6);
  talus_test::check("mean Gauss-point sigma_xx (Pa)", sxx, -p, 1e-6);
  std::printf("largest difference of sigma_zz between Gauss points over the strength: %s\n",
              spread / strength < 1e-6 ? "below 1e-6" : "TOO LARGE");
  std::printf("Gauss points flagged as having yielded in shear: %u of %zu\n", yielded, points);
}
