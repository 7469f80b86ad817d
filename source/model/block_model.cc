#include <talus/geometry/mass_properties.h>
#include <talus/model/block_model.h>

#include <algorithm>

namespace talus
{

unsigned int BlockModel::add_block(const ConvexPolyhedron& shape, unsigned int group_id)
{
  const unsigned int first_vertex = n_vertices();
  vertex.insert(vertex.end(), shape.vertices().begin(), shape.vertices().end());
  vertex_start.push_back(n_vertices());
  for (unsigned int f = 0; f < shape.n_faces(); ++f)
  {
    for (unsigned int k = 0; k < shape.face_size(f); ++k)
      face_vertex.push_back(first_vertex + shape.face_vertex(f, k));
    face_loop_start.push_back(static_cast<unsigned int>(face_vertex.size()));
    face_normal.push_back(shape.face_plane(f).normal);
    face_origin.push_back(shape.face_origin(f));
  }
  face_start.push_back(n_faces());

  const MassProperties m = compute_mass_properties(shape);
  volume.push_back(m.volume);
  centroid.push_back(m.centroid);
  const auto& I = m.inertia;
  inertia.push_back({{I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(1, 2), I(2, 0)}});
  group.push_back(group_id);
  return n_blocks() - 1;
}

BlockModel BlockModel::subset(const std::vector<unsigned int>& blocks) const
{
  BlockModel out;
  out.group_names = group_names;
  for (unsigned int b : blocks)
  {
    const unsigned int v0 = vertex_start[b], first = out.n_vertices();
    out.vertex.insert(out.vertex.end(), vertex.begin() + v0, vertex.begin() + vertex_start[b + 1]);
    out.vertex_start.push_back(out.n_vertices());
    for (unsigned int f = face_start[b]; f < face_start[b + 1]; ++f)
    {
      for (unsigned int k = face_loop_start[f]; k < face_loop_start[f + 1]; ++k)
        out.face_vertex.push_back(face_vertex[k] - v0 + first);
      out.face_loop_start.push_back(static_cast<unsigned int>(out.face_vertex.size()));
      out.face_normal.push_back(face_normal[f]);
      out.face_origin.push_back(face_origin[f]);
      if (!face_corner_share.empty())
        out.face_corner_share.push_back(face_corner_share[f]);
    }
    out.face_start.push_back(out.n_faces());
    out.volume.push_back(volume[b]);
    out.centroid.push_back(centroid[b]);
    out.inertia.push_back(inertia[b]);
    out.group.push_back(group[b]);
  }
  return out;
}

ConvexPolyhedron BlockModel::polyhedron(unsigned int b) const
{
  const unsigned int v0 = vertex_start[b];
  std::vector<Vec3> v(vertex.begin() + v0, vertex.begin() + vertex_start[b + 1]);
  std::vector<unsigned int> starts{0}, loops;
  for (unsigned int f = face_start[b]; f < face_start[b + 1]; ++f)
  {
    for (unsigned int k = face_loop_start[f]; k < face_loop_start[f + 1]; ++k)
      loops.push_back(face_vertex[k] - v0);
    starts.push_back(static_cast<unsigned int>(loops.size()));
  }
  return ConvexPolyhedron(std::move(v), std::move(starts), std::move(loops));
}

unsigned int BlockModel::group_index(const std::string& name)
{
  const auto it = std::find(group_names.begin(), group_names.end(), name);
  if (it != group_names.end())
    return static_cast<unsigned int>(it - group_names.begin());
  group_names.push_back(name);
  return static_cast<unsigned int>(group_names.size()) - 1;
}

double BlockModel::total_volume() const
{
  double sum = 0.0;
  for (double v : volume)
    sum += v;
  return sum;
}

} // namespace talus
