// Rigid-block engine throughput: n x n x n unit cubes stacked in columns on
// a fixed floor layer, settling under gravity with local damping (static
// mode). For n = 5, 10, 20, 30 prints block-cycles per second, sub-contact
// updates per second, the share of time per stage and the bytes held per
// block, contact and sub-contact. One core; run from a Release build:
//   cmake --build build --target benchmark_rigid_settling
//   build/contrib/benchmarks/benchmark_rigid_settling [steps]

#include "benchmark_arguments.h"
#include "settling_cubes.h"

#include <talus/geometry/block_generator.h>
#include <talus/model/block_model.h>
#include <talus/solver/rigid_solver.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>

using namespace talus;

template <typename T>
std::size_t bytes(const std::vector<T>& v)
{
  return v.capacity() * sizeof(T);
}

int main(int argc, char** argv)
{
  const unsigned long steps =
      argc > 1 ? whole_argument(argv[0], argv[1], "the step count (first argument)", 1, 1000000)
               : 500;
  std::printf("%4s %7s %9s %11s %9s %14s %16s %8s %8s %8s %8s %10s %10s %10s\n", "n", "blocks",
              "contacts", "subcontacts", "seconds", "block-cycles/s", "subcontact-upd/s", "detect%",
              "planes%", "forces%", "motion%", "B/block", "B/contact", "B/subcont");
  double cost_10 = 0.0;
  for (unsigned int n : {5u, 10u, 20u, 30u})
  {
    SolverSettings s;
    BlockModel model = settling_cubes(n, steps, s);
    RigidSolver solver(model, 2650.0, s);
    const auto start = std::chrono::steady_clock::now();
    for (unsigned long k = 0; k < steps; ++k)
      solver.step();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const SolverReport r = solver.report();
    const double stages =
        r.seconds_detection + r.seconds_planes + r.seconds_forces + r.seconds_motion;
    const double block_cycles = double(model.n_blocks()) * steps / seconds;
    const double sub_updates = double(r.subcontacts) * steps / seconds;
    // Bytes per item of the arrays the cycle touches.
    const double per_block =
        double(bytes(model.vertex) + bytes(model.face_normal) + bytes(model.face_vertex) +
               bytes(model.face_loop_start) + bytes(model.vertex_start) + bytes(model.face_start) +
               bytes(model.volume) + bytes(model.centroid) + bytes(model.inertia) +
               bytes(model.group) + bytes(solver.mass) + bytes(solver.inertial_mass) +
               bytes(solver.inertia) + bytes(solver.velocity) + bytes(solver.spin) +
               bytes(solver.force) + bytes(solver.moment) + bytes(solver.displacement) +
               bytes(solver.rotation) + bytes(solver.fixed) + bytes(solver.moved) +
               bytes(solver.applied_force) + bytes(solver.applied_force_rate) +
               bytes(solver.prescribed)) /
        model.n_blocks();
    const ContactSet& c = solver.contacts();
    const double per_contact = double(bytes(c.block_a) + bytes(c.block_b) + bytes(c.plane) +
                                      bytes(c.gap) + bytes(c.type) + bytes(c.alive)) /
                               std::max(1u, c.n_contacts());
    const double per_sub =
        double(bytes(c.sc_contact) + bytes(c.sc_position) + bytes(c.sc_area) + bytes(c.sc_un) +
               bytes(c.sc_fn) + bytes(c.sc_fs) + bytes(c.sc_us) + bytes(c.sc_dilation) +
               bytes(c.sc_state) + bytes(c.sc_fresh)) /
        std::max(1u, c.n_subcontacts());
    if (n == 10)
      cost_10 = seconds / (double(model.n_blocks()) * steps);
    std::printf("%4u %7u %9u %11u %9.3f %14.0f %16.0f %8.1f %8.1f %8.1f %8.1f %10.0f %10.0f %10.0f",
                n, model.n_blocks(), c.n_contacts(), c.n_subcontacts(), seconds, block_cycles,
                sub_updates, 100 * r.seconds_detection / stages, 100 * r.seconds_planes / stages,
                100 * r.seconds_forces / stages, 100 * r.seconds_motion / stages, per_block,
                per_contact, per_sub);
    if (cost_10 > 0.0)
      std::printf("  time/block-cycle vs n=10: %.2f",
                  seconds / (double(model.n_blocks()) * steps) / cost_10);
    std::printf("\n");
  }
  std::printf("ratio of unbalanced force at the end is not the point here; steps per size: %lu\n",
              steps);
}
