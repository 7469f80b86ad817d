// CGAL Mesh_3 on one convex block (benchmark only; see cgal_block_mesher.h).
// The block's polygon faces are fanned into triangles of a Surface_mesh; the
// domain (Polyhedral_mesh_domain_with_features_3, as deal.II's
// GridGenerator::surface_mesh_to_volumetric_mesh uses) protects the block's
// edges by balls so that its corners and edges stay in the mesh.

#include "cgal_block_mesher.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polyhedral_mesh_domain_with_features_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/make_mesh_3.h>

#include <cmath>
#include <stdexcept>
#include <unordered_map>

namespace talus
{

namespace
{
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Surface = CGAL::Surface_mesh<Kernel::Point_3>;
using Domain = CGAL::Polyhedral_mesh_domain_with_features_3<Kernel, Surface>;
using Triangulation = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using Complex = CGAL::Mesh_complex_3_in_triangulation_3<Triangulation, Domain::Corner_index,
                                                        Domain::Curve_index>;
using Criteria = CGAL::Mesh_criteria_3<Triangulation>;
} // namespace

CgalCriteria cgal_criteria_for(double h)
{
  CgalCriteria c;
  c.edge_size = h;
  c.facet_size = h / std::sqrt(3.0);
  c.cell_size = h * std::sqrt(6.0) / 4.0;
  c.facet_distance = 0.01 * h;
  return c;
}

BlockTetrahedra cgal_mesh_convex_block(const BlockModel& m, unsigned int b, const CgalCriteria& c)
{
  Surface surface;
  const unsigned int v0 = m.vertex_start[b];
  std::vector<Surface::Vertex_index> corner;
  for (unsigned int v = v0; v < m.vertex_start[b + 1]; ++v)
    corner.push_back(surface.add_vertex({m.vertex[v].x(), m.vertex[v].y(), m.vertex[v].z()}));
  for (unsigned int f = m.face_start[b]; f < m.face_start[b + 1]; ++f)
  {
    // Loops are counter-clockwise seen from outside: a fan keeps that.
    const unsigned int first = m.face_loop_start[f], n = m.face_loop_start[f + 1] - first;
    for (unsigned int k = 1; k + 1 < n; ++k)
      if (surface.add_face(corner[m.face_vertex[first] - v0], corner[m.face_vertex[first + k] - v0],
                           corner[m.face_vertex[first + k + 1] - v0]) == Surface::null_face())
        throw std::runtime_error("block " + std::to_string(b) +
                                 ": its faces are no closed surface");
  }

  Domain domain(surface);
  domain.detect_features(c.feature_angle);
  namespace p = CGAL::parameters;
  const Criteria criteria(p::edge_size = c.edge_size, p::facet_angle = c.facet_angle,
                          p::facet_size = c.facet_size, p::facet_distance = c.facet_distance,
                          p::cell_radius_edge_ratio = c.cell_radius_edge_ratio,
                          p::cell_size = c.cell_size);
  const Complex complex =
      c.optimise ? CGAL::make_mesh_3<Complex>(domain, criteria)
                 : CGAL::make_mesh_3<Complex>(domain, criteria, p::no_perturb(), p::no_exude());

  BlockTetrahedra out;
  std::unordered_map<const void*, unsigned int> local;
  for (auto cell = complex.cells_in_complex_begin(); cell != complex.cells_in_complex_end(); ++cell)
  {
    std::array<unsigned int, 4> t;
    for (int i = 0; i < 4; ++i)
    {
      const auto v = cell->vertex(i);
      const auto [it, fresh] = local.emplace(&*v, static_cast<unsigned int>(out.point.size()));
      if (fresh)
      {
        const auto& x = v->point();
        out.point.emplace_back(CGAL::to_double(x.x()), CGAL::to_double(x.y()),
                               CGAL::to_double(x.z()));
      }
      t[i] = it->second;
    }
    const Vec3 &a = out.point[t[0]], &p1 = out.point[t[1]], &p2 = out.point[t[2]],
               &p3 = out.point[t[3]];
    if ((p1 - a).dot((p2 - a).cross(p3 - a)) < 0.0)
      std::swap(t[1], t[2]);
    out.tet.push_back(t);
  }
  if (out.tet.empty())
    throw std::runtime_error("block " + std::to_string(b) + ": CGAL made no zones");
  return out;
}

} // namespace talus
