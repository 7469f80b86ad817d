// Block generation rate: a brick cut by three joint sets into about 10^3,
// 10^4 and 10^5 blocks. Prints blocks per second for each size and the ratio
// of the time per block at the largest size to that at the smallest (a linear
// cost keeps it near 1). Run: build/contrib/benchmarks/benchmark_block_generation

#include <talus/geometry/block_generator.h>
#include <talus/model/block_model.h>

#include <chrono>
#include <cmath>
#include <cstdio>

int main()
{
  using namespace talus;
  std::printf("%-10s %-10s %-12s %-14s %-14s\n", "n", "blocks", "seconds", "blocks/s",
              "model blocks/s");
  double first_cost = 0.0;
  for (unsigned int n : {10u, 22u, 47u})
  {
    const double size = n;
    const auto start = std::chrono::steady_clock::now();
    BlockGenerator generator(ConvexPolyhedron::box(Vec3::Zero(), Vec3::Constant(size)), {});
    // One sub-horizontal set and two steep sets crossing it: oblique cuts, the
    // usual case in rock, so blocks are general polyhedra, not cubes.
    generator.cut_joint_set({10.0, 30.0, 1.0, Vec3::Constant(0.5), 0, false, {}});
    generator.cut_joint_set({80.0, 120.0, 1.0, Vec3::Constant(0.5), 0, false, {}});
    generator.cut_joint_set({75.0, 220.0, 1.0, Vec3::Constant(0.5), 0, false, {}});
    const auto cut = std::chrono::steady_clock::now();
    BlockModel model;
    for (const ConvexPolyhedron& b : generator.blocks())
      model.add_block(b, 0);
    const auto done = std::chrono::steady_clock::now();
    const double t_cut = std::chrono::duration<double>(cut - start).count();
    const double t_all = std::chrono::duration<double>(done - start).count();
    const double blocks = model.n_blocks();
    if (first_cost == 0.0)
      first_cost = t_all / blocks;
    std::printf("%-10u %-10.0f %-12.4f %-14.0f %-14.0f  time/block vs first: %.2f\n", n, blocks,
                t_all, blocks / t_cut, blocks / t_all, (t_all / blocks) / first_cost);
  }
  return 0;
}
