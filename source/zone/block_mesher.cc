#include <talus/base/exceptions.h>
#include <talus/zone/block_mesher.h>
#include <talus/zone/hex_mesher.h>
#include <talus/zone/hex_mixed.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>

namespace talus
{

namespace
{
using dealii::Point;

/// True when the block is an axis-aligned box (six faces, normals along
/// the axes): deal.II's generator meshes it directly.
bool is_axis_aligned_box(const BlockModel& m, unsigned int b, Box& box)
{
  if (m.face_start[b + 1] - m.face_start[b] != 6 || m.vertex_start[b + 1] - m.vertex_start[b] != 8)
    return false;
  for (unsigned int f = m.face_start[b]; f < m.face_start[b + 1]; ++f)
  {
    const Vec3& n = m.face_normal[f];
    if (std::abs(std::abs(n.x()) + std::abs(n.y()) + std::abs(n.z()) - 1.0) > 1e-12 ||
        n.cwiseAbs().maxCoeff() < 1.0 - 1e-12)
      return false;
  }
  box.lo = box.hi = m.vertex[m.vertex_start[b]];
  for (unsigned int v = m.vertex_start[b]; v < m.vertex_start[b + 1]; ++v)
  {
    box.lo = box.lo.cwiseMin(m.vertex[v]);
    box.hi = box.hi.cwiseMax(m.vertex[v]);
  }
  return true;
}

double signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

/// The fine mesh of one block as its own small triangulation.
/// Divisions of a brick along each axis for zones of edge at most `edge`.
std::vector<unsigned int> brick_divisions(const Box& box, double edge)
{
  std::vector<unsigned int> n(3);
  for (int d = 0; d < 3; ++d)
    n[d] =
        std::max(1u, static_cast<unsigned int>(std::ceil((box.hi[d] - box.lo[d]) / edge - 1e-9)));
  return n;
}

void mesh_one_block(const BlockModel& m, unsigned int b, double edge,
                    dealii::Triangulation<3>& tria)
{
  Box box;
  if (is_axis_aligned_box(m, b, box))
  {
    const std::vector<unsigned int> n = brick_divisions(box, edge);
    dealii::GridGenerator::subdivided_hyper_rectangle_with_simplices(
        tria, n, Point<3>(box.lo.x(), box.lo.y(), box.lo.z()),
        Point<3>(box.hi.x(), box.hi.y(), box.hi.z()));
    return;
  }
  // Any convex block: tetrahedra from the centroid to every triangle of a
  // fan over each face, then uniform refinement (each tetrahedron into
  // eight) until the longest edge is at most `edge`.
  std::vector<Point<3>> vertices;
  for (unsigned int v = m.vertex_start[b]; v < m.vertex_start[b + 1]; ++v)
    vertices.emplace_back(m.vertex[v].x(), m.vertex[v].y(), m.vertex[v].z());
  const unsigned int centre = static_cast<unsigned int>(vertices.size());
  const Vec3 c = m.centroid[b];
  vertices.emplace_back(c.x(), c.y(), c.z());
  std::vector<dealii::CellData<3>> cells;
  double longest = 0.0;
  for (unsigned int f = m.face_start[b]; f < m.face_start[b + 1]; ++f)
  {
    const unsigned int first = m.face_loop_start[f], n = m.face_loop_start[f + 1] - first;
    for (unsigned int k = 1; k + 1 < n; ++k)
    {
      std::array<unsigned int, 4> t{m.face_vertex[first] - m.vertex_start[b],
                                    m.face_vertex[first + k] - m.vertex_start[b],
                                    m.face_vertex[first + k + 1] - m.vertex_start[b], centre};
      const auto P = [&](unsigned int i)
      { return Vec3(vertices[t[i]][0], vertices[t[i]][1], vertices[t[i]][2]); };
      if (signed_volume(P(0), P(1), P(2), P(3)) < 0.0)
        std::swap(t[1], t[2]);
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j)
          longest = std::max(longest, (P(i) - P(j)).norm());
      dealii::CellData<3> cell(4);
      for (int i = 0; i < 4; ++i)
        cell.vertices[i] = t[i];
      cells.push_back(cell);
    }
  }
  tria.create_triangulation(vertices, cells, dealii::SubCellData());
  const unsigned int levels =
      longest > edge ? static_cast<unsigned int>(std::ceil(std::log2(longest / edge) - 1e-9)) : 0;
  if (levels > 0)
    tria.refine_global(levels);
}

} // namespace

void append_tetrahedra(TetMesh& mesh, const dealii::Triangulation<3>& tria, unsigned int block)
{
  const auto P = [&](unsigned int g)
  { return Vec3(mesh.position[3 * g], mesh.position[3 * g + 1], mesh.position[3 * g + 2]); };
  // The block's cells, with its own gridpoints (blocks never share one).
  const unsigned int offset = mesh.n_gridpoints();
  std::vector<int> local(tria.n_vertices(), -1);
  const std::size_t first_zone = mesh.zone_gridpoint.size();
  for (const auto& cell : tria.active_cell_iterators())
  {
    if (cell->n_vertices() != 4)
      throw InputError("a deformable block's mesh must be made of tetrahedra only");
    std::array<unsigned int, 4> t;
    for (unsigned int i = 0; i < 4; ++i)
    {
      const unsigned int v = cell->vertex_index(i);
      if (local[v] < 0)
      {
        local[v] = static_cast<int>(mesh.n_gridpoints() - offset);
        for (int d = 0; d < 3; ++d)
          mesh.position.push_back(tria.get_vertices()[v][d]);
        mesh.gridpoint_block.push_back(block);
      }
      t[i] = offset + static_cast<unsigned int>(local[v]);
    }
    if (signed_volume(P(t[0]), P(t[1]), P(t[2]), P(t[3])) < 0.0)
      std::swap(t[1], t[2]);
    mesh.zone_gridpoint.push_back(t);
    mesh.zone_block.push_back(block);
  }
  // Boundary faces of this block: the zone faces that appear once.
  std::map<std::array<unsigned int, 3>, std::pair<unsigned int, int>> seen;
  static const int face_of[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  for (std::size_t z = first_zone; z < mesh.zone_gridpoint.size(); ++z)
    for (int f = 0; f < 4; ++f)
    {
      std::array<unsigned int, 3> key{mesh.zone_gridpoint[z][face_of[f][0]],
                                      mesh.zone_gridpoint[z][face_of[f][1]],
                                      mesh.zone_gridpoint[z][face_of[f][2]]};
      std::sort(key.begin(), key.end());
      auto [it, fresh] = seen.emplace(key, std::make_pair(static_cast<unsigned int>(z), f));
      if (!fresh)
        seen.erase(it);
    }
  for (const auto& [key, where] : seen)
  {
    const auto& t = mesh.zone_gridpoint[where.first];
    // Face f of the zone is opposite its vertex f: turn it to face away.
    std::array<unsigned int, 3> face{t[face_of[where.second][0]], t[face_of[where.second][1]],
                                     t[face_of[where.second][2]]};
    const Vec3 n = (P(face[1]) - P(face[0])).cross(P(face[2]) - P(face[0]));
    if (n.dot(P(face[0]) - P(t[where.second])) < 0.0)
      std::swap(face[1], face[2]);
    mesh.face_gridpoint.push_back(face);
    mesh.face_zone.push_back(where.first);
  }
}

TetMesh read_gmsh_block(const std::string& path, unsigned int block)
{
  std::ifstream in(path);
  if (!in)
    throw InputError(path + ": cannot open the mesh file");
  dealii::Triangulation<3> tria;
  try
  {
    dealii::GridIn<3> reader;
    reader.attach_triangulation(tria);
    reader.read_msh(in);
  }
  catch (const std::exception& e)
  {
    std::string why = e.what();
    // deal.II's messages span many lines; keep the line that says what.
    const std::size_t at = why.find("Additional information:");
    if (at != std::string::npos)
      why = why.substr(at + 23);
    why = why.substr(0, why.find("Stacktrace"));
    std::replace(why.begin(), why.end(), '\n', ' ');
    // Squeeze runs of spaces left by the line breaks.
    why.erase(
        std::unique(why.begin(), why.end(), [](char a, char b) { return a == ' ' && b == ' '; }),
        why.end());
    while (!why.empty() && why.back() == ' ')
      why.pop_back();
    while (!why.empty() && why.front() == ' ')
      why.erase(why.begin());
    throw InputError(path + ": not a gmsh mesh talus can read: " + why);
  }
  TetMesh mesh;
  append_tetrahedra(mesh, tria, block);
  return mesh;
}

MeshReport measure_mesh(const TetMesh& mesh)
{
  const auto P = [&](unsigned int g)
  { return Vec3(mesh.position[3 * g], mesh.position[3 * g + 1], mesh.position[3 * g + 2]); };
  MeshReport report;
  report.zones = mesh.n_zones();
  report.gridpoints = mesh.n_gridpoints();
  report.boundary_faces = mesh.n_faces();
  report.hexes = mesh.n_hexes();
  const std::vector<char> in_hex = zones_in_hexes(mesh);
  report.smallest_height = 1e300;
  std::vector<char> seen_block;
  for (unsigned int b : mesh.zone_block)
  {
    if (b >= seen_block.size())
      seen_block.resize(b + 1, 0);
    report.blocks += seen_block[b] == 0;
    seen_block[b] = 1;
  }
  for (const auto& t : mesh.zone_gridpoint)
  {
    const double v = signed_volume(P(t[0]), P(t[1]), P(t[2]), P(t[3]));
    if (!(v > 0.0))
      throw InputError("a zone has zero volume (a degenerate block or mesh)");
    // The two overlays of a hexahedral zone fill it twice.
    report.zone_volume += in_hex[&t - mesh.zone_gridpoint.data()] ? 0.5 * v : v;
    double largest_face = 0.0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
      {
        report.largest_edge = std::max(report.largest_edge, (P(t[i]) - P(t[j])).norm());
        for (int k = j + 1; k < 4; ++k)
          largest_face =
              std::max(largest_face, 0.5 * (P(t[j]) - P(t[i])).cross(P(t[k]) - P(t[i])).norm());
      }
    report.smallest_height = std::min(report.smallest_height, 3.0 * v / largest_face);
  }
  return report;
}

TetMesh mesh_blocks(const BlockModel& m, const std::vector<unsigned int>& which, double edge_length,
                    MeshReport& report, ZoneElement element)
{
  if (!(edge_length > 0.0))
    throw InputError("zone edge length must be positive");
  if (element == ZoneElement::tet10)
    throw InputError("entry 'Element' in subsection 'Deformable': tet10 is not built yet; allowed: "
                     "tet4 or hex-mixed");
  TetMesh mesh;
  for (unsigned int b : which)
  {
    if (element == ZoneElement::hex_mixed)
    {
      Box box;
      if (!is_axis_aligned_box(m, b, box))
        throw InputError("entry 'Element' in subsection 'Deformable': hex-mixed needs every "
                         "deformable block to be an axis-aligned brick, and block " +
                         std::to_string(b) + " (" +
                         std::to_string(m.face_start[b + 1] - m.face_start[b]) +
                         " faces) is not one; allowed: tet4 for blocks of other shapes");
      const std::vector<unsigned int> n = brick_divisions(box, edge_length);
      append_hex_mixed_brick(mesh, box, {n[0], n[1], n[2]}, b);
      continue;
    }
    dealii::Triangulation<3> one;
    mesh_one_block(m, b, edge_length, one);
    append_tetrahedra(mesh, one, b);
  }
  report = measure_mesh(mesh);
  return mesh;
}

} // namespace talus
