// Verification 2 (uniaxial_01) with 10-node zones: uniaxial compression of
// an elastic cube (1 m, E = 10 GPa,
// nu = 0.25) by a pressure p = 10 kPa on its top face, the bottom face on
// rollers (held vertically; one corner held, a second held sideways against
// spinning). Closed form: vertical strain -p/E, lateral strain +nu p/E, every
// Gauss point at sigma_zz = -p and no other stress (the face load is the
// consistent one of a quadratic face: nothing at its vertices). The code follows the geometry
// (pressure on the current face area, stresses on the deformed zones), so
// it differs from the small-strain closed form by the order of the strain
// (1e-6 here); the tolerance is ten times that.

#include <talus/base/parallel_environment.h>
#include <talus/solver/deformable_solver.h>
#include <talus/zone/block_mesher.h>
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
  const double E = 1e10, nu = 0.25, p = 1e4;
  rock.set_young_poisson(E, nu);
  rock.element = ZoneElement::tet10;
  SolverSettings settings;
  settings.gravity = Vec3::Zero();
  const double eps = 1e-9;
  GridpointCondition bottom, corner, side;
  bottom.region = Box{Vec3(-1, -1, -eps), Vec3(2, 2, eps)};
  bottom.held[0] = bottom.held[1] = false;
  corner.region = Box{Vec3(-eps, -eps, -eps), Vec3(eps, eps, eps)};
  side.region = Box{Vec3(1 - eps, -eps, -eps), Vec3(1 + eps, eps, eps)};
  side.held[0] = side.held[2] = false;
  // The same load as a pressure and as a traction (force per unit area).
  for (const bool as_traction : {false, true})
  {
    FacePressure top{Box{Vec3(-1, -1, 1 - eps), Vec3(2, 2, 1 + eps)}, as_traction ? 0.0 : p,
                     as_traction ? Vec3(0, 0, -p) : Vec3::Zero()};
    std::printf("%s:\n", as_traction ? "traction (0, 0, -p)" : "pressure p");
    DeformableSolver solver(mesh, {rock}, std::vector<unsigned int>(mesh.n_zones(), 0), settings,
                            {bottom, corner, side}, {top});
    const unsigned long steps = solver.run_to_ratio(1e-10, 100000);
    std::fprintf(stderr, "%lu steps to ratio 1e-10\n", steps);
    std::printf("static run: %s\n",
                solver.unbalanced_ratio() < 1e-10 ? "reached ratio 1e-10" : "NOT converged");
    const std::vector<double> u = solver.displacements();
    double top_uz = 0.0, side_ux = 0.0;
    unsigned int n_top = 0, n_side = 0;
    for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
    {
      if (std::abs(mesh.position[3 * g + 2] - 1.0) < eps)
      {
        top_uz += u[3 * g + 2];
        ++n_top;
      }
      if (std::abs(mesh.position[3 * g] - 1.0) < eps)
      {
        side_ux += u[3 * g];
        ++n_side;
      }
    }
    // Lateral strain: mean u_x at x = 1 less mean u_x at x = 0.
    double x0_ux = 0.0;
    unsigned int n_x0 = 0;
    for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
      if (std::abs(mesh.position[3 * g]) < eps)
      {
        x0_ux += u[3 * g];
        ++n_x0;
      }
    talus_test::check("vertical strain", top_uz / n_top, -p / E, 1e-5);
    talus_test::check("lateral strain", side_ux / n_side - x0_ux / n_x0, nu * p / E, 1e-5);
    double szz = 0.0, others = 0.0;
    const std::size_t points = solver.stress().size() / 6;
    for (std::size_t z = 0; z < points; ++z)
    {
      szz += solver.stress()[6 * z + 2] / points;
      for (int c : {0, 1, 3, 4, 5})
        others = std::max(others, std::abs(solver.stress()[6 * z + c]));
    }
    talus_test::check("mean Gauss-point sigma_zz (Pa)", szz, -p, 1e-5);
    std::fprintf(stderr, "largest other stress component over p: %g\n", others / p);
    std::printf("largest other stress component over p: %s\n",
                others / p < 1e-5 ? "below 1e-5" : "TOO LARGE");
  }
}
