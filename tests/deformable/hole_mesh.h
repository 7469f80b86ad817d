#pragma once

// A quarter of a plane-strain slab with a circular hole at the origin, for
// the verification tests of deformable blocks around openings: x >= 0,
// y >= 0, 0 <= z <= thickness, hole radius a, outer boundary a circle of
// radius R or the square [0, R]^2. The quadrilaterals of the plane are
// bounded by n_theta equal sectors and n_r rings spaced geometrically along
// each ray from the centre (so that the zones stay about as long as they are
// wide, small at the wall and large far out); deal.II extrudes them into one
// layer of hexahedra and splits each into 24 tetrahedra (symmetric in z, no
// preferred diagonal), which become the zones of block 0. With `filled`,
// the hole holds zones too, on the same wall gridpoints (an O-grid: a
// square core and rings from it to the wall), to be excavated later.

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
  bool filled = false; ///< zones inside the hole too (n_theta even)

  /// The Kirsch tests' slab: the square [0, R]^2, n_theta sectors, rings
  /// as deep as the sectors are wide at the wall, two wall-zone widths
  /// thick.
  static HoleMesh square_slab(double a, double R, unsigned int n_theta)
  {
    HoleMesh hole;
    hole.a = a;
    hole.R = R;
    hole.square = true;
    hole.n_theta = n_theta;
    const double dtheta = 0.5 * M_PI / n_theta;
    hole.n_r = static_cast<unsigned int>(std::lround(std::log(R / a) / std::log(1.0 + dtheta)));
    hole.thickness = 2.0 * a * dtheta;
    return hole;
  }
  /// Ratio of the radii of neighbouring rings along a ray at theta = 0.
  double ring_ratio() const { return std::pow(R / a, 1.0 / n_r); }

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
    if (filled)
      fill_hole(vertices, cells);
    dealii::Triangulation<2> plane;
    plane.create_triangulation(vertices, cells, dealii::SubCellData());
    dealii::Triangulation<3> slab, tets;
    dealii::GridGenerator::extrude_triangulation(plane, 2, thickness, slab);
    dealii::GridGenerator::convert_hypercube_to_simplex_mesh(slab, tets);
    talus::TetMesh mesh;
    talus::append_tetrahedra(mesh, tets, 0);
    return mesh;
  }

  /// The O-grid inside the hole: a square core of side a/2 in h x h cells
  /// (h = n_theta / 2) whose two outer sides, n_theta segments, face the
  /// n_theta wall segments across `layers` rings of cells.
  void fill_hole(std::vector<dealii::Point<2>>& vertices,
                 std::vector<dealii::CellData<2>>& cells) const
  {
    const unsigned int n = n_theta, h = n / 2;
    const unsigned int layers = std::max(2u, static_cast<unsigned int>(std::lround(n / M_PI)));
    const double s = 0.5 * a;
    const unsigned int core0 = static_cast<unsigned int>(vertices.size());
    for (unsigned int q = 0; q <= h; ++q)
      for (unsigned int p = 0; p <= h; ++p)
        vertices.emplace_back(s * p / h, s * q / h);
    const auto core = [&](unsigned int p, unsigned int q) { return core0 + q * (h + 1) + p; };
    // Point k of the core's outer sides, from (s, 0) up to (s, s), then to (0, s).
    const auto side = [&](unsigned int k) { return k <= h ? core(h, k) : core(n - k, h); };
    const unsigned int ring0 = static_cast<unsigned int>(vertices.size());
    for (unsigned int l = 1; l < layers; ++l)
      for (unsigned int k = 0; k <= n; ++k)
      {
        const dealii::Point<2> from = vertices[side(k)], to = vertices[k * (n_r + 1)];
        const double w = double(l) / layers;
        // Exact zeros on the symmetry planes, so that regions find them.
        vertices.emplace_back(k == n ? 0.0 : (1.0 - w) * from[0] + w * to[0],
                              k == 0 ? 0.0 : (1.0 - w) * from[1] + w * to[1]);
      }
    const auto ring = [&](unsigned int l, unsigned int k)
    {
      return l == 0 ? side(k) : l == layers ? k * (n_r + 1) : ring0 + (l - 1) * (n + 1) + k;
    };
    const auto add = [&](unsigned int v0, unsigned int v1, unsigned int v2, unsigned int v3)
    {
      dealii::CellData<2> cell;
      cell.vertices[0] = v0;
      cell.vertices[1] = v1;
      cell.vertices[2] = v2;
      cell.vertices[3] = v3;
      cells.push_back(cell);
    };
    for (unsigned int q = 0; q < h; ++q)
      for (unsigned int p = 0; p < h; ++p)
        add(core(p, q), core(p + 1, q), core(p, q + 1), core(p + 1, q + 1));
    for (unsigned int l = 0; l < layers; ++l)
      for (unsigned int k = 0; k < n; ++k)
        add(ring(l, k), ring(l + 1, k), ring(l, k + 1), ring(l + 1, k + 1));
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
