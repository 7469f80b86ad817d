// A rigid model split among ranks gives the serial run's bits. Every rank
// runs the whole model alone (the reference) and its share of it: the
// blocks it owns under a CellPartition and two layers of ghosts
// (decompose_blocks), a RigidSolver on those (BlockModel::subset) whose
// ghosts are written after every step by their owners (GhostExchange), and
// which searches and updates contacts when any rank must. After 1,500
// dynamic or static steps each owned block's vertices, velocity and spin must equal the
// serial run's bit for bit: the contacts of an owned block are all held
// and summed in the serial order (ContactSet's order by block pair). Each
// contact is computed once: the common planes the ranks compute over the
// steps add up to the serial run's, a contact across ranks being found,
// updated and laid out by one of its two ranks alone and taken by the
// other (ContactSet::update with a ContactTrade); which rank computes it
// alternates (RankBlocks::computes_contact), so that every rank takes
// some.
//
// The scene: a slab 24 m x 4 m x 3 m cut by three orthogonal joint sets at
// 1 m and an oblique one (slivers, blocks of different sizes), its bottom
// layer fixed, under gravity tilted so that the blocks above slide along x
// on 15-degree joints (about 0.2 m in the 1,500 steps, twenty contact
// tolerances: contacts are found and lost, blocks cross the rank
// boundaries); run on 2 and 3 ranks (mpirun), split along x.

#include <talus/base/parallel_environment.h>
#include <talus/contact/block_decomposition.h>
#include <talus/scene/build_blocks.h>
#include <talus/scene/scene.h>
#include <talus/solver/ghost_exchange.h>
#include <talus/solver/rigid_solver.h>
#include <talus/solver/subcontact_exchange.h>

#include <mpi.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "../tests.h"
#include "rank_checks.h"

using namespace talus;

namespace
{

const char* scene_text = R"(
subsection Model
  set Brick min = 0, 0, 0
  set Brick max = 24, 4, 3
  set Default group = slab
end
subsection Material
  set Density = 2650
end
subsection Joint set 1
  set Dip = 90
  set Dip direction = 90
  set Spacing = 1
end
subsection Joint set 2
  set Dip = 90
  set Dip direction = 0
  set Spacing = 1
end
subsection Joint set 3
  set Dip = 0
  set Spacing = 1
end
subsection Joint set 4
  set Dip = 60
  set Dip direction = 45
  set Spacing = 2.3
end
subsection Group 1
  set Name = base
  set Corner min = -1, -1, -1
  set Corner max = 25, 5, 1
end
subsection Joint properties
  set Normal stiffness = 1e8
  set Shear stiffness = 1e8
  set Friction angle = 15
end
subsection Contacts
  set Tolerance = 0.01
end
subsection Solver
  set Mode = dynamic
  set Steps = 1500
  set Gravity = 6, 0, -8
  set Fixed groups = base
end
)";

} // namespace

/// Runs the model whole and split on every rank; rank 0 prints the
/// verdicts.
void run_case(const Scene& scene, const BlockModel& model, const SolverSettings& settings,
              const char* mode, MPI_Comm comm)
{
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  // The reference: the whole model on this rank.
  BlockModel whole = model;
  RigidSolver serial(whole, scene.density, settings);

  // This rank's share.
  Box domain{model.vertex[0], model.vertex[0]};
  for (const Vec3& v : model.vertex)
  {
    domain.lo = domain.lo.cwiseMin(v);
    domain.hi = domain.hi.cwiseMax(v);
  }
  const CellPartition partition(domain, domain.lo, (domain.hi - domain.lo) / 16.0, model.centroid,
                                std::vector<double>(model.n_blocks(), 1.0),
                                static_cast<unsigned int>(ranks));
  const double reach = 4.0 * settings.contact.tolerance; // tolerance and motion
  const RankBlocks mine =
      decompose_blocks(model, partition, static_cast<unsigned int>(rank), reach, 2);
  BlockModel local = model.subset(mine.local);
  RigidSolver solver(local, scene.density, settings);
  std::vector<char> ghost(mine.local.size());
  for (std::size_t i = 0; i < ghost.size(); ++i)
    ghost[i] = !mine.owned[i];
  solver.split_among_ranks(ghost, reductions_over(comm));
  GhostExchange exchange(mine, comm);
  SubContactExchange shared(mine, comm); // each contact across ranks computed once
  solver.share_subcontacts(&shared);
  // Common planes computed from here on (the set-up computes those of the
  // blocks each holds).
  const unsigned long serial_planes = serial.contacts().planes_computed(),
                      split_planes = solver.contacts().planes_computed();

  long taken = 0; // sub-contacts whose state came from another rank, summed over steps
  long laid = 0;  // contacts laid out by another rank, summed over updates
  for (unsigned long s = 0; s < settings.steps; ++s)
  {
    serial.step();
    solver.step();
    taken += static_cast<long>(shared.received());
    laid += static_cast<long>(shared.contacts_taken());
    exchange.refresh(solver);
  }
  long taken_everywhere = 0, laid_everywhere = 0, planes_everywhere = 0, laid_least = 0;
  MPI_Allreduce(&taken, &taken_everywhere, 1, MPI_LONG, MPI_SUM, comm);
  MPI_Allreduce(&laid, &laid_everywhere, 1, MPI_LONG, MPI_SUM, comm);
  MPI_Allreduce(&laid, &laid_least, 1, MPI_LONG, MPI_MIN, comm);
  const long my_planes = static_cast<long>(solver.contacts().planes_computed() - split_planes);
  MPI_Allreduce(&my_planes, &planes_everywhere, 1, MPI_LONG, MPI_SUM, comm);
  const long planes_serial = static_cast<long>(serial.contacts().planes_computed() - serial_planes);
  const double serial_ratio = serial.unbalanced_ratio(), split_ratio = solver.unbalanced_ratio();
  const bool same_step = serial.dt() == solver.dt();

  long counts[4] = {0, 0, 0, 0}; // owned, differing, held, ratio differs
  counts[3] = std::memcmp(&serial_ratio, &split_ratio, sizeof(double)) != 0 || !same_step;
  double largest_move = 0.0;
  for (std::size_t i = 0; i < mine.local.size(); ++i)
  {
    ++counts[2];
    if (!mine.owned[i])
      continue;
    const unsigned int g = mine.local[i];
    ++counts[0];
    counts[1] += !talus_test::same_block(solver, local, i, serial, whole, g);
    largest_move = std::max(largest_move, serial.displacement[g].norm());
  }
  long total[4];
  MPI_Allreduce(counts, total, 4, MPI_LONG, MPI_SUM, comm);
  double moved = 0.0;
  MPI_Allreduce(&largest_move, &moved, 1, MPI_DOUBLE, MPI_MAX, comm);
  std::fprintf(stderr, "rank %d: %ld owned, %ld held, %ld differ; %zu doubles sent last step\n",
               rank, counts[0], counts[2], counts[1], exchange.sent());
  if (rank == 0)
  {
    std::printf("sliding slab on %d ranks, %lu %s steps: blocks owned once %s\n", ranks,
                settings.steps, mode, talus_test::verdict(total[0] == model.n_blocks()));
    std::printf("  the blocks slid more than ten contact tolerances %s\n",
                talus_test::verdict(moved > 10 * settings.contact.tolerance));
    std::printf("  each rank held part of the model %s\n",
                talus_test::verdict(total[2] < static_cast<long>(ranks) * model.n_blocks()));
    std::printf(
        "  every block's vertices, velocity and spin as in the serial run, bit for bit %s\n",
        talus_test::verdict(total[1] == 0));
    std::printf("  time step and unbalanced-force ratio on every rank as in the serial run %s\n",
                talus_test::verdict(total[3] == 0));
    std::printf("  contacts across ranks computed by one rank, the other taking their state %s\n",
                talus_test::verdict(taken_everywhere > 0));
    std::printf("  contacts across ranks laid out by one rank, the other taking them %s\n",
                talus_test::verdict(laid_everywhere > 0));
    std::printf("  every rank takes some of them: neighbours share the contacts between them %s\n",
                talus_test::verdict(laid_least > 0));
    std::printf("  every common plane computed once: the ranks' add up to the serial run's %s\n",
                talus_test::verdict(planes_everywhere == planes_serial));
    std::fprintf(stderr, "common planes: %ld on the ranks, %ld serial\n", planes_everywhere,
                 planes_serial);
    std::fprintf(stderr, "largest displacement %.3g m; %ld blocks differ\n", moved, total[1]);
  }
}

int main(int argc, char** argv)
{
  ParallelEnvironment mpi(argc, argv);
  const MPI_Comm comm = MPI_COMM_WORLD;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const std::string file = "ranks_rigid_" + std::to_string(rank) + ".prm";
  if (FILE* f = std::fopen(file.c_str(), "w"))
  {
    std::fputs(scene_text, f);
    std::fclose(f);
  }
  Scene scene = read_scene(file, false);
  BuildReport built;
  BlockModel model = build_blocks(scene, built);
  resolve_group_names(scene, model);
  SolverSettings settings = scene.solver;
  run_case(scene, model, settings, "dynamic", comm);
  // Static: local damping, density scaling to the mean mass (over all
  // ranks' blocks), the time step of the whole model.
  settings.dynamic = false;
  settings.target_ratio = 0.0;
  run_case(scene, model, settings, "static", comm);
}
