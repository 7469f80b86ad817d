#include <talus/zone/zone_surface.h>

#include <algorithm>
#include <array>
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

std::vector<int> zone_face_origins(const BlockModel& m, const TetMesh& mesh)
{
  const auto P = [&](unsigned int g)
  { return Vec3(mesh.position[3 * g], mesh.position[3 * g + 1], mesh.position[3 * g + 2]); };
  const auto origin = [&](const std::array<unsigned int, 3>& t)
  {
    const Vec3 normal = (P(t[1]) - P(t[0])).cross(P(t[2]) - P(t[0])).normalized();
    return face_origin_of_triangle(m, mesh.gridpoint_block[t[0]], normal,
                                   (P(t[0]) + P(t[1]) + P(t[2])) / 3.0);
  };
  std::vector<int> origins;
  for (const auto& t : mesh.face_gridpoint)
    origins.push_back(origin(t));
  for (const auto& t : mesh.second_overlay_face_gridpoint)
    origins.push_back(origin(t));
  return origins;
}

namespace
{

double triangle_area(const TetMesh& mesh, unsigned int a, unsigned int b, unsigned int c)
{
  const auto P = [&](unsigned int g)
  { return Vec3(mesh.position[3 * g], mesh.position[3 * g + 1], mesh.position[3 * g + 2]); };
  return 0.5 * (P(b) - P(a)).cross(P(c) - P(a)).norm();
}

/// Per face of the new block model (`mesh_face_of`: its boundary face of
/// the mesh, for deformable blocks), the share of its area that each corner
/// carries in contacts. A contact spring at a gridpoint must stand for the
/// area whose load the zones would take there: a third of each triangle of
/// 4-node zones. A hexahedral zone is two overlays, each taking half a
/// load, and the overlays split a boundary quadrilateral p q r s along
/// opposite diagonals (p-r: triangles pqr, prs; q-s: pqs, qrs), so a corner
/// stands for half the thirds of both splits: a quarter of a square each,
/// where the first overlay's triangles alone (the block's faces) would
/// give the diagonal's corners a third and the others a sixth. Those
/// areas are put on the first overlay's triangles: q and s wholly on the
/// triangle that holds them, p and r on both in proportion to area.
std::vector<std::array<double, 3>>
contact_corner_shares(const TetMesh& mesh, unsigned int n_faces,
                      const std::map<unsigned int, unsigned int>& mesh_face_of)
{
  std::vector<std::array<double, 3>> share(n_faces, {{1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0}});
  if (mesh.quadratic())
  {
    // 10-node zones: a uniform load on a 6-node face goes wholly to its
    // midpoints, a third of the face each; of the face's four
    // sub-triangles, a corner one gives half its area to each of its two
    // midpoints and nothing to the zone vertex, the middle one a third to
    // each (as the face loads of the deformable solver).
    std::vector<char> is_vertex(mesh.n_gridpoints(), 0);
    for (const auto& t : mesh.zone_gridpoint)
      for (unsigned int g : t)
        is_vertex[g] = 1;
    for (const auto& [face, f] : mesh_face_of)
      for (int j = 0; j < 3; ++j)
        if (is_vertex[mesh.face_gridpoint[f][j]])
        {
          share[face] = {{0.5, 0.5, 0.5}};
          share[face][j] = 0.0;
        }
    return share;
  }
  if (mesh.n_hexes() == 0)
    return share;
  // The two first-overlay triangles of each boundary quadrilateral: those
  // of one hexahedron with the same normal.
  std::map<std::pair<unsigned int, std::array<long, 3>>, std::vector<unsigned int>> quads;
  for (const auto& [face, f] : mesh_face_of)
  {
    const unsigned int z = mesh.face_zone[f];
    const auto after = std::upper_bound(mesh.hex_first_zone.begin(), mesh.hex_first_zone.end(), z);
    if (after == mesh.hex_first_zone.begin() ||
        z >= *(after - 1) + TetMesh::tets_per_hex) // not a hexahedral zone
      continue;
    const auto& t = mesh.face_gridpoint[f];
    const auto P = [&](unsigned int g)
    { return Vec3(mesh.position[3 * g], mesh.position[3 * g + 1], mesh.position[3 * g + 2]); };
    const Vec3 n = (P(t[1]) - P(t[0])).cross(P(t[2]) - P(t[0])).normalized();
    const std::array<long, 3> key{
        {std::lround(1e6 * n[0]), std::lround(1e6 * n[1]), std::lround(1e6 * n[2])}};
    quads[{static_cast<unsigned int>(after - mesh.hex_first_zone.begin() - 1), key}].push_back(
        face);
  }
  for (const auto& [key, faces] : quads)
  {
    if (faces.size() != 2)
      continue;
    const auto& t1 = mesh.face_gridpoint[mesh_face_of.at(faces[0])];
    const auto& t2 = mesh.face_gridpoint[mesh_face_of.at(faces[1])];
    // q: the corner of t1 not in t2; s: that of t2 not in t1.
    int iq = -1, is = -1;
    for (int j = 0; j < 3; ++j)
    {
      if (std::find(t2.begin(), t2.end(), t1[j]) == t2.end())
        iq = j;
      if (std::find(t1.begin(), t1.end(), t2[j]) == t1.end())
        is = j;
    }
    if (iq < 0 || is < 0)
      continue;
    const unsigned int q = t1[iq], s = t2[is], p = t1[(iq + 1) % 3], r = t1[(iq + 2) % 3];
    const double a1 = triangle_area(mesh, p, q, r), a2 = triangle_area(mesh, p, r, s);
    const double a3 = triangle_area(mesh, p, q, s), a4 = triangle_area(mesh, q, r, s);
    const auto corner = [](double mine, double other_split)
    { return 0.5 * (mine + other_split) / 3.0; };
    const double area_p = corner(a1 + a2, a3), area_r = corner(a1 + a2, a4);
    const double area_q = corner(a1, a3 + a4), area_s = corner(a2, a3 + a4);
    for (int k = 0; k < 2; ++k)
    {
      const auto& t = k == 0 ? t1 : t2;
      const double a = k == 0 ? a1 : a2;
      std::array<double, 3>& w = share[faces[k]];
      for (int j = 0; j < 3; ++j)
        w[j] = t[j] == p   ? area_p / (a1 + a2)
               : t[j] == r ? area_r / (a1 + a2)
               : t[j] == q ? area_q / a
                           : area_s / a;
    }
  }
  return share;
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
  std::map<unsigned int, unsigned int> mesh_face_of; // face of `out` -> boundary face of the mesh
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
        mesh_face_of[out.n_faces()] = f;
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
  out.face_corner_share = contact_corner_shares(mesh, out.n_faces(), mesh_face_of);
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
