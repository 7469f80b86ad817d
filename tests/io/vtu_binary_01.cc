// Compressed binary VTU output (issue 21): the zone, block and contact
// files are written once in binary and once in ASCII, decoded by the test's
// own base64 and zlib reader (vtu_reading.h), and every array must hold
// exactly the same values in both (ASCII writes the shortest text that
// reads back exactly), with a consistent header: block count, block size,
// last block size (0 when full), compressed sizes adding up to the data.
// The encoder alone is checked at its edges (an array of exactly two full
// blocks, one a value over, an empty one) against the values given. The
// zone file is also checked against the mesh: the points at the positions
// given (Float64), the connectivity, the stress tensor, the block ids. The
// entry 'VTU encoding' of a scene chooses the encoding.

#include <talus/io/block_vtu_writer.h>
#include <talus/io/contact_vtu_writer.h>
#include <talus/scene/scene.h>
#include <talus/io/vtu_encoding.h>
#include <talus/io/zone_vtu_writer.h>
#include <talus/scene/build_blocks.h>
#include <talus/solver/rigid_solver.h>
#include <talus/zone/block_mesher.h>
#include <talus/zone/hex_mixed.h>
#include <talus/zone/tet10_mesh.h>

#include "../tests.h"
#include "vtu_reading.h"

#include <cmath>
#include <fstream>
#include <sstream>

using namespace talus;

namespace
{

/// Whether two files hold the same arrays (names, types, components,
/// values exactly), the binary one in binary with consistent headers.
bool same_arrays(const char* what, const std::string& binary_path, const std::string& ascii_path)
{
  const std::string binary_text = vtu_reading::read_text(binary_path);
  const auto binary = vtu_reading::read_arrays(binary_text);
  const auto ascii = vtu_reading::read_arrays(vtu_reading::read_text(ascii_path));
  bool good = binary.size() == ascii.size() && !binary.empty() &&
              binary_text.find("compressor=\"vtkZLibDataCompressor\"") != std::string::npos &&
              binary_text.find("header_type=\"UInt64\"") != std::string::npos;
  unsigned int multi_block = 0;
  for (std::size_t k = 0; good && k < binary.size(); ++k)
  {
    const auto &b = binary[k], &a = ascii[k];
    const bool in_binary = b.format == "binary" || b.name == "TIME";
    const bool same = in_binary && a.format == "ascii" && b.problem.empty() && a.problem.empty() &&
                      b.name == a.name && b.type == a.type && b.components == a.components &&
                      b.values == a.values;
    if (!same)
      std::fprintf(stderr, "%s: array %s (%s, %s) differs: %s %s, %zu and %zu values\n", what,
                   b.name.c_str(), b.type.c_str(), b.format.c_str(), b.problem.c_str(),
                   a.problem.c_str(), b.values.size(), a.values.size());
    good &= same;
    multi_block += b.blocks > 1;
  }
  std::fprintf(stderr, "%s: %zu arrays, %u of several blocks, binary %zu bytes, ascii %zu\n", what,
               binary.size(), multi_block, binary_text.size(),
               vtu_reading::read_text(ascii_path).size());
  return good;
}

/// The encoder on its own: `n` tuples of T with `components` each, from
/// values that use every bit (or every small integer).
template <typename T>
bool encoder_round_trip(unsigned int components, std::size_t n, std::uint64_t want_blocks,
                        std::uint64_t want_last)
{
  std::vector<T> values(n * components);
  for (std::size_t i = 0; i < values.size(); ++i)
    values[i] = std::is_floating_point_v<T> ? static_cast<T>(std::sin(0.37 * i) / 3.0)
                                            : static_cast<T>((i * 7919) % 1000003);
  bool good = true;
  for (const VtuEncoding e : {VtuEncoding::binary, VtuEncoding::ascii})
  {
    std::ostringstream out;
    write_data_array<T>(out, e, "x", components, values);
    const auto arrays = vtu_reading::read_arrays(out.str());
    good &= arrays.size() == 1 && arrays[0].problem.empty() &&
            arrays[0].values == std::vector<double>(values.begin(), values.end()) &&
            arrays[0].type == vtk_type_name<T>() && arrays[0].components == components;
    if (e == VtuEncoding::binary)
      good &= arrays.size() == 1 && arrays[0].blocks == want_blocks &&
              arrays[0].last_block_size == want_last &&
              arrays[0].block_size ==
                  vtu_block_bytes / (components * sizeof(T)) * (components * sizeof(T));
  }
  return good;
}

} // namespace

int main()
{
  // The encoder at its edges (64 KiB blocks of whole tuples).
  std::printf("two full blocks of Int32: %s\n",
              talus_test::verdict(encoder_round_trip<std::int32_t>(1, 2 * 16384, 2, 0)));
  std::printf("two blocks and one tuple of Float64 x 3: %s\n",
              talus_test::verdict(encoder_round_trip<double>(3, 2 * 2730 + 1, 3, 24)));
  std::printf("part of a block of Float32 x 9: %s\n",
              talus_test::verdict(encoder_round_trip<float>(9, 100, 1, 3600)));
  // Values that zlib's matching hardly shrinks: from the fifth block on,
  // Huffman coding alone.
  std::printf("six full blocks of Float32: %s\n",
              talus_test::verdict(encoder_round_trip<float>(1, 6 * 16384, 6, 0)));
  std::printf("empty UInt8: %s\n",
              talus_test::verdict(encoder_round_trip<std::uint8_t>(1, 0, 0, 0)));

  // Zones: two bricks, some 7500 zones, so that arrays span several blocks.
  BlockModel blocks;
  blocks.add_block(ConvexPolyhedron::box(Vec3(0, 0, 0), Vec3(1, 1, 1)), 0);
  blocks.add_block(ConvexPolyhedron::box(Vec3(1, 0, 0), Vec3(2, 1, 0.5)), 0);
  MeshReport report;
  const TetMesh mesh = mesh_blocks(blocks, {0, 1}, 0.1, report);
  std::printf("mesh: %u zones, %u gridpoints\n", report.zones, report.gridpoints);
  std::vector<double> x(3 * mesh.n_gridpoints()), u(x.size());
  for (std::size_t i = 0; i < x.size(); ++i)
  {
    u[i] = 1e-3 * std::sin(1.7 * i);
    x[i] = mesh.position[i] + u[i];
  }
  std::vector<double> stress(6 * mesh.n_zones()), principal(3 * mesh.n_zones()),
      state(mesh.n_zones());
  for (unsigned int z = 0; z < mesh.n_zones(); ++z)
  {
    for (int c = 0; c < 6; ++c)
      stress[6 * z + c] = -1e6 * (c + 1) * (1.0 + 0.1 * std::cos(0.3 * z + c));
    principal_stresses(&stress[6 * z], &principal[3 * z]);
    state[z] = z % 3;
  }
  for (const VtuEncoding e : {VtuEncoding::binary, VtuEncoding::ascii})
    ZoneWriter(mesh, e).write(
        e == VtuEncoding::binary ? "zones_binary.vtu" : "zones_ascii.vtu", x,
        {{"displacement", 3, u}},
        {{"stress", 6, stress}, {"principal_stress", 3, principal}, {"plastic_state", 1, state}},
        0.25);
  std::printf("zones, binary as ascii: %s\n",
              talus_test::verdict(same_arrays("zones", "zones_binary.vtu", "zones_ascii.vtu")));
  {
    const auto arrays = vtu_reading::read_arrays(vtu_reading::read_text("zones_binary.vtu"));
    const auto points = vtu_reading::find(arrays, "Points").values;
    const auto connectivity = vtu_reading::find(arrays, "connectivity").values;
    const auto tensor = vtu_reading::find(arrays, "stress").values;
    const auto block = vtu_reading::find(arrays, "block_id").values;
    const auto time = vtu_reading::find(arrays, "TIME").values;
    bool points_ok = points == x, cells_ok = connectivity.size() == 4 * mesh.n_zones(),
         stress_ok = tensor.size() == 9 * mesh.n_zones(), block_ok = block.size() == mesh.n_zones();
    const unsigned int voigt[9] = {0, 3, 5, 3, 1, 4, 5, 4, 2};
    for (unsigned int z = 0; z < mesh.n_zones() && cells_ok && stress_ok && block_ok; ++z)
    {
      for (int k = 0; k < 4; ++k)
        cells_ok &= connectivity[4 * z + k] == mesh.zone_gridpoint[z][k];
      for (int c = 0; c < 9; ++c)
        stress_ok &= tensor[9 * z + c] == static_cast<float>(stress[6 * z + voigt[c]]);
      block_ok &= block[z] == mesh.zone_block[z];
    }
    std::printf("zones: points at the positions: %s\n", talus_test::verdict(points_ok));
    std::printf("zones: cells on the zones' gridpoints: %s\n", talus_test::verdict(cells_ok));
    std::printf("zones: stress tensor per zone: %s\n", talus_test::verdict(stress_ok));
    std::printf("zones: block id per zone: %s\n", talus_test::verdict(block_ok));
    std::printf("zones: time: %s\n", talus_test::verdict(time == std::vector<double>{0.25}));
  }

  // 10-node and hexahedral zones: the cells are those of shown_tetrahedra,
  // each with the block of its zone.
  {
    TetMesh tet10 = mesh_blocks(blocks, {0, 1}, 0.25, report);
    make_quadratic(tet10);
    const TetMesh hex = mesh_blocks(blocks, {0, 1}, 0.25, report, ZoneElement::hex_mixed);
    for (const TetMesh* m : {static_cast<const TetMesh*>(&tet10), &hex})
    {
      const auto cells = shown_tetrahedra(*m);
      std::vector<unsigned int> cell_block;
      const std::vector<char> in_hex = zones_in_hexes(*m);
      for (unsigned int z = 0; z < m->n_zones(); ++z)
        if (!in_hex[z])
          cell_block.insert(cell_block.end(), m->quadratic() ? 8 : 1, m->zone_block[z]);
      for (unsigned int h = 0; h < m->n_hexes(); ++h)
        cell_block.insert(cell_block.end(), TetMesh::tets_per_hex / 2,
                          m->zone_block[m->hex_first_zone[h]]);
      ZoneWriter(*m).write("zones_other.vtu", m->position, {},
                           {{"stress", 6, std::vector<double>(6 * cells.size(), 1.0)}}, 0.0);
      const auto arrays = vtu_reading::read_arrays(vtu_reading::read_text("zones_other.vtu"));
      const auto connectivity = vtu_reading::find(arrays, "connectivity").values;
      const auto block = vtu_reading::find(arrays, "block_id").values;
      bool good = connectivity.size() == 4 * cells.size() && block.size() == cells.size() &&
                  cell_block.size() == cells.size();
      for (std::size_t i = 0; good && i < cells.size(); ++i)
      {
        for (int k = 0; k < 4; ++k)
          good &= connectivity[4 * i + k] == cells[i][k];
        good &= block[i] == cell_block[i];
      }
      std::printf("%s zones: %zu cells as shown_tetrahedra, block ids: %s\n",
                  m->quadratic() ? "10-node" : "hexahedral", cells.size(),
                  talus_test::verdict(good));
    }
  }

  // Blocks and contacts: three rows of blocks cut by two joint sets and a
  // joint, after 20 steps of settling on the fixed bottom row.
  std::ofstream("vtu_binary_01.prm") << "subsection Model\n"
                                        "  set Brick min = 0, 0, 0\n"
                                        "  set Brick max = 2, 1, 3\n"
                                        "end\n"
                                        "subsection Joint set 1\n"
                                        "  set Dip = 0\n"
                                        "  set Spacing = 1\n"
                                        "end\n"
                                        "subsection Joint set 2\n"
                                        "  set Dip = 90\n"
                                        "  set Dip direction = 90\n"
                                        "  set Spacing = 1\n"
                                        "end\n"
                                        "subsection Joint 1\n"
                                        "  set Dip = 90\n"
                                        "  set Origin = 0, 0.5, 0\n"
                                        "end\n"
                                        "subsection Group 1\n"
                                        "  set Name = floor\n"
                                        "  set Corner min = 0, 0, 0\n"
                                        "  set Corner max = 2, 1, 1\n"
                                        "end\n"
                                        "subsection Solver\n"
                                        "  set Mode = dynamic\n"
                                        "  set Steps = 20\n"
                                        "  set Fixed groups = floor\n"
                                        "end\n";
  Scene scene = read_scene("vtu_binary_01.prm", false);
  // The entry 'VTU encoding' of subsection Output: binary unless asked.
  std::ofstream("vtu_binary_01_ascii.prm") << "subsection Output\n"
                                              "  set VTU encoding = ascii\n"
                                              "end\n";
  std::printf(
      "'VTU encoding': binary by default, ascii when asked: %s\n",
      talus_test::verdict(scene.output.vtu_encoding == VtuEncoding::binary &&
                          read_scene("vtu_binary_01_ascii.prm", false).output.vtu_encoding ==
                              VtuEncoding::ascii));
  BuildReport build;
  BlockModel model = build_blocks(scene, build);
  resolve_group_names(scene, model);
  RigidSolver solver(model, scene.density, scene.solver);
  for (int i = 0; i < 20; ++i)
    solver.step();
  std::vector<BlockField> fields{{"velocity", 3, {}}};
  for (unsigned int b = 0; b < model.n_blocks(); ++b)
    for (int d = 0; d < 3; ++d)
      fields[0].values.push_back(solver.velocity[b][d]);
  for (const VtuEncoding e : {VtuEncoding::binary, VtuEncoding::ascii})
  {
    const bool binary = e == VtuEncoding::binary;
    write_blocks_vtu(binary ? "blocks_binary.vtu" : "blocks_ascii.vtu", model, fields, e);
    write_contacts_vtu(binary ? "contacts_binary.vtu" : "contacts_ascii.vtu", solver.contacts(),
                       model, JointNumbers{{1, 2}, {1}}, e);
  }
  std::printf("blocks: %u, sub-contacts: %s\n", model.n_blocks(),
              talus_test::verdict(solver.contacts().n_subcontacts() > 50));
  std::printf("blocks, binary as ascii: %s\n",
              talus_test::verdict(same_arrays("blocks", "blocks_binary.vtu", "blocks_ascii.vtu")));
  std::printf(
      "contacts, binary as ascii: %s\n",
      talus_test::verdict(same_arrays("contacts", "contacts_binary.vtu", "contacts_ascii.vtu")));
  const auto volume =
      vtu_reading::find(vtu_reading::read_arrays(vtu_reading::read_text("blocks_binary.vtu")),
                        "volume")
          .values;
  std::printf("blocks: volumes exact: %s\n", talus_test::verdict(volume == model.volume));
  const auto area =
      vtu_reading::find(vtu_reading::read_arrays(vtu_reading::read_text("contacts_binary.vtu")),
                        "area")
          .values;
  std::printf("contacts: areas exact: %s\n",
              talus_test::verdict(area == solver.contacts().sc_area));
  return 0;
}
