// A zone mesh split among ranks by its gridpoints (share_mesh,
// GridpointShare): each rank holds every zone with a gridpoint of its own
// (a 10-node zone with any of its ten nodes, a hexahedral zone's ten
// tetrahedra together) and moves only its own gridpoints; the ghosts'
// positions and velocities come from their owners through PETSc's ghost
// update after every step. Every rank runs the whole mesh alone (the
// reference) and its share, and every owned gridpoint's position and
// velocity must be the whole run's after 200 steps of: statics with
// density scaling (elastic, then Mohr-Coulomb yielding from the
// gravitational stress), dynamics with the automatic step (the least over
// the ranks of their own gridpoints' steps, eq. 84), nodal mixed
// discretization (eqs. 68-76, elastic and yielding: the ghosts' averages
// come from their owners), and Mohr-Coulomb yielding in 10-node and in
// hexahedral zones, all bit for bit. (With nodal mixed discretization a
// rank adds its zones' forces in the order of its own batches, which can
// differ from one run's on other meshes; here it does not.) The largest
// difference and value are printed to stderr. Without the ghost
// update, 300 of the 2,197 gridpoints of a 12-cell cube differed on 2
// ranks (benchmark_zone_ranks).
//
// The cube: 6 m, 6 cells a side (4-node zones: 1,080 zones, 343
// gridpoints), base held, gravity, rho = 2650 kg/m^3, E = 10 GPa, nu =
// 0.25; Mohr-Coulomb c = 40 kPa, phi = 30, sigma_t = 10 kPa (the base's
// vertical stress, 156 kPa, exceeds the uniaxial strength of 139 kPa
// there).

#include <talus/base/parallel_environment.h>
#include <talus/solver/deformable_solver.h>
#include <talus/solver/mesh_share.h>
#include <talus/zone/block_mesher.h>
#include <talus/zone/tet10_mesh.h>

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "../tests.h"

using namespace talus;

namespace
{

constexpr double side = 6.0, density = 2650.0;

struct Case
{
  const char* name;
  bool dynamic;
  bool plastic;
  bool nodal_mixed;
  ZoneElement element;
};

void run(const Case& c, const TetMesh& mesh, const MeshShare& mine, int rank, int ranks)
{
  ZoneMaterial material;
  material.element = c.element;
  material.density = density;
  material.set_young_poisson(1e10, 0.25);
  if (c.plastic)
  {
    material.model = ZoneModel::mohr_coulomb;
    material.cohesion = 4e4;
    material.friction_angle = 30.0;
    material.tensile_strength = 1e4;
  }
  material.nodal_mixed = c.nodal_mixed;
  SolverSettings settings;
  settings.dynamic = c.dynamic;
  settings.gravity = Vec3(0, 0, -9.81);
  GridpointCondition base;
  base.region = Box{Vec3(-1, -1, -1e-9), Vec3(side + 1, side + 1, 1e-9)};
  InitialStress initial;
  initial.base[2] = -density * 9.81 * side;
  initial.gradient[2] = density * 9.81;

  int refused = 0;
  long differ = 0, yielded = 0, owned = mine.share.n_owned;
  double largest = 0.0, difference = 0.0; // m and m/s
  double dt_whole = 0.0, dt_split = 0.0;
  try
  {
    DeformableSolver split(mine.mesh, {material}, std::vector<unsigned int>(mine.mesh.n_zones(), 0),
                           settings, {base}, {}, &initial, &mine.share);
    DeformableSolver whole(mesh, {material}, std::vector<unsigned int>(mesh.n_zones(), 0), settings,
                           {base}, {}, &initial);
    for (int k = 0; k < 200; ++k)
    {
      whole.step();
      split.step();
    }
    dt_whole = whole.dt();
    dt_split = split.dt();
    const std::vector<double> xw = whole.positions(), vw = whole.velocities();
    const std::vector<double> xs = split.positions(), vs = split.velocities();
    for (unsigned int i = 0; i < mine.share.n_owned; ++i)
    {
      const unsigned int g = mine.gridpoint[i];
      differ += std::memcmp(&xw[3 * g], &xs[3 * i], 3 * sizeof(double)) != 0 ||
                std::memcmp(&vw[3 * g], &vs[3 * i], 3 * sizeof(double)) != 0;
      for (int d = 0; d < 3; ++d)
      {
        const double uw = xw[3 * g + d] - mesh.position[3 * g + d],
                     us = xs[3 * i + d] - mesh.position[3 * g + d];
        largest = std::max({largest, std::abs(uw), std::abs(vw[3 * g + d])});
        difference =
            std::max({difference, std::abs(uw - us), std::abs(vw[3 * g + d] - vs[3 * i + d])});
      }
    }
    for (unsigned char s : whole.plastic_state())
      yielded += s != 0;
  }
  catch (const std::logic_error&)
  {
    refused = 1;
  }
  long sums[3] = {differ, owned, refused}, total[3] = {0, 0, 0};
  MPI_Allreduce(sums, total, 3, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  double most[2] = {largest, difference};
  MPI_Allreduce(MPI_IN_PLACE, most, 2, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  int same_step = dt_whole == dt_split, all_same_step = 0;
  MPI_Allreduce(&same_step, &all_same_step, 1, MPI_INT, MPI_LAND, MPI_COMM_WORLD);
  if (rank != 0)
    return;
  std::printf("%s: every gridpoint owned once %s\n", c.name,
              talus_test::verdict(total[1] == long(mesh.n_gridpoints())));
  std::printf("  the time step the whole run's %s\n", talus_test::verdict(all_same_step != 0));
  if (c.plastic)
    std::printf("  zones yielded %s\n", talus_test::verdict(yielded > 0));
  std::printf("  every owned gridpoint's position and velocity the whole run's, bit for bit %s\n",
              talus_test::verdict(total[0] == 0 && total[2] == 0));
  std::fprintf(stderr,
               "%s: %ld gridpoints differ (by %.3g of %.3g at most), dt %.17g s, %ld zones "
               "yielded on rank 0\n",
               c.name, total[0], most[1], most[0], dt_whole, yielded);
}

} // namespace

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  BlockModel blocks;
  blocks.add_block(ConvexPolyhedron::box(Vec3::Zero(), Vec3::Constant(side)), 0);
  for (const ZoneElement element : {ZoneElement::tet4, ZoneElement::tet10, ZoneElement::hex_mixed})
  {
    MeshReport report;
    // 10-node zones: the 4-node mesh made quadratic (as talus makes them).
    TetMesh mesh = mesh_blocks(blocks, {0}, 1.0, report,
                               element == ZoneElement::tet10 ? ZoneElement::tet4 : element);
    if (element == ZoneElement::tet10)
      make_quadratic(mesh);
    const unsigned int ng = mesh.n_gridpoints();
    const std::vector<unsigned int> owner = gridpoint_owners(
        mesh, Box{Vec3::Zero(), Vec3::Constant(side)}, 1.0, static_cast<unsigned int>(ranks));
    const MeshShare mine = share_mesh(mesh, owner, static_cast<unsigned int>(rank),
                                      static_cast<unsigned int>(ranks), MPI_COMM_WORLD);
    long ghosts = mine.mesh.n_gridpoints() - mine.share.n_owned, all_ghosts = 0;
    MPI_Allreduce(&ghosts, &all_ghosts, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
    const char* kind = element == ZoneElement::tet4    ? "4-node zones"
                       : element == ZoneElement::tet10 ? "10-node zones"
                                                       : "tetrahedra of hexahedral zones";
    if (rank == 0)
      std::printf("a cube of %u %s, %u gridpoints on %d ranks, with ghosts %s\n", mesh.n_zones(),
                  kind, ng, ranks, talus_test::verdict(all_ghosts > 0));
    const ZoneElement e = element;
    if (element == ZoneElement::tet4)
      for (const Case& c : {Case{"statics, elastic", false, false, false, e},
                            Case{"statics, Mohr-Coulomb", false, true, false, e},
                            Case{"dynamics, automatic step", true, false, false, e},
                            Case{"nodal mixed, elastic", false, false, true, e},
                            Case{"nodal mixed, Mohr-Coulomb", false, true, true, e},
                            Case{"nodal mixed, dynamics", true, false, true, e}})
        run(c, mesh, mine, rank, ranks);
    else
      for (const Case& c : {Case{"statics, Mohr-Coulomb", false, true, false, e},
                            Case{"dynamics, automatic step", true, false, false, e}})
        run(c, mesh, mine, rank, ranks);
  }
}
