// Graded meshing of a jointed model: a brick of 48 x 12 x 48 m cut by three
// oblique joint sets at 5-6 m spacing (as contrib/benchmarks/
// block_generation.cc), every block meshed by mesh_blocks (gmsh's Delaunay
// mesher, convex_block_mesher.h) with an EdgeLengthField of 2 m away from a
// box of 8 x 6 x 8 m at the centre (a cavern), 0.5 m at the box, growing
// linearly over 10 m. Checks:
// 1. EdgeLengthField::at against its closed form: fine inside the region,
//    coarse beyond `distance`, fine + (coarse - fine) d / distance between;
// 2. the zones follow the field: the median over zones of a zone's mean edge
//    length over the target at its centroid within 0.6-1.5, both near the
//    box (within 2 m) and far from it (beyond 12 m), and the median edge
//    near below 0.4 of the median edge far (the targets' ratio is about
//    0.28; gmsh's Delaunay volume mesher makes interior edges about 1.3 of
//    the target, at any scale, where surface-bound blocks of 2-3 edges
//    across get about 1.0, so the meshes' ratio is about 0.37);
// 3. the zone count within 0.5-2x of count_zones (the estimate the summary
//    prints before meshing and the memory check uses), and below a tenth of
//    what a uniform mesh at the fine length would make (count_zones, not
//    meshed);
// 4. the zone volumes sum to each block's volume within 1e-12 and every zone
//    has a positive volume; the median radius ratio at least 0.6.

#include <talus/base/parallel_environment.h>
#include <talus/geometry/block_generator.h>
#include <talus/zone/block_mesher.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "../tests.h"
#include "convex_block_mesher_checks.h"

using namespace talus;
using talus_test::verdict;

namespace
{
Vec3 position(const TetMesh& mesh, unsigned int g)
{
  return Vec3(mesh.position[3 * g], mesh.position[3 * g + 1], mesh.position[3 * g + 2]);
}

/// Distance from x to a box region as EdgeLengthField measures it: the
/// largest signed distance to its planes, 0 inside.
double distance_to(const ConvexRegion& r, const Vec3& x)
{
  double d = 0.0;
  for (const Plane& p : r.planes)
    d = std::max(d, p.signed_distance(x));
  return d;
}
} // namespace

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  const auto start = std::chrono::steady_clock::now();

  BlockGenerator generator(ConvexPolyhedron::box(Vec3::Zero(), Vec3(48, 12, 48)), {});
  generator.cut_joint_set({15.0, 30.0, 5.5, Vec3(0.3, 0.2, 0.7), 0, false, {}});
  generator.cut_joint_set({75.0, 120.0, 6.0, Vec3(0.4, 0.1, 0.2), 0, false, {}});
  generator.cut_joint_set({70.0, 230.0, 5.0, Vec3(0.6, 0.3, 0.5), 0, false, {}});
  BlockModel blocks;
  for (const ConvexPolyhedron& b : generator.blocks())
    blocks.add_block(b, 0);
  std::vector<unsigned int> which(blocks.n_blocks());
  for (unsigned int b = 0; b < blocks.n_blocks(); ++b)
    which[b] = b;

  const Vec3 centre(24, 6, 24);
  EdgeLengthField field;
  field.coarse = 2.0;
  field.fine = 0.5;
  field.distance = 10.0;
  field.near.push_back(ConvexRegion::box(Box{centre - Vec3(4, 3, 4), centre + Vec3(4, 3, 4)}));
  const ConvexRegion& cavern = field.near[0];

  // 1. The field's closed form at three points: inside the box, 4 m off its
  // +x face (1.1 m), 15 m off it (coarse).
  {
    const double inside = field.at(centre + Vec3(1.0, -0.5, 2.0));
    const double between = field.at(centre + Vec3(4.0 + 4.0, 0.5, -1.0));
    const double beyond = field.at(centre + Vec3(4.0 + 15.0, 0.0, 0.0));
    std::printf("1. edge length field: fine inside the region, %s; 4 m off it, fine + (coarse - "
                "fine) 4/10: %s; 15 m off it, coarse: %s\n",
                verdict(std::abs(inside - 0.5) <= 1e-15),
                verdict(std::abs(between - (0.5 + 1.5 * 0.4)) <= 1e-14),
                verdict(std::abs(beyond - 2.0) <= 1e-15));
    std::fprintf(stderr, "1. at: %.17g %.17g %.17g\n", inside, between, beyond);
  }

  MeshReport report;
  const TetMesh mesh = mesh_blocks(blocks, which, field, report);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // 2. Zone sizes against the field, near the box and far from it.
  std::vector<double> ratio_near, ratio_far, edge_near, edge_far, quality;
  std::vector<double> filled(blocks.n_blocks(), 0.0);
  unsigned int non_positive = 0;
  for (unsigned int z = 0; z < mesh.n_zones(); ++z)
  {
    const auto& t = mesh.zone_gridpoint[z];
    const Vec3 p[4] = {position(mesh, t[0]), position(mesh, t[1]), position(mesh, t[2]),
                       position(mesh, t[3])};
    double edge = 0.0;
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b)
        edge += (p[b] - p[a]).norm() / 6.0;
    const Vec3 c = 0.25 * (p[0] + p[1] + p[2] + p[3]);
    const double d = distance_to(cavern, c);
    if (d < 2.0)
    {
      ratio_near.push_back(edge / field.at(c));
      edge_near.push_back(edge);
    }
    else if (d > 12.0)
    {
      ratio_far.push_back(edge / field.at(c));
      edge_far.push_back(edge);
    }
    const double v = talus_test::signed_volume(p[0], p[1], p[2], p[3]);
    if (!(v > 0.0))
      ++non_positive;
    filled[mesh.zone_block[z]] += v;
    quality.push_back(radius_ratio(p[0], p[1], p[2], p[3]));
  }
  for (auto* v : {&ratio_near, &ratio_far, &edge_near, &edge_far, &quality})
    std::sort(v->begin(), v->end());
  const double near = talus_test::median(ratio_near), far = talus_test::median(ratio_far);
  const double edge_ratio = talus_test::median(edge_near) / talus_test::median(edge_far);
  std::printf("2. mean zone edge over the target at the zone's centroid, median near the region "
              "(< 2 m) within 0.6-1.5: %s; far from it (> 12 m): %s\n",
              verdict(!ratio_near.empty() && near >= 0.6 && near <= 1.5),
              verdict(!ratio_far.empty() && far >= 0.6 && far <= 1.5));
  std::printf("   median edge near below 0.4 of the median edge far: %s\n",
              verdict(edge_ratio < 0.4));

  // 3. Counts.
  const double estimate = count_zones(blocks, which, field);
  const double uniform = count_zones(blocks, which, EdgeLengthField(0.5));
  const double counted = mesh.n_zones() / estimate;
  std::printf("3. zones within 0.5-2x of count_zones: %s (ratio %.1f)\n",
              verdict(counted >= 0.5 && counted <= 2.0), counted);
  std::printf("   zones below 0.1 of a uniform mesh at the fine length (count_zones): %s\n",
              verdict(mesh.n_zones() < 0.1 * uniform));

  // 4. Volumes and quality.
  double volume_error = 0.0;
  for (unsigned int b = 0; b < blocks.n_blocks(); ++b)
    volume_error =
        std::max(volume_error, std::abs(filled[b] - blocks.volume[b]) / blocks.volume[b]);
  std::printf("4. every zone of positive volume: %s; zone volumes sum to each block's volume "
              "within 1e-12: %s\n",
              verdict(non_positive == 0), verdict(volume_error <= 1e-12));
  std::printf("   median radius ratio at least 0.6: %s\n",
              verdict(talus_test::median(quality) >= 0.6));

  std::fprintf(stderr,
               "%u blocks, %u zones, %u gridpoints, %.1f s to generate and mesh\n"
               "2. near: %zu zones, median edge/target %.4f, median edge %.4f m; far: %zu zones, "
               "median edge/target %.4f, median edge %.4f m; near/far %.4f\n"
               "3. count_zones %.0f (ratio %.4f), uniform at 0.5 m %.0f (graded/uniform %.4f)\n"
               "4. %u non-positive zones, volume error %.1e, median radius ratio %.4f, "
               "smallest %.3g\n",
               blocks.n_blocks(), mesh.n_zones(), mesh.n_gridpoints(), seconds, ratio_near.size(),
               near, talus_test::median(edge_near), ratio_far.size(), far,
               talus_test::median(edge_far), edge_ratio, estimate, counted, uniform,
               mesh.n_zones() / uniform, non_positive, volume_error, talus_test::median(quality),
               quality.empty() ? 0.0 : quality.front());
}
