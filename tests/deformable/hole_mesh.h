#pragma once

// A quarter of a plane-strain slab with a circular hole at the origin, for
// the verification tests of deformable blocks around openings: x >= 0,
// y >= 0, 0 <= z <= thickness, hole radius a, outer boundary a circle of
// radius R or the square [0, R]^2. The quadrilaterals of the plane are
// bounded by n_theta equal sectors and n_r rings spaced geometrically along
// each ray from the centre (so that the zones stay about as long as they are
// wide, small at the wall and large far out); deal.II extrudes them into one
// layer of hexahedra and splits each into 24 tetrahedra (symmetric in z, no
// preferred diagonal), which become the zones of block 0.

#include <talus/solver/deformable_solver.h>
#include <talus/zone/block_mesher.h>
#include <talus/zone/tet_mesh.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <cmath>
#include <vector>

struct HoleMesh
{
  double a = 1.0;         ///< hole radius, m
  double R = 20.0;        ///< outer radius or half-width of the square, m
  double thickness = 0.1; ///< slab thickness, m
  bool square = false;    ///< outer boundary the square [0, R]^2 instead of a circle
  unsigned int n_theta = 8, n_r = 16;

  /// Distance from the centre to the outer boundary along angle theta.
  double outer(double theta) const
  {
    return square ? R / std::max(std::cos(theta), std::sin(theta)) : R;
  }

  talus::TetMesh build() const
  {
    std::vector<dealii::Point<2>> vertices;
    for (unsigned int j = 0; j <= n_theta; ++j)
    {
      const double theta = 0.5 * M_PI * j / n_theta;
      for (unsigned int i = 0; i <= n_r; ++i)
      {
        const double r = a * std::pow(outer(theta) / a, double(i) / n_r);
        // Exact zeros on the symmetry planes, so that regions find them.
        vertices.emplace_back(j == n_theta ? 0.0 : r * std::cos(theta),
                              j == 0 ? 0.0 : r * std::sin(theta));
      }
    }
    std::vector<dealii::CellData<2>> cells;
    const auto id = [this](unsigned int i, unsigned int j) { return j * (n_r + 1) + i; };
    for (unsigned int j = 0; j < n_theta; ++j)
      for (unsigned int i = 0; i < n_r; ++i)
      {
        dealii::CellData<2> cell;
        // deal.II's lexicographic order: (i,j), (i+1,j), (i,j+1), (i+1,j+1).
        cell.vertices[0] = id(i, j);
        cell.vertices[1] = id(i + 1, j);
        cell.vertices[2] = id(i, j + 1);
        cell.vertices[3] = id(i + 1, j + 1);
        cells.push_back(cell);
      }
    dealii::Triangulation<2> plane;
    plane.create_triangulation(vertices, cells, dealii::SubCellData());
    dealii::Triangulation<3> slab, tets;
    dealii::GridGenerator::extrude_triangulation(plane, 2, thickness, slab);
    dealii::GridGenerator::convert_hypercube_to_simplex_mesh(slab, tets);
    talus::TetMesh mesh;
    talus::append_tetrahedra(mesh, tets, 0);
    return mesh;
  }
};

/// Rollers of a quarter-symmetric slab of thickness t (plane strain): the
/// planes x = 0 and y = 0 held normally, both z faces held in z. `eps` is
/// the capture width (m), `big` a length beyond the model.
inline std::vector<talus::GridpointCondition> plane_strain_rollers(double t, double eps, double big)
{
  using talus::Box;
  using talus::Vec3;
  talus::GridpointCondition x_roller, y_roller, z_low, z_high;
  x_roller.region = Box{Vec3(-eps, -big, -big), Vec3(eps, big, big)};
  x_roller.held[1] = x_roller.held[2] = false;
  y_roller.region = Box{Vec3(-big, -eps, -big), Vec3(big, eps, big)};
  y_roller.held[0] = y_roller.held[2] = false;
  z_low.region = Box{Vec3(-big, -big, -eps), Vec3(big, big, eps)};
  z_low.held[0] = z_low.held[1] = false;
  z_high.region = Box{Vec3(-big, -big, t - eps), Vec3(big, big, t + eps)};
  z_high.held[0] = z_high.held[1] = false;
  return {x_roller, y_roller, z_low, z_high};
}
