#include <talus/base/exceptions.h>
#include <talus/zone/convex_block_mesher.h>

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

namespace talus
{

namespace
{
int sessions = 0; // GmshSession objects alive (gmsh's state is global)

double signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

/// Why gmsh failed, in one line.
std::string gmsh_reason(const std::exception* e)
{
  std::string why;
  try
  {
    gmsh::logger::getLastError(why);
  }
  catch (...)
  {
  }
  if (why.empty() && e != nullptr)
    why = e->what();
  std::replace(why.begin(), why.end(), '\n', ' ');
  return why.empty() ? std::string("gmsh gave no reason") : why;
}

/// The closest point to p on the segment a-b.
Vec3 onto_segment(const Vec3& p, const Vec3& a, const Vec3& b)
{
  const Vec3 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return a + t * ab;
}
} // namespace

GmshSession::GmshSession()
{
  if (sessions++ > 0)
    return;
  owner = true;
  gmsh::initialize(0, nullptr, false);
  // Quiet, and errors as exceptions rather than messages.
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::option::setNumber("General.Verbosity", 0);
  gmsh::option::setNumber("General.AbortOnError", 2);
  // One thread everywhere: HXT's parallel insertion makes a different mesh
  // from run to run, and a model must mesh the same every time.
  gmsh::option::setNumber("General.NumThreads", 1);
  for (const char* stage : {"Mesh.MaxNumThreads1D", "Mesh.MaxNumThreads2D", "Mesh.MaxNumThreads3D"})
    gmsh::option::setNumber(stage, 1);
  // Sizes come from the callback only (not from the points or curvature).
  gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
  gmsh::option::setNumber("Mesh.Algorithm", 6);    // frontal-Delaunay faces
  // gmsh's Delaunay volume mesher (1), not HXT (10): HXT (gmsh 4.8) gives
  // the same block a different mesh from one call to the next in a process
  // (371, 361, 362 zones for one tetrahedron; convex_block_mesher_04), so a
  // run's answer would depend on what was meshed before.
  gmsh::option::setNumber("Mesh.Algorithm3D", 1);
  gmsh::option::setNumber("Mesh.Optimize", 1);     // gmsh's sliver removal
}

GmshSession::~GmshSession()
{
  --sessions;
  if (owner)
    gmsh::finalize();
}

double radius_ratio(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
  const double v = std::abs(signed_volume(a, b, c, d));
  const double area = 0.5 * ((b - a).cross(c - a).norm() + (b - a).cross(d - a).norm() +
                             (c - a).cross(d - a).norm() + (c - b).cross(d - b).norm());
  if (!(v > 0.0) || !(area > 0.0))
    return 0.0;
  const double r_in = 3.0 * v / area;
  // Circumradius: |A|/(12 V) with A the sum of the squared edge lengths
  // times the cross products (Cayley–Menger in vector form).
  const Vec3 u = b - a, w = c - a, t = d - a;
  const Vec3 centre_offset =
      (u.squaredNorm() * w.cross(t) + w.squaredNorm() * t.cross(u) + t.squaredNorm() * u.cross(w)) /
      (2.0 * u.dot(w.cross(t)));
  const double r_circ = centre_offset.norm();
  return 3.0 * r_in / r_circ;
}

double regular_tetrahedra_in(double volume, double edge_length)
{
  return volume / (edge_length * edge_length * edge_length * std::sqrt(2.0) / 12.0);
}

PolyhedralSurface block_surface(const BlockModel& m, unsigned int b)
{
  PolyhedralSurface s;
  const unsigned int v0 = m.vertex_start[b];
  s.vertex.assign(m.vertex.begin() + v0, m.vertex.begin() + m.vertex_start[b + 1]);
  for (unsigned int f = m.face_start[b]; f < m.face_start[b + 1]; ++f)
  {
    std::vector<unsigned int> loop;
    for (unsigned int k = m.face_loop_start[f]; k < m.face_loop_start[f + 1]; ++k)
      loop.push_back(m.face_vertex[k] - v0);
    s.face.push_back(std::move(loop));
    s.face_normal.push_back(m.face_normal[f]);
  }
  return s;
}

namespace
{
/// What one body became in gmsh's model: its entity tags.
struct BodyEntities
{
  int first_point; ///< corner v is point first_point + v
  std::vector<std::pair<unsigned int, unsigned int>> line_ends; ///< corners, per line
  int first_line;                                               ///< line l is tag first_line + l
  std::vector<int> surfaces;                                    ///< one per face, in face order
  int volume;
};

/// Adds a body to gmsh's current model (built-in kernel), with tags after
/// those already used.
BodyEntities add_body(const PolyhedralSurface& body, int& next_point, int& next_line)
{
  BodyEntities e;
  e.first_point = next_point;
  for (const Vec3& p : body.vertex)
    gmsh::model::geo::addPoint(p.x(), p.y(), p.z(), 0.0, next_point++);
  e.first_line = next_line;
  std::map<std::pair<unsigned int, unsigned int>, int> line_of;
  for (const std::vector<unsigned int>& face : body.face)
  {
    std::vector<int> loop;
    const std::size_t n = face.size();
    for (std::size_t k = 0; k < n; ++k)
    {
      const unsigned int p = face[k], q = face[(k + 1) % n];
      const auto key = std::minmax(p, q);
      auto it = line_of.find(key);
      if (it == line_of.end())
      {
        gmsh::model::geo::addLine(e.first_point + static_cast<int>(key.first),
                                  e.first_point + static_cast<int>(key.second), next_line);
        e.line_ends.push_back(key);
        it = line_of.emplace(key, next_line++).first;
      }
      loop.push_back(p == key.first ? it->second : -it->second);
    }
    e.surfaces.push_back(gmsh::model::geo::addPlaneSurface({gmsh::model::geo::addCurveLoop(loop)}));
  }
  e.volume = gmsh::model::geo::addVolume({gmsh::model::geo::addSurfaceLoop(e.surfaces)});
  return e;
}

/// The zones gmsh made in one body's volume, with gridpoints put back
/// exactly on the corner, edge or face gmsh classified them on. Each node
/// is read once, from the one entity it lies on (its coordinates are the
/// same whichever call returns them), and local numbers follow the order in
/// which the zones first name the nodes.
BlockTetrahedra take_body(const PolyhedralSurface& body, const BodyEntities& e)
{
  BlockTetrahedra out;
  std::vector<std::size_t> elements, corners, tags;
  std::vector<double> xyz, parametric;
  gmsh::model::mesh::getElementsByType(4, elements, corners, e.volume); // 4-node tetrahedra
  if (corners.empty())
    return out;
  // gmsh numbers a model's nodes from 1 up, so a dense table from node tag
  // to local number is small (a std::map here cost 1-2 % of the meshing).
  const auto [lowest, highest] = std::minmax_element(corners.begin(), corners.end());
  const std::size_t first_tag = *lowest;
  constexpr unsigned int unused = ~0u;
  std::vector<unsigned int> local(*highest - first_tag + 1, unused);
  unsigned int n_points = 0;
  out.tet.resize(elements.size());
  for (std::size_t z = 0; z < elements.size(); ++z)
    for (int i = 0; i < 4; ++i)
    {
      unsigned int& number = local[corners[4 * z + i] - first_tag];
      if (number == unused)
        number = n_points++;
      out.tet[z][i] = number;
    }
  out.point.resize(n_points);
  const auto take = [&](int dim, int tag, const auto& onto)
  {
    gmsh::model::mesh::getNodes(tags, xyz, parametric, dim, tag, false, false);
    for (std::size_t k = 0; k < tags.size(); ++k)
    {
      if (tags[k] < first_tag || tags[k] - first_tag >= local.size())
        continue;
      const unsigned int number = local[tags[k] - first_tag];
      if (number != unused)
        out.point[number] = onto(Vec3(xyz[3 * k], xyz[3 * k + 1], xyz[3 * k + 2]));
    }
  };
  take(3, e.volume, [](const Vec3& p) { return p; });
  for (std::size_t v = 0; v < body.vertex.size(); ++v)
    take(0, e.first_point + static_cast<int>(v), [&](const Vec3&) { return body.vertex[v]; });
  for (std::size_t l = 0; l < e.line_ends.size(); ++l)
  {
    const Vec3 &a = body.vertex[e.line_ends[l].first], &c = body.vertex[e.line_ends[l].second];
    take(1, e.first_line + static_cast<int>(l),
         [&](const Vec3& p) { return onto_segment(p, a, c); });
  }
  for (std::size_t f = 0; f < e.surfaces.size(); ++f)
  {
    const Vec3& n = body.face_normal[f];
    const Vec3& on_plane = body.vertex[body.face[f][0]];
    take(2, e.surfaces[f], [&](const Vec3& p) -> Vec3 { return p - n * n.dot(p - on_plane); });
  }
  for (auto& t : out.tet)
    if (signed_volume(out.point[t[0]], out.point[t[1]], out.point[t[2]], out.point[t[3]]) < 0.0)
      std::swap(t[1], t[2]);
  return out;
}

/// Meshes the bodies in one gmsh model; throws InputError naming `what` if
/// gmsh fails.
std::vector<BlockTetrahedra> mesh_batch(const std::vector<PolyhedralSurface>& bodies,
                                        const EdgeLengthAt& size, const std::string& what)
{
  std::vector<BlockTetrahedra> out;
  try
  {
    gmsh::model::add("bodies");
    int next_point = 1, next_line = 1;
    std::vector<BodyEntities> entities;
    for (const PolyhedralSurface& body : bodies)
      entities.push_back(add_body(body, next_point, next_line));
    gmsh::model::geo::synchronize();
    gmsh::model::mesh::setSizeCallback([&size](int, int, double x, double y, double z)
                                       { return size(Vec3(x, y, z)); });
    gmsh::model::mesh::generate(3);
    for (std::size_t i = 0; i < bodies.size(); ++i)
    {
      out.push_back(take_body(bodies[i], entities[i]));
      if (out.back().tet.empty())
        throw std::runtime_error("gmsh made no zones");
    }
    gmsh::model::mesh::removeSizeCallback();
    gmsh::model::remove();
  }
  catch (const std::exception& e)
  {
    const std::string why = gmsh_reason(&e);
    gmsh::clear();
    throw InputError(what + " could not be meshed: " + why);
  }
  catch (...)
  {
    const std::string why = gmsh_reason(nullptr);
    gmsh::clear();
    throw InputError(what + " could not be meshed: " + why);
  }
  return out;
}
} // namespace

BlockTetrahedra mesh_polyhedron(const PolyhedralSurface& body, const EdgeLengthAt& size)
{
  GmshSession session;
  return std::move(mesh_batch({body}, size, "the body")[0]);
}

BlockTetrahedra mesh_convex_block(const BlockModel& m, unsigned int b, const EdgeLengthAt& size)
{
  GmshSession session;
  return std::move(mesh_batch({block_surface(m, b)}, size, "block " + std::to_string(b))[0]);
}

std::vector<BlockTetrahedra> mesh_convex_blocks(const BlockModel& m,
                                                const std::vector<unsigned int>& blocks,
                                                const EdgeLengthAt& size, std::size_t batch)
{
  GmshSession session;
  std::vector<BlockTetrahedra> out;
  out.reserve(blocks.size());
  for (std::size_t first = 0; first < blocks.size(); first += batch)
  {
    const std::size_t count = std::min(batch, blocks.size() - first);
    std::vector<PolyhedralSurface> bodies;
    for (std::size_t i = first; i < first + count; ++i)
      bodies.push_back(block_surface(m, blocks[i]));
    std::vector<BlockTetrahedra> some;
    try
    {
      some = mesh_batch(bodies, size, "block " + std::to_string(blocks[first]));
    }
    catch (const InputError&)
    {
      // Find the block gmsh cannot mesh, one at a time.
      some.clear();
      for (std::size_t i = first; i < first + count; ++i)
        some.push_back(mesh_convex_block(m, blocks[i], size));
    }
    for (auto& t : some)
      out.push_back(std::move(t));
  }
  return out;
}

} // namespace talus
