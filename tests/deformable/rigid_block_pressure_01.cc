// Pressure and traction of 'Boundary N' on rigid blocks (issue 20, item 9;
// before, a rigid block took none of it). Dynamic, no gravity, one free
// block, no contacts:
//
// (1) A rigid dam block 10 m thick (x), 10 m wide (y), 28 m high, its
//     upstream face x = 0 under 14 bands of water pressure 2 m high, each
//     at the hydrostatic pressure of its middle, rho_w g (28 - z_i). The
//     resultant is rho_w g H^2 w / 2 = 38.4552 MN along +x, with the moment
//     of the bands about the centroid (z = 14 m); after t the block has
//     moved F t^2 / (2 m) and turned M t^2 / (2 I) about y (I the
//     isotropic inertia of the solver, (2/9) m r^2 with r the mean
//     distance of the vertices from the centroid; both exact for the
//     central-difference scheme under a constant load).
// (2) A 1 m cube under a shear traction (1 kPa along x) on its top face:
//     force tA and moment (0, tA/2, 0) about its centroid.
//
// Each band loads the part of the face inside its box (the face is one
// polygon); the load turns with the face. The work of the loads is the
// work of boundaries in the energy account, which must balance.

#include <talus/base/parallel_environment.h>
#include <talus/scene/build_blocks.h>
#include <talus/scene/block_system.h>

#include <cmath>
#include <cstdio>

#include "../tests.h"

using namespace talus;

namespace
{
Scene one_block(const Vec3& size, double density)
{
  Scene scene;
  scene.parameter_file = "rigid_block_pressure_01";
  scene.brick = Box{Vec3::Zero(), size};
  scene.density = density;
  scene.solver.dynamic = true;
  scene.solver.steps = 1000000;
  scene.solver.gravity = Vec3::Zero();
  return scene;
}

/// Runs the scene's one block for `duration` seconds; prints the checks.
void run(Scene& scene, double duration, const Vec3& force, const Vec3& moment)
{
  BuildReport built;
  BlockModel model = build_blocks(scene, built);
  resolve_group_names(scene, model);
  const double mass = scene.density * model.volume[0];
  double r = 0.0;
  for (unsigned int v = 0; v < model.n_vertices(); ++v)
    r += (model.vertex[v] - model.centroid[0]).norm() / model.n_vertices();
  const double inertia = 2.0 / 9.0 * mass * r * r;
  BlockSystem system = build_block_system(scene, model);
  RigidSolver& solver = *system.solver;
  while (solver.time() + 0.5 * solver.dt() < duration)
    solver.step();
  const double t = solver.time();
  std::fprintf(stderr, "  %lu steps of %.4g s\n", solver.steps_done(), solver.dt());
  talus_test::check_within("  displacement x (m)", solver.displacement[0][0],
                           0.5 * force[0] / mass * t * t, 1e-5);
  talus_test::check_within("  rotation about y (rad)", solver.rotation[0][1],
                           0.5 * moment[1] / inertia * t * t, 1e-4);
  const EnergyAccount e = solver.energy_account();
  std::fprintf(stderr, "  work of boundaries %.9g J, kinetic %.9g J, balance error %.3g J\n",
               e.boundary_work, e.kinetic, e.error());
  std::printf(
      "  work of boundaries positive and balanced (1e-6): %s\n",
      talus_test::verdict(e.boundary_work > 0.0 && std::abs(e.error()) <= 1e-6 * e.scale()));
}
} // namespace

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  {
    Scene scene = one_block(Vec3(10, 10, 28), 2400.0);
    const double rho_g = 1000.0 * 9.81, width = 10.0, band = 2.0;
    Vec3 force = Vec3::Zero(), moment = Vec3::Zero();
    for (int i = 0; i < 14; ++i)
    {
      const double z = band * (i + 0.5), p = rho_g * (28.0 - z);
      scene.face_pressures.push_back(
          FacePressure{Box{Vec3(-0.01, -1, band * i), Vec3(0.01, 11, band * (i + 1))}, p});
      scene.face_pressure_sections.push_back("Boundary " + std::to_string(i + 1));
      // The band pushes in (+x) at the middle of its part of the face.
      const Vec3 f(p * band * width, 0, 0);
      force += f;
      moment += (Vec3(0, 5, z) - Vec3(5, 5, 14)).cross(f);
    }
    std::printf("dam block, 14 bands of water pressure: resultant %.6g MN (rho_w g H^2 w / 2 = "
                "%.6g MN), moment about y %.6g MN m\n",
                force[0] / 1e6, rho_g * 28 * 28 * width / 2 / 1e6, moment[1] / 1e6);
    run(scene, 0.1, force, moment);
  }
  {
    Scene scene = one_block(Vec3(1, 1, 1), 2000.0);
    scene.face_pressures.push_back(
        FacePressure{Box{Vec3(-1, -1, 0.999), Vec3(2, 2, 1.001)}, 0.0, Vec3(1e3, 0, 0)});
    scene.face_pressure_sections.push_back("Boundary 1");
    std::printf("cube, traction 1 kPa along x on the top face: force 1000 N, moment 500 N m\n");
    run(scene, 0.1, Vec3(1e3, 0, 0), Vec3(0, 500, 0));
  }
}
