#include <talus/base/exceptions.h>
#include <talus/zone/block_mesher.h>
#include <talus/zone/hex_mesher.h>
#include <talus/zone/hex_mixed.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>

namespace talus
{

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

namespace
{
using dealii::Point;

double signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

/// Hexahedra along a side of `length` of an axis-aligned block (m).
double hexahedra_along(double length, double edge)
{
  return std::max(1.0, std::ceil(length / edge - 1e-9));
}

/// Divisions of a brick along each axis for zones of edge at most `edge`.
std::vector<unsigned int> brick_divisions(const Box& box, double edge)
{
  std::vector<unsigned int> n(3);
  for (int d = 0; d < 3; ++d)
    n[d] = static_cast<unsigned int>(hexahedra_along(box.hi[d] - box.lo[d], edge));
  return n;
}

/// The edge length for a brick meshed by deal.II's generator: the
/// smallest the field asks for at its corners and centre (m).
double brick_edge(const Box& box, const EdgeLengthField& field)
{
  double h = field.at(0.5 * (box.lo + box.hi));
  for (int i = 0; i < 8; ++i)
    h = std::min(h, field.at(Vec3(i & 1 ? box.hi.x() : box.lo.x(), i & 2 ? box.hi.y() : box.lo.y(),
                                  i & 4 ? box.hi.z() : box.lo.z())));
  return h;
}

/// Appends zones `tets` on `points` as block `block`'s, each gridpoint its
/// own, turned to positive volume, and the block's boundary faces (the zone
/// faces that appear once), turned to face out.
void append_zones(TetMesh& mesh, const std::vector<Vec3>& points,
                  std::vector<std::array<unsigned int, 4>> tets, unsigned int block)
{
  const unsigned int offset = mesh.n_gridpoints();
  for (const Vec3& p : points)
  {
    mesh.position.insert(mesh.position.end(), {p.x(), p.y(), p.z()});
    mesh.gridpoint_block.push_back(block);
  }
  const std::size_t first_zone = mesh.zone_gridpoint.size();
  for (auto& t : tets)
  {
    for (auto& g : t)
      g += offset;
    const auto P = [&](unsigned int g) { return points[g - offset]; };
    if (signed_volume(P(t[0]), P(t[1]), P(t[2]), P(t[3])) < 0.0)
      std::swap(t[1], t[2]);
    mesh.zone_gridpoint.push_back(t);
    mesh.zone_block.push_back(block);
  }
  // Boundary faces: sort every zone face by its sorted corners; a face
  // found once is on the boundary.
  static const int face_of[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  struct ZoneFace
  {
    std::array<unsigned int, 3> key;
    unsigned int zone;
    int face;
  };
  std::vector<ZoneFace> faces;
  faces.reserve(4 * tets.size());
  for (std::size_t z = first_zone; z < mesh.zone_gridpoint.size(); ++z)
    for (int f = 0; f < 4; ++f)
    {
      ZoneFace zf{{{mesh.zone_gridpoint[z][face_of[f][0]], mesh.zone_gridpoint[z][face_of[f][1]],
                    mesh.zone_gridpoint[z][face_of[f][2]]}},
                  static_cast<unsigned int>(z),
                  f};
      std::sort(zf.key.begin(), zf.key.end());
      faces.push_back(zf);
    }
  std::sort(faces.begin(), faces.end(),
            [](const ZoneFace& a, const ZoneFace& b)
            { return a.key != b.key ? a.key < b.key : a.zone < b.zone; });
  const auto P = [&](unsigned int g) { return points[g - offset]; };
  for (std::size_t i = 0; i < faces.size();)
  {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key)
      ++j;
    if (j == i + 1)
    {
      const auto& t = mesh.zone_gridpoint[faces[i].zone];
      const int f = faces[i].face;
      // Face f of the zone is opposite its vertex f: turn it to face away.
      std::array<unsigned int, 3> face{{t[face_of[f][0]], t[face_of[f][1]], t[face_of[f][2]]}};
      const Vec3 n = (P(face[1]) - P(face[0])).cross(P(face[2]) - P(face[0]));
      if (n.dot(P(face[0]) - P(t[f])) < 0.0)
        std::swap(face[1], face[2]);
      mesh.face_gridpoint.push_back(face);
      mesh.face_zone.push_back(faces[i].zone);
    }
    i = j;
  }
}

/// Throws InputError naming `path` unless the zones form one body: every
/// zone face shared by at most two zones, the boundary faces a closed
/// surface (each of their edges on exactly two of them), all zones connected
/// through shared faces.
void check_one_closed_body(const TetMesh& mesh, const std::string& path)
{
  if (mesh.n_zones() == 0)
    throw InputError(path + ": the mesh holds no tetrahedra");
  static const int face_of[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  std::map<std::array<unsigned int, 3>, std::vector<unsigned int>> zones_of_face;
  for (unsigned int z = 0; z < mesh.n_zones(); ++z)
    for (const auto& f : face_of)
    {
      std::array<unsigned int, 3> key{{mesh.zone_gridpoint[z][f[0]], mesh.zone_gridpoint[z][f[1]],
                                      mesh.zone_gridpoint[z][f[2]]}};
      std::sort(key.begin(), key.end());
      if (key[0] == key[1] || key[1] == key[2])
        throw InputError(path + ": tetrahedron " + std::to_string(z + 1) + " uses one node twice");
      zones_of_face[key].push_back(z);
    }
  // Zones joined through shared faces (union-find), and the boundary edges.
  std::vector<unsigned int> root(mesh.n_zones());
  for (unsigned int z = 0; z < mesh.n_zones(); ++z)
    root[z] = z;
  const auto find = [&](unsigned int z)
  {
    while (root[z] != z)
      z = root[z] = root[root[z]];
    return z;
  };
  std::map<std::pair<unsigned int, unsigned int>, unsigned int> boundary_edges;
  for (const auto& [face, zones] : zones_of_face)
  {
    if (zones.size() > 2)
      throw InputError(path + ": " + std::to_string(zones.size()) +
                       " tetrahedra share one face (zones overlap)");
    if (zones.size() == 2)
      root[find(zones[0])] = find(zones[1]);
    else
      for (int i = 0; i < 3; ++i)
        ++boundary_edges[std::minmax(face[i], face[(i + 1) % 3])];
  }
  for (const auto& [edge, count] : boundary_edges)
    if (count != 2)
    {
      const unsigned int g = edge.first;
      throw InputError(path + ": the boundary of the body is not a closed surface (an edge at " +
                       number(mesh.position[3 * g]) + ", " + number(mesh.position[3 * g + 1]) +
                       ", " + number(mesh.position[3 * g + 2]) + " joins " + std::to_string(count) +
                       " boundary faces instead of 2)");
    }
  unsigned int bodies = 0;
  for (unsigned int z = 0; z < mesh.n_zones(); ++z)
    bodies += find(z) == z;
  if (bodies != 1)
    throw InputError(path + ": the tetrahedra form " + std::to_string(bodies) +
                     " separate bodies (a deformable block is one body)");
  // Zones that overlap fill more than their boundary encloses (the volume
  // inside the outward boundary faces, by the divergence theorem).
  const auto P = [&](unsigned int g)
  { return Vec3(mesh.position[3 * g], mesh.position[3 * g + 1], mesh.position[3 * g + 2]); };
  double filled = 0.0, enclosed = 0.0;
  for (const auto& t : mesh.zone_gridpoint)
    filled += std::abs(signed_volume(P(t[0]), P(t[1]), P(t[2]), P(t[3])));
  const Vec3 o = P(0); // near the body, for round-off
  for (const auto& f : mesh.face_gridpoint)
    enclosed += (P(f[0]) - o).dot((P(f[1]) - o).cross(P(f[2]) - o)) / 6.0;
  if (!(std::abs(filled - enclosed) <= 1e-8 * filled))
    throw InputError(path + ": the tetrahedra overlap (they fill " + number(filled) +
                     " m^3, while the boundary of the body encloses " + number(enclosed) + " m^3)");
}

} // namespace

void append_tetrahedra(TetMesh& mesh, const dealii::Triangulation<3>& tria, unsigned int block)
{
  // The triangulation's vertices that cells use, numbered in the order the
  // cells meet them.
  std::vector<int> local(tria.n_vertices(), -1);
  std::vector<Vec3> points;
  std::vector<std::array<unsigned int, 4>> tets;
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
        local[v] = static_cast<int>(points.size());
        const auto& x = tria.get_vertices()[v];
        points.emplace_back(x[0], x[1], x[2]);
      }
      t[i] = static_cast<unsigned int>(local[v]);
    }
    tets.push_back(t);
  }
  append_zones(mesh, points, std::move(tets), block);
}

void append_tetrahedra(TetMesh& mesh, const BlockTetrahedra& tetrahedra, unsigned int block)
{
  append_zones(mesh, tetrahedra.point, tetrahedra.tet, block);
}

TetMesh read_gmsh_block(const std::string& path, unsigned int block, MeshOrder order)
{
  std::ifstream in(path);
  if (!in)
    throw InputError(path + ": cannot open the mesh file");
  {
    // "$MeshFormat", then "version file-type data-size": file-type 1 is
    // gmsh's binary format, which deal.II's reader takes for broken text.
    std::string format, version;
    int file_type = 0;
    if (std::getline(in, format) && format.rfind("$MeshFormat", 0) == 0 && (in >> version) &&
        (in >> file_type) && file_type == 1)
      throw InputError(path + ": a binary gmsh file (format " + version +
                       "); save the mesh as ASCII (gmsh: without -bin, or Mesh.Binary = 0)");
    in.clear();
    in.seekg(0);
  }
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
  check_one_closed_body(mesh, path);
  order_for_locality(mesh, order);
  return mesh;
}

namespace
{
/// The radius-ratio figures of the report.
void measure_quality(const TetMesh& mesh, MeshReport& report)
{
  const auto P = [&](unsigned int g)
  { return Vec3(mesh.position[3 * g], mesh.position[3 * g + 1], mesh.position[3 * g + 2]); };
  const unsigned int n = mesh.n_zones();
  if (n == 0)
    return;
  std::vector<double> q(n);
  std::map<unsigned int, unsigned int> poor_in_block;
  report.quality_min = 2.0;
  for (unsigned int z = 0; z < n; ++z)
  {
    const auto& t = mesh.zone_gridpoint[z];
    q[z] = radius_ratio(P(t[0]), P(t[1]), P(t[2]), P(t[3]));
    if (q[z] < report.quality_min)
    {
      report.quality_min = q[z];
      report.worst_zone = z;
      report.worst_block = mesh.zone_block[z];
    }
    if (q[z] < 0.1)
    {
      ++report.poor_zones;
      ++poor_in_block[mesh.zone_block[z]];
    }
  }
  for (const auto& [block, count] : poor_in_block)
    report.poor_blocks.emplace_back(block, count);
  std::stable_sort(report.poor_blocks.begin(), report.poor_blocks.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  if (report.poor_blocks.size() > 20)
    report.poor_blocks.resize(20);
  std::nth_element(q.begin(), q.begin() + n / 100, q.end());
  report.quality_1 = q[n / 100];
  std::nth_element(q.begin(), q.begin() + n / 2, q.end());
  report.quality_median = q[n / 2];
}
} // namespace

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
  measure_quality(mesh, report);
  return report;
}

namespace
{
/// The zones of mesh_blocks, in the mesher's order (then ordered by
/// mesh_blocks).
TetMesh mesh_in_generator_order(const BlockModel& m, const std::vector<unsigned int>& which,
                                const EdgeLengthField& field, ZoneElement element,
                                ConvexMesher mesher, MPI_Comm comm)
{
  if (!(field.smallest() > 0.0))
    throw InputError("zone edge length must be positive");
  if (element == ZoneElement::tet10)
    throw InputError("internal: the mesher makes 4-node zones; 10-node zones are made from them "
                     "by make_quadratic");
  // Blocks that are not bricks go to the convex mesher together (fewer gmsh
  // calls); then every block is appended in the order asked.
  std::vector<unsigned int> general;
  std::vector<int> general_index(m.n_blocks(), -1);
  for (unsigned int b : which)
  {
    Box box;
    if (element == ZoneElement::hex_mixed && !is_axis_aligned_box(m, b, box))
      throw InputError("entry 'Element' in subsection 'Deformable': hex-mixed needs every "
                       "deformable block to be an axis-aligned brick, and block " +
                       std::to_string(b) + " (" +
                       std::to_string(m.face_start[b + 1] - m.face_start[b]) +
                       " faces) is not one; allowed: tet4 for blocks of other shapes");
    if (!is_axis_aligned_box(m, b, box))
    {
      general_index[b] = static_cast<int>(general.size());
      general.push_back(b);
    }
  }
  const EdgeLengthAt size = [&field](const Vec3& x) { return field.at(x); };
  int ranks = 1;
  if (comm != MPI_COMM_SELF)
    MPI_Comm_size(comm, &ranks);
  std::vector<BlockTetrahedra> meshed;
  if (ranks > 1)
  {
    std::vector<double> expected;
    for (unsigned int b : general)
      expected.push_back(count_zones(m, {b}, field));
    meshed = mesh_convex_blocks_on_ranks(m, general, size, mesher, expected, comm);
  }
  else
    meshed = mesh_convex_blocks_with(m, general, size, mesher);
  TetMesh mesh;
  for (unsigned int b : which)
  {
    if (general_index[b] >= 0)
    {
      BlockTetrahedra& t = meshed[general_index[b]];
      append_tetrahedra(mesh, t, b);
      t = BlockTetrahedra(); // free it as we go
      continue;
    }
    Box box;
    is_axis_aligned_box(m, b, box);
    const std::vector<unsigned int> n = brick_divisions(box, brick_edge(box, field));
    if (element == ZoneElement::hex_mixed)
    {
      append_hex_mixed_brick(mesh, box, {{n[0], n[1], n[2]}}, b);
      continue;
    }
    dealii::Triangulation<3> one;
    dealii::GridGenerator::subdivided_hyper_rectangle_with_simplices(
        one, n, Point<3>(box.lo.x(), box.lo.y(), box.lo.z()),
        Point<3>(box.hi.x(), box.hi.y(), box.hi.z()));
    append_tetrahedra(mesh, one, b);
  }
  return mesh;
}

template <typename Order>
TetMesh mesh_and_order(const BlockModel& m, const std::vector<unsigned int>& which,
                       const EdgeLengthField& field, MeshReport& report, ZoneElement element,
                       const Order& order, ConvexMesher mesher, MPI_Comm comm)
{
  TetMesh mesh = mesh_in_generator_order(m, which, field, element, mesher, comm);
  order_for_locality(mesh, order);
  report = measure_mesh(mesh);
  return mesh;
}
} // namespace

TetMesh mesh_blocks(const BlockModel& m, const std::vector<unsigned int>& which,
                    const EdgeLengthField& field, MeshReport& report, ZoneElement element,
                    MeshOrder order, ConvexMesher mesher, MPI_Comm comm)
{
  return mesh_and_order(m, which, field, report, element, order, mesher, comm);
}

TetMesh mesh_blocks(const BlockModel& m, const std::vector<unsigned int>& which,
                    const EdgeLengthField& field, MeshReport& report, ZoneElement element,
                    const BlockMeshOrder& order, ConvexMesher mesher, MPI_Comm comm)
{
  return mesh_and_order(m, which, field, report, element, order, mesher, comm);
}

double count_zones(const BlockModel& m, const std::vector<unsigned int>& which,
                   const EdgeLengthField& field)
{
  double zones = 0.0;
  for (unsigned int b : which)
  {
    Box box;
    if (is_axis_aligned_box(m, b, box))
    {
      const double edge = brick_edge(box, field);
      double hexahedra = 1.0;
      for (int d = 0; d < 3; ++d)
        hexahedra *= hexahedra_along(box.hi[d] - box.lo[d], edge);
      zones += 5.0 * hexahedra;
      continue;
    }
    // The regular tetrahedra that fill the block at the local edge length,
    // summed over a fan of tetrahedra from the centroid to the faces' fans
    // (each at the edge length at its own centroid); at least the fan.
    double regular = 0.0, fan = 0.0;
    const Vec3& c = m.centroid[b];
    for (unsigned int f = m.face_start[b]; f < m.face_start[b + 1]; ++f)
    {
      const unsigned int first = m.face_loop_start[f], n = m.face_loop_start[f + 1] - first;
      for (unsigned int k = 1; k + 1 < n; ++k)
      {
        const Vec3 &p = m.vertex[m.face_vertex[first]], &q = m.vertex[m.face_vertex[first + k]],
                   &r = m.vertex[m.face_vertex[first + k + 1]];
        regular += regular_tetrahedra_in(std::abs(signed_volume(p, q, r, c)),
                                         field.at(0.25 * (p + q + r + c)));
        fan += 1.0;
      }
    }
    zones += std::max(regular, fan);
  }
  return zones;
}

} // namespace talus
