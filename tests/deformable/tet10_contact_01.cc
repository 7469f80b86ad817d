// Contact of 10-node zones: each boundary face of a zone is four flat
// triangles, and the contact code sees them as it sees the faces of 4-node
// zones.
// 1. A tet10 block slides down the rigid incline of
//    parameters/verification/deformable_on_incline.prm: after 0.5 s the
//    mean displacement of its gridpoints is g (sin a - cos a tan phi) t^2/2.
// 2. The column of five 1 m cubes of stack_of_blocks.prm made of tet10
//    blocks, settled: each joint (deformable on deformable, and on the rigid
//    floor) carries the weight above it, rho g (6 - z) per m^2.

#include <talus/base/parallel_environment.h>
#include <talus/scene/build_blocks.h>
#include <talus/scene/block_system.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "../tests.h"

using namespace talus;

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  {
    Scene scene = read_scene(std::string(SOURCE_DIR) +
                                 "/../../parameters/verification/deformable_on_incline.prm",
                             false);
    scene.deformable.material.element = ZoneElement::tet10;
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
    std::printf("1. tet10 block on the incline (%u zones, %u gridpoints, %u sub-contacts): ",
                system.mesh.n_zones(), n, solver.contacts().n_subcontacts());
    talus_test::check_within("slide after 0.5 s (m)", x, exact, 5e-3);
    std::fprintf(stderr, "largest vertical displacement of a gridpoint: %.3g m, dt %g s\n", lift,
                 solver.dt());
  }
  {
    Scene scene = read_scene(
        std::string(SOURCE_DIR) + "/../../parameters/verification/stack_of_blocks.prm", false);
    scene.deformable.groups = {"column"};
    scene.deformable.edge_length = 0.5;
    scene.deformable.material.set_young_poisson(1e10, 0.25);
    scene.deformable.material.density = scene.density;
    scene.deformable.material.element = ZoneElement::tet10;
    BuildReport built;
    BlockModel model = build_blocks(scene, built);
    resolve_group_names(scene, model);
    BlockSystem system = build_block_system(scene, model);
    RigidSolver& solver = *system.solver;
    unsigned long steps = 0;
    while ((steps < 20 || solver.unbalanced_ratio() >= 1e-7) && steps < 100000)
    {
      solver.step();
      ++steps;
    }
    std::fprintf(stderr, "stack: %lu steps\n", steps);
    std::printf("2. %u tet10 blocks, %u zones: static run %s\n", system.mesh_report.blocks,
                system.mesh.n_zones(),
                solver.unbalanced_ratio() < 1e-7 ? "reached ratio 1e-7" : "NOT converged");
    const ContactSet& c = solver.contacts();
    std::map<long, double> joint_force;
    for (unsigned int i = 0; i < c.n_subcontacts(); ++i)
      joint_force[std::lround(c.sc_position[i].z())] += c.sc_fn[i];
    const double rho_g = scene.density * 9.81;
    for (const auto& [z, fn] : joint_force)
    {
      std::printf("   ");
      talus_test::check_within("joint at z = " + std::to_string(z) + ": normal force (N)", fn,
                               rho_g * (6 - z), 1e-5);
    }
  }
}
