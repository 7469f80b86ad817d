#include <talus/base/exceptions.h>
#include <talus/contact/cell_partition.h>
#include <talus/contact/cell_space.h>
#include <talus/io/scene_checks.h>
#include <talus/run/rank_share.h>
#include <talus/run/rank_zones.h>
#include <talus/run/run_summary.h>
#include <talus/solver/rigid_solver.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

namespace talus
{

int world_ranks()
{
  int started = 0, ranks = 1;
  MPI_Initialized(&started);
  if (started)
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  return ranks;
}

int world_rank()
{
  int started = 0, rank = 0;
  MPI_Initialized(&started);
  if (started)
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

void agree_on_input_errors(const std::function<void()>& build)
{
  const int ranks = world_ranks();
  if (ranks < 2)
  {
    build();
    return;
  }
  std::string message;
  int failed = ranks;
  try
  {
    build();
  }
  catch (const InputError& e)
  {
    message = e.what();
    failed = world_rank();
  }
  int first = ranks;
  MPI_Allreduce(&failed, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (first == ranks)
    return;
  int length = static_cast<int>(message.size());
  MPI_Bcast(&length, 1, MPI_INT, first, MPI_COMM_WORLD);
  message.resize(static_cast<std::size_t>(length));
  MPI_Bcast(message.data(), length, MPI_CHAR, first, MPI_COMM_WORLD);
  throw InputError(message);
}

void check_runs_on_ranks(const Scene& scene, int ranks)
{
  (void)scene;
  (void)ranks;
  rebalance_threshold(); // refused before any output is written
}

RankShare::RankShare(const BlockModel& model, double reach, MPI_Comm comm, const RankBlocks* saved,
                     const std::vector<double>* zones_of_block)
    : comm_(comm), reach_(reach), n_blocks_(model.n_blocks())
{
  MPI_Comm_rank(comm, &rank_);
  MPI_Comm_size(comm, &ranks_);
  // The cell space of the whole model, about one cell per block (as the
  // contact search's), cut into regions of equal work: a block each, and
  // a deformable block's zones besides (one each).
  Box domain{Vec3::Zero(), Vec3::Zero()};
  if (!model.vertex.empty())
    domain = Box{model.vertex[0], model.vertex[0]};
  for (const Vec3& v : model.vertex)
  {
    domain.lo = domain.lo.cwiseMin(v);
    domain.hi = domain.hi.cwiseMax(v);
  }
  CellSpace cells;
  cells.define(domain, model.n_blocks());
  std::vector<double> work(model.n_blocks(), 1.0);
  if (zones_of_block != nullptr)
    for (unsigned int b = 0; b < model.n_blocks(); ++b)
      work[b] += (*zones_of_block)[b];
  partition_ = std::make_unique<CellPartition>(domain, domain.lo, cells.cell_size(), model.centroid,
                                               work, static_cast<unsigned int>(ranks_));
  balance_ = std::make_unique<RankBalance>(domain, cells.cell_size(), rebalance_threshold());
  if (zones_of_block != nullptr)
    zones_of_block_ = *zones_of_block;
  blocks_ = saved ? *saved
                  : decompose_blocks(model, *partition_, static_cast<unsigned int>(rank_), reach,
                                     ghost_layers);
  local_ = model.subset(blocks_.local);
  start_exchanges();
}

void RankShare::start_exchanges()
{
  exchange_ = std::make_unique<GhostExchange>(blocks_, comm_);
  subcontacts_ = std::make_unique<SubContactExchange>(blocks_, comm_);
}

void RankShare::refresh(RigidSolver& solver)
{
  exchange_->refresh(solver);
  if (!migration_)
    make_migration(solver);
  std::unique_ptr<CellPartition> regions;
  if (balance_->choose(solver, blocks_, local_, zones_of_block_, comm_, regions))
  {
    // In place: the migration holds the partition by reference.
    CellPartition before = *partition_;
    *partition_ = std::move(*regions);
    if (migration_->migrate_to_new_regions(solver, blocks_))
    {
      balance_->taken();
      event_steps_ += solver.steps_done();
      return;
    }
    *partition_ = std::move(before); // a deformable block's surface is not held where needed
    balance_->declined();
  }
  if (migration_->update(solver, blocks_))
    event_steps_ += solver.steps_done();
}

void RankShare::make_migration(const RigidSolver& solver)
{
  migration_ =
      std::make_unique<BlockMigration>(solver, blocks_, *partition_, reach_, ghost_layers, comm_);
  if (zone_rebuild_)
    migration_->let_zones_follow(zone_rebuild_);
}

void RankShare::let_zones_follow(BlockMigration::ZoneRebuild rebuild)
{
  zone_rebuild_ = std::move(rebuild);
  if (migration_)
    migration_->let_zones_follow(zone_rebuild_);
}

unsigned long RankShare::zone_moves() const
{
  return migration_ ? migration_->zone_moves() : 0;
}

unsigned long RankShare::migrations() const
{
  return migration_ ? migration_->events() : 0;
}

unsigned long RankShare::owner_changes() const
{
  return migration_ ? migration_->owner_changes() : 0;
}

std::vector<char> RankShare::ghost_flags() const
{
  std::vector<char> ghost(blocks_.local.size());
  for (std::size_t i = 0; i < ghost.size(); ++i)
    ghost[i] = !blocks_.owned[i];
  return ghost;
}

int RankShare::local_of(unsigned int global) const
{
  const auto at = std::lower_bound(blocks_.local.begin(), blocks_.local.end(), global);
  if (at == blocks_.local.end() || *at != global)
    return -1;
  return static_cast<int>(at - blocks_.local.begin());
}

bool RankShare::owns(unsigned int global) const
{
  const int i = local_of(global);
  return i >= 0 && blocks_.owned[static_cast<std::size_t>(i)];
}

void RankShare::sum(std::vector<double>& values) const
{
  MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_SUM,
                comm_);
}

unsigned long RankShare::sum(unsigned long value) const
{
  unsigned long total = 0;
  MPI_Allreduce(&value, &total, 1, MPI_UNSIGNED_LONG, MPI_SUM, comm_);
  return total;
}

std::pair<double, unsigned int> RankShare::largest(double value, unsigned int global) const
{
  // MPI_MAXLOC keeps the smaller index of equal values.
  struct
  {
    double value;
    int index;
  } mine{value, static_cast<int>(global)}, all{0.0, 0};
  MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm_);
  return {all.value, static_cast<unsigned int>(all.index)};
}

} // namespace talus
