// scratch: gmsh mesher on jointed blocks
#include <talus/geometry/block_generator.h>
#include <talus/model/block_model.h>
#include <talus/zone/convex_block_mesher.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>
#include <gmsh.h>

int main(int argc, char** argv)
{
  using namespace talus;
  const double n = argc > 1 ? std::atof(argv[1]) : 5.0;
  const double h = argc > 2 ? std::atof(argv[2]) : 0.5;
  BlockGenerator generator(ConvexPolyhedron::box(Vec3::Zero(), Vec3::Constant(n)), {});
  generator.cut_joint_set({10.0, 30.0, 1.0, Vec3::Constant(0.5), 0, false, {}});
  generator.cut_joint_set({80.0, 120.0, 1.0, Vec3::Constant(0.5), 0, false, {}});
  generator.cut_joint_set({75.0, 220.0, 1.0, Vec3::Constant(0.5), 0, false, {}});
  BlockModel model;
  for (const ConvexPolyhedron& b : generator.blocks())
    model.add_block(b, 0);
  GmshSession session;
  if (argc > 3) gmsh::option::setNumber("Mesh.Algorithm", std::atof(argv[3]));
  if (argc > 4) gmsh::option::setNumber("Mesh.Algorithm3D", std::atof(argv[4]));
  if (argc > 5) gmsh::option::setNumber("Mesh.Optimize", std::atof(argv[5]));
  std::vector<double> q;
  double zones = 0, band = 0, vol_err = 0;
  const auto start = std::chrono::steady_clock::now();
  std::vector<unsigned int> all;
  for (unsigned int b = 0; b < model.n_blocks(); ++b) all.push_back(b);
  const std::size_t batch = argc > 6 ? std::atoi(argv[6]) : 64;
  std::vector<BlockTetrahedra> meshes = mesh_convex_blocks(model, all, [h](const Vec3&) { return h; }, batch);
  for (unsigned int b = 0; b < model.n_blocks(); ++b)
  {
    BlockTetrahedra& t = meshes[b];
    zones += t.tet.size();
    band += regular_tetrahedra_in(model.volume[b], h);
    double v = 0;
    for (auto& z : t.tet)
    {
      q.push_back(radius_ratio(t.point[z[0]], t.point[z[1]], t.point[z[2]], t.point[z[3]]));
      v += (t.point[z[1]] - t.point[z[0]]).dot((t.point[z[2]] - t.point[z[0]]).cross(t.point[z[3]] - t.point[z[0]])) / 6;
    }
    vol_err = std::max(vol_err, std::abs(v - model.volume[b]) / model.volume[b]);
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::sort(q.begin(), q.end());
  std::printf("blocks %u zones %.0f regular %.0f ratio %.2f  %.3f s  %.0f zones/s  q min %.3f 1%% %.3f med %.3f  <0.1: %zu  volerr %.1e\n",
              model.n_blocks(), zones, band, zones / band, s, zones / s, q[0], q[q.size() / 100], q[q.size() / 2],
              std::size_t(std::lower_bound(q.begin(), q.end(), 0.1) - q.begin()), vol_err);
}
