// The zone writer: two brick blocks meshed into tetrahedra, a linear
// displacement field, a constant velocity per block and a stress made from
// the zone index are written, the VTU file is decoded again (base64, zlib:
// vtu_reading.h) and every cell is checked: its points at the displaced
// gridpoints of the zone, the displacement and velocity there, its stress
// tensor, principal stress and block id. Checks the numbering between
// zones/gridpoints and the file's cells/points.

#include <talus/base/parallel_environment.h>
#include <talus/io/zone_vtu_writer.h>
#include <talus/model/block_model.h>
#include <talus/zone/block_mesher.h>

#include <cstdint>
#include <stdexcept>

#include "../tests.h"
#include "vtu_reading.h"

using namespace talus;

namespace
{
/// The values of the data array called `name`, which must decode cleanly.
std::vector<double> read_array(const std::vector<vtu_reading::Array>& arrays,
                               const std::string& name)
{
  const vtu_reading::Array a = vtu_reading::find(arrays, name);
  if (a.name != name || !a.problem.empty() || a.format != "binary")
    throw std::runtime_error("cannot read array " + name + ": " + a.problem);
  return a.values;
}
} // namespace

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  BlockModel blocks;
  blocks.add_block(ConvexPolyhedron::box(Vec3(0, 0, 0), Vec3(1, 1, 1)), 0);
  blocks.add_block(ConvexPolyhedron::box(Vec3(1, 0, 0), Vec3(2, 1, 0.5)), 0);
  MeshReport report;
  const TetMesh mesh = mesh_blocks(blocks, {0, 1}, 0.5, report);
  std::printf("mesh: %u zones, %u gridpoints in %u blocks\n", report.zones, report.gridpoints,
              report.blocks);

  // u = A X (m), v = (1, 2, 3) (block + 1) m/s, stress of zone z: (z + 1)
  // times (1, 2, 3, 4, 5, 6) Pa.
  const double A[3][3] = {{1e-3, 2e-3, 0.0}, {0.0, -1e-3, 3e-3}, {2e-3, 0.0, 4e-3}};
  std::vector<double> x(3 * mesh.n_gridpoints()), u(x.size()), v(x.size());
  for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
    for (int i = 0; i < 3; ++i)
    {
      u[3 * g + i] = 0.0;
      for (int j = 0; j < 3; ++j)
        u[3 * g + i] += A[i][j] * mesh.position[3 * g + j];
      x[3 * g + i] = mesh.position[3 * g + i] + u[3 * g + i];
      v[3 * g + i] = (i + 1.0) * (mesh.gridpoint_block[g] + 1.0);
    }
  std::vector<double> stress(6 * mesh.n_zones()), principal(3 * mesh.n_zones());
  for (unsigned int z = 0; z < mesh.n_zones(); ++z)
  {
    for (int c = 0; c < 6; ++c)
      stress[6 * z + c] = (z + 1.0) * (c + 1.0);
    principal_stresses(&stress[6 * z], &principal[3 * z]);
  }
  ZoneWriter writer(mesh);
  const std::string path = "zone_writer_01.vtu";
  // Twice: the second frame reuses the DoF numbering of the first.
  for (int frame = 0; frame < 2; ++frame)
    writer.write(path, x, {{"displacement", 3, u}, {"velocity", 3, v}},
                 {{"stress", 6, stress}, {"principal_stress", 3, principal}}, 1.5);

  const std::string file = vtu_reading::read_text(path);
  const auto arrays = vtu_reading::read_arrays(file);
  const auto points = read_array(arrays, "Points");
  const auto connectivity = read_array(arrays, "connectivity");
  const auto disp = read_array(arrays, "displacement");
  const auto vel = read_array(arrays, "velocity");
  const auto sig = read_array(arrays, "stress");
  const auto prin = read_array(arrays, "principal_stress");
  const auto block = read_array(arrays, "block_id");
  std::printf("file: %zu cells, %zu points\n", connectivity.size() / 4, points.size() / 3);

  // Largest relative mismatch of each quantity over all cells (the fields
  // are single precision, the points double).
  double e_x = 0, e_u = 0, e_v = 0, e_s = 0, e_p = 0, e_b = 0;
  const auto rel = [](double a, double b) { return std::abs(a - b) / std::max(1.0, std::abs(b)); };
  const unsigned int voigt[9] = {0, 3, 5, 3, 1, 4, 5, 4, 2};
  for (unsigned int z = 0; z < mesh.n_zones(); ++z)
  {
    for (int k = 0; k < 4; ++k)
    {
      const std::size_t p = static_cast<std::size_t>(connectivity[4 * z + k]);
      const unsigned int g = mesh.zone_gridpoint[z][k];
      for (int d = 0; d < 3; ++d)
      {
        e_x = std::max(e_x, rel(points[3 * p + d], x[3 * g + d]));
        e_u = std::max(e_u, rel(disp[3 * p + d], u[3 * g + d]));
        e_v = std::max(e_v, rel(vel[3 * p + d], v[3 * g + d]));
      }
    }
    // Zone data are cell data.
    for (int c = 0; c < 9; ++c)
      e_s = std::max(e_s, rel(sig[9 * z + c], stress[6 * z + voigt[c]]) /
                              std::max(1.0, stress[6 * z + voigt[c]]));
    for (int c = 0; c < 3; ++c)
      e_p = std::max(e_p, rel(prin[3 * z + c], principal[3 * z + c]) /
                              std::max(1.0, std::abs(principal[3 * z + c])));
    e_b = std::max(e_b, std::abs(block[z] - mesh.zone_block[z]));
  }
  talus_test::check("positions, largest mismatch", e_x, 0.0, 1e-6);
  talus_test::check("displacement, largest mismatch", e_u, 0.0, 1e-6);
  talus_test::check("velocity, largest mismatch", e_v, 0.0, 1e-6);
  talus_test::check("stress tensor, largest relative mismatch", e_s, 0.0, 1e-6);
  talus_test::check("principal stress, largest relative mismatch", e_p, 0.0, 1e-6);
  talus_test::check("block id, largest mismatch", e_b, 0.0, 0.0);
  std::printf("time in file: %s\n",
              file.find(">1.5</DataArray>") != std::string::npos ? "1.5" : "missing");
  return 0;
}
