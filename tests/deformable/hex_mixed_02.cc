// Uniaxial compression of an elastic cube (1 m, E = 10 GPa, nu = 0.25) of
// 4 x 4 x 4 hexahedral zones of mixed discretization by a pressure
// p = 10 kPa on its top face, the bottom on rollers (one corner held, a
// second held sideways against spinning). Closed form: vertical strain
// -p/E, lateral strain +nu p/E, every zone at sigma_zz = -p and no other
// stress. The pressure is shared half and half by the two overlays' splits
// of each boundary quadrilateral (each corner a quarter), as the averaged
// overlays need: with one split only, the diagonal's ends would take twice
// the load of the other corners and the zones under the loaded face would
// not be uniform. The code follows the geometry, so it differs from the
// small-strain closed form by the order of the strain (1e-6); the tolerance
// is ten times that.
//
// Then the same cube, dynamic, with the automatic time step (eq. 84 with
// each overlay counting half in mass and stiffness) under the pressure
// applied suddenly: undamped, the top must oscillate between rest and
// twice the static shortening (at most, as the zones' own modes share the
// energy), never grow: a time step too long for the overlays' stiffness
// would blow up.

#include <talus/base/parallel_environment.h>
#include <talus/solver/deformable_solver.h>
#include <talus/zone/block_mesher.h>

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
  const TetMesh mesh = mesh_blocks(blocks, {0}, 0.25, report, ZoneElement::hex_mixed);
  ZoneMaterial rock;
  const double E = 1e10, nu = 0.25, p = 1e4;
  rock.set_young_poisson(E, nu);
  rock.element = ZoneElement::hex_mixed;
  const double eps = 1e-9;
  GridpointCondition bottom, corner, side;
  bottom.region = Box{Vec3(-1, -1, -eps), Vec3(2, 2, eps)};
  bottom.held[0] = bottom.held[1] = false;
  corner.region = Box{Vec3(-eps, -eps, -eps), Vec3(eps, eps, eps)};
  side.region = Box{Vec3(1 - eps, -eps, -eps), Vec3(1 + eps, eps, eps)};
  side.held[0] = side.held[2] = false;
  const FacePressure top{Box{Vec3(-1, -1, 1 - eps), Vec3(2, 2, 1 + eps)}, p, Vec3::Zero()};
  const auto mean_u = [&](const std::vector<double>& u, int d, int c, double value)
  {
    double sum = 0.0;
    unsigned int n = 0;
    for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
      if (std::abs(mesh.position[3 * g + c] - value) < eps)
      {
        sum += u[3 * g + d];
        ++n;
      }
    return sum / n;
  };
  double static_top = 0.0;
  {
    SolverSettings settings;
    settings.gravity = Vec3::Zero();
    DeformableSolver solver(mesh, {rock}, std::vector<unsigned int>(mesh.n_zones(), 0), settings,
                            {bottom, corner, side}, {top});
    solver.run_to_ratio(1e-10, 100000);
    std::printf("static run: %s\n",
                solver.unbalanced_ratio() < 1e-10 ? "reached ratio 1e-10" : "NOT converged");
    const std::vector<double> u = solver.displacements();
    static_top = mean_u(u, 2, 2, 1.0);
    talus_test::check("vertical strain", static_top, -p / E, 1e-5);
    talus_test::check("lateral strain", mean_u(u, 0, 0, 1.0) - mean_u(u, 0, 0, 0.0), nu * p / E,
                      1e-5);
    double szz = 0.0, szz_spread = 0.0, others = 0.0;
    for (unsigned int z = 0; z < mesh.n_zones(); ++z)
    {
      szz += solver.stress()[6 * z + 2] / mesh.n_zones();
      szz_spread = std::max(szz_spread, std::abs(solver.stress()[6 * z + 2] + p));
      for (int c : {0, 1, 3, 4, 5})
        others = std::max(others, std::abs(solver.stress()[6 * z + c]));
    }
    talus_test::check("mean sigma_zz (Pa)", szz, -p, 1e-5);
    std::fprintf(stderr, "largest |sigma_zz + p| / p %g, other stress components / p %g\n",
                 szz_spread / p, others / p);
    std::printf("every tetrahedron: |sigma_zz + p| and the other stress components %s\n",
                std::max(szz_spread, others) / p < 1e-5 ? "below 1e-5 of p" : "TOO LARGE");
  }
  {
    SolverSettings settings;
    settings.gravity = Vec3::Zero();
    settings.dynamic = true;
    DeformableSolver solver(mesh, {rock}, std::vector<unsigned int>(mesh.n_zones(), 0), settings,
                            {bottom, corner, side}, {top});
    // The first mode's period is about 4 H / c_p = 4 sqrt(rho / M) (M the
    // constrained modulus) = 0.0024 s; run ten of them.
    const unsigned int steps = static_cast<unsigned int>(0.024 / solver.dt());
    double lowest = 0.0, highest = 0.0;
    for (unsigned int k = 0; k < steps; ++k)
    {
      solver.step();
      const double top_uz = mean_u(solver.displacements(), 2, 2, 1.0);
      lowest = std::min(lowest, top_uz);
      highest = std::max(highest, top_uz);
    }
    std::fprintf(stderr, "dynamic: dt %g s, %u steps, top between %g and %g of the static\n",
                 solver.dt(), steps, highest / static_top, lowest / static_top);
    std::printf("dynamic, %u steps of the automatic time step: largest top shortening over the "
                "static: %.2f (%s)\n",
                steps, lowest / static_top,
                lowest / static_top > 1.5 && lowest / static_top < 2.2 ? "bounded, about 2"
                                                                       : "WRONG");
  }
}
