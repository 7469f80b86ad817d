#include <talus/zone/zone_surface.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace talus
{

namespace
{
/// The origin of the face of block b that a boundary triangle of its zones
/// (outward `normal`, centre `centre`) lies on: the face of the same normal
/// whose plane passes through the centre (0 when none does).
int face_origin_of_triangle(const BlockModel& m, unsigned int b, const Vec3& normal,
                            const Vec3& centre)
{
  const double tolerance = 1e-6 * std::cbrt(m.volume[b]);
  for (unsigned int f = m.face_start[b]; f < m.face_start[b + 1]; ++f)
  {
    const Vec3& on_face = m.vertex[m.face_vertex[m.face_loop_start[f]]];
    if (m.face_normal[f].dot(normal) > 1.0 - 1e-6 &&
        std::abs(m.face_normal[f].dot(centre - on_face)) < tolerance)
      return m.face_origin[f];
  }
  return 0;
}
} // namespace

std::vector<int> use_zone_surfaces(BlockModel& m, const TetMesh& mesh)
{
  // Boundary triangles of each deformable block.
  std::map<unsigned int, std::vector<unsigned int>> faces_of;
  for (unsigned int f = 0; f < mesh.n_faces(); ++f)
    faces_of[mesh.zone_block[mesh.face_zone[f]]].push_back(f);

  BlockModel out;
  out.group_names = m.group_names;
  std::vector<int> vertex_gridpoint;
  for (unsigned int b = 0; b < m.n_blocks(); ++b)
  {
    const auto it = faces_of.find(b);
    const unsigned int first_vertex = out.n_vertices();
    if (it == faces_of.end())
    {
      // Rigid: as it was.
      for (unsigned int v = m.vertex_start[b]; v < m.vertex_start[b + 1]; ++v)
      {
        out.vertex.push_back(m.vertex[v]);
        vertex_gridpoint.push_back(-1);
      }
      for (unsigned int f = m.face_start[b]; f < m.face_start[b + 1]; ++f)
      {
        for (unsigned int k = m.face_loop_start[f]; k < m.face_loop_start[f + 1]; ++k)
          out.face_vertex.push_back(m.face_vertex[k] - m.vertex_start[b] + first_vertex);
        out.face_loop_start.push_back(static_cast<unsigned int>(out.face_vertex.size()));
        out.face_normal.push_back(m.face_normal[f]);
        out.face_origin.push_back(m.face_origin[f]);
      }
    }
    else
    {
      std::map<unsigned int, unsigned int> local; // gridpoint -> vertex
      for (unsigned int f : it->second)
      {
        for (unsigned int g : mesh.face_gridpoint[f])
        {
          auto [pos, fresh] = local.emplace(g, out.n_vertices());
          if (fresh)
          {
            out.vertex.emplace_back(mesh.position[3 * g], mesh.position[3 * g + 1],
                                    mesh.position[3 * g + 2]);
            vertex_gridpoint.push_back(static_cast<int>(g));
          }
          out.face_vertex.push_back(pos->second);
        }
        out.face_loop_start.push_back(static_cast<unsigned int>(out.face_vertex.size()));
        const auto& t = mesh.face_gridpoint[f];
        const auto P = [&](unsigned int g)
        { return Vec3(mesh.position[3 * g], mesh.position[3 * g + 1], mesh.position[3 * g + 2]); };
        const Vec3 normal = (P(t[1]) - P(t[0])).cross(P(t[2]) - P(t[0])).normalized();
        out.face_normal.push_back(normal);
        out.face_origin.push_back(face_origin_of_triangle(m, b, normal, (P(t[0]) + P(t[1]) + P(t[2])) / 3.0));
      }
    }
    out.vertex_start.push_back(out.n_vertices());
    out.face_start.push_back(out.n_faces());
    out.volume.push_back(m.volume[b]);
    if (it == faces_of.end())
      out.centroid.push_back(m.centroid[b]);
    else
    {
      // The mean of the surface gridpoints, which follow_gridpoints keeps
      // up to date (a deformable block's displacement is that point's).
      Vec3 sum = Vec3::Zero();
      for (unsigned int v = first_vertex; v < out.n_vertices(); ++v)
        sum += out.vertex[v];
      out.centroid.push_back(sum / double(out.n_vertices() - first_vertex));
    }
    out.inertia.push_back(m.inertia[b]);
    out.group.push_back(m.group[b]);
  }
  m = std::move(out);
  return vertex_gridpoint;
}

void follow_gridpoints(BlockModel& m, const std::vector<int>& vertex_gridpoint,
                       const std::vector<unsigned int>& deformable_blocks, const double* x,
                       std::vector<double>& moved)
{
  for (unsigned int b : deformable_blocks)
  {
    Vec3 sum = Vec3::Zero();
    double largest = 0.0;
    for (unsigned int v = m.vertex_start[b]; v < m.vertex_start[b + 1]; ++v)
    {
      const double* p = x + 3 * vertex_gridpoint[v];
      const Vec3 now(p[0], p[1], p[2]);
      largest = std::max(largest, (now - m.vertex[v]).cwiseAbs().maxCoeff());
      m.vertex[v] = now;
      sum += now;
    }
    moved[b] += largest;
    // The surface's vertex mean stands in for the centroid (moment arms of
    // a deformable block are never used).
    m.centroid[b] = sum / double(m.vertex_start[b + 1] - m.vertex_start[b]);
    for (unsigned int f = m.face_start[b]; f < m.face_start[b + 1]; ++f)
    {
      const unsigned int k = m.face_loop_start[f];
      const Vec3 n = (m.vertex[m.face_vertex[k + 1]] - m.vertex[m.face_vertex[k]])
                         .cross(m.vertex[m.face_vertex[k + 2]] - m.vertex[m.face_vertex[k]]);
      m.face_normal[f] = n.normalized();
    }
  }
}

} // namespace talus
