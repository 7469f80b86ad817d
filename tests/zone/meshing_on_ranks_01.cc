// Meshing shared among MPI ranks (mesh_convex_blocks_on_ranks): each block
// is meshed by one rank and sent to all, and every rank must then hold,
// for every block, the tetrahedra and points one rank makes alone, bit for
// bit. The model: a 6 x 4 x 4 m brick cut by two oblique joint sets
// (spacings 1.3 and 1.7 m), blocks of many shapes and sizes; meshed by the
// lattice mesher at a uniform 0.5 m and by gmsh with an edge length graded
// from 0.3 m at x = 0 to 0.8 m at x = 6. The ranks' shares (by the zones
// expected) and the largest share over the mean are printed; a block the
// mesher cannot mesh must stop every rank with the message one rank alone
// gives (the first such block's, in the blocks' order).

#include <talus/base/exceptions.h>
#include <talus/base/parallel_environment.h>
#include <talus/geometry/block_generator.h>
#include <talus/run/rank_share.h>
#include <talus/zone/block_mesher.h>
#include <talus/zone/meshing_on_ranks.h>

#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <numeric>
#include <string>

#include "../tests.h"

using namespace talus;

namespace
{

bool same(const BlockTetrahedra& a, const BlockTetrahedra& b)
{
  if (a.point.size() != b.point.size() || a.tet.size() != b.tet.size())
    return false;
  for (std::size_t i = 0; i < a.point.size(); ++i)
    if (std::memcmp(a.point[i].data(), b.point[i].data(), 3 * sizeof(double)) != 0)
      return false;
  return std::equal(a.tet.begin(), a.tet.end(), b.tet.begin());
}

} // namespace

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  const int rank = world_rank(), ranks = world_ranks();

  BlockGenerator generator(ConvexPolyhedron::box(Vec3::Zero(), Vec3(6.0, 4.0, 4.0)), {});
  JointSetSpec first, second;
  first.dip = 35.0;
  first.dip_direction = 120.0;
  first.spacing = 1.3;
  second.dip = 70.0;
  second.dip_direction = 250.0;
  second.spacing = 1.7;
  generator.cut_joint_set(first);
  generator.cut_joint_set(second);
  BlockModel model;
  for (const ConvexPolyhedron& b : generator.blocks())
    model.add_block(b, 0);
  std::vector<unsigned int> which(model.n_blocks());
  std::iota(which.begin(), which.end(), 0u);
  if (rank == 0)
    std::printf("%u blocks on %d ranks\n", model.n_blocks(), ranks);

  struct Case
  {
    const char* name;
    ConvexMesher mesher;
    EdgeLengthAt size;
  };
  const Case cases[] = {{"lattice, 0.5 m", ConvexMesher::lattice, [](const Vec3&) { return 0.5; }},
                        {"gmsh, 0.3-0.8 m", ConvexMesher::gmsh,
                         [](const Vec3& x) { return 0.3 + 0.5 * x.x() / 6.0; }}};
  for (const Case& c : cases)
  {
    const std::vector<BlockTetrahedra> alone =
        mesh_convex_blocks_with(model, which, c.size, c.mesher);
    std::vector<double> expected;
    for (unsigned int b : which)
      expected.push_back(regular_tetrahedra_in(model.volume[b], c.size(model.centroid[b])));
    const std::vector<BlockTetrahedra> shared =
        mesh_convex_blocks_on_ranks(model, which, c.size, c.mesher, expected, MPI_COMM_WORLD);
    int differing = 0;
    std::size_t zones = 0;
    for (std::size_t i = 0; i < which.size(); ++i)
    {
      differing += !same(alone[i], shared[i]);
      zones += alone[i].tet.size();
    }
    int all_differing = 0;
    MPI_Allreduce(&differing, &all_differing, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
    // Each rank's share of the zones made.
    const std::vector<int> rank_of = meshing_ranks(expected, ranks);
    std::vector<double> share(static_cast<std::size_t>(ranks), 0.0);
    for (std::size_t i = 0; i < which.size(); ++i)
      share[static_cast<std::size_t>(rank_of[i])] += static_cast<double>(alone[i].tet.size());
    const double most = *std::max_element(share.begin(), share.end());
    if (rank == 0)
    {
      // (The count of zones differs in the last blocks' bits between builds
      // with and without fused multiply-adds: standard error.)
      std::printf("%s: every block on every rank as one rank meshes it, bit for bit: %s\n", c.name,
                  talus_test::verdict(all_differing == 0));
      std::printf("  the largest rank's share of the zones over the mean below 1.1: %s\n",
                  talus_test::verdict(most / (static_cast<double>(zones) / ranks) < 1.1));
      std::fprintf(stderr, "%s: %zu zones, largest share over the mean %.4f, %d blocks differing\n",
                   c.name, zones, most / (static_cast<double>(zones) / ranks), all_differing);
    }
  }

  // A block that cannot be meshed, on whichever rank meshes it: the edge
  // length refused at the first point asked beyond x = 3 m (the message
  // names the point, so each block's differs).
  const EdgeLengthAt bad = [](const Vec3& x)
  {
    if (x.x() > 3.0)
      throw InputError("no edge length at (" + std::to_string(x.x()) + ", " +
                       std::to_string(x.y()) + ", " + std::to_string(x.z()) + ")");
    return 0.5;
  };
  std::string message;
  try
  {
    const std::vector<double> expected(which.size(), 1.0);
    mesh_convex_blocks_on_ranks(model, which, bad, ConvexMesher::lattice, expected, MPI_COMM_WORLD);
  }
  catch (const InputError& e)
  {
    message = e.what();
  }
  std::string alone_message;
  try
  {
    mesh_convex_blocks_with(model, which, bad, ConvexMesher::lattice);
  }
  catch (const InputError& e)
  {
    alone_message = e.what();
  }
  int differs = message != alone_message || message.empty(), any = 0;
  MPI_Allreduce(&differs, &any, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  if (rank == 0)
  {
    std::printf("a block that cannot be meshed: every rank stops with one rank's message: %s\n",
                talus_test::verdict(any == 0));
    std::fprintf(stderr, "message: %s\n", message.c_str());
  }
  return 0;
}
