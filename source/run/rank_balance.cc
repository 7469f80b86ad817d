#include <talus/base/exceptions.h>
#include <talus/run/rank_balance.h>
#include <talus/solver/rigid_solver.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>

namespace talus
{

void sum_exactly_over_ranks(std::vector<double>& numbers, MPI_Comm comm)
{
  // In units of 2^-24 (6e-8 us a step: far below any cost), as integers:
  // their sum does not depend on the order the ranks are added in.
  constexpr double unit = 16777216.0; // 2^24
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  const double largest = 9.2e18 / ranks; // the ranks' sum fits in 64 bits
  std::vector<long long> units(numbers.size());
  for (std::size_t i = 0; i < numbers.size(); ++i)
  {
    const double u = numbers[i] * unit;
    if (!(std::abs(u) < largest))
      throw std::runtime_error("RankBalance: a work to add over the ranks is not finite or too "
                               "large");
    units[i] = std::llround(u);
  }
  if (!units.empty())
    MPI_Allreduce(MPI_IN_PLACE, units.data(), static_cast<int>(units.size()), MPI_LONG_LONG,
                  MPI_SUM, comm);
  for (std::size_t i = 0; i < numbers.size(); ++i)
    numbers[i] = static_cast<double>(units[i]) / unit;
}

double rebalance_threshold()
{
  const char* text = std::getenv("TALUS_REBALANCE_THRESHOLD");
  if (text == nullptr)
    return 1.15;
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  if (end == text || *end != '\0' || !(value > 1.0 || value == 0.0) || !std::isfinite(value))
    throw InputError(std::string("environment variable TALUS_REBALANCE_THRESHOLD: '") + text +
                     "' is not allowed; allowed: a number above 1 (the ranks' largest work over "
                     "the mean above which their regions are cut again), or 0 (never)");
  return value;
}

RankBalance::RankBalance(const Box& domain, const Vec3& cell_size, double threshold,
                         unsigned long interval)
    : domain_(domain), cell_size_(cell_size), threshold_(threshold), interval_(interval)
{
  if (!(threshold > 1.0 || threshold == 0.0) || interval == 0)
    throw std::logic_error("RankBalance: the threshold must exceed 1 (or be 0: off), the "
                           "interval 0");
}

bool RankBalance::choose(const RigidSolver& solver, const RankBlocks& blocks,
                         const BlockModel& local, const std::vector<double>& zones_of_block,
                         MPI_Comm comm, std::unique_ptr<CellPartition>& next)
{
  if (threshold_ == 0.0 || (!check_soon_ && solver.steps_done() % interval_ != 0))
    return false;
  check_soon_ = false;
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  // This rank's work a step, block by block (us, StepCosts).
  const unsigned int n = static_cast<unsigned int>(blocks.local.size());
  std::vector<double> work(n, 0.0);
  for (unsigned int i = 0; i < n; ++i)
    if (blocks.owned[i] && !solver.removed(i))
      work[i] = costs_.block +
                (zones_of_block.empty() ? 0.0 : costs_.zone * zones_of_block[blocks.local[i]]);
  const ContactSet& cs = solver.contacts();
  std::vector<unsigned int> subcontacts(cs.n_slots(), 0);
  for (unsigned int c : cs.sc_contact)
    ++subcontacts[c];
  for (unsigned int c = 0; c < cs.n_slots(); ++c)
  {
    // Counted where it is computed (RankBlocks::computes_contact: a
    // contact across ranks by one of its two ranks), on its block owned
    // there, whose centroid places the work when the regions are cut again.
    const unsigned int a = cs.block_a[c], b = cs.block_b[c];
    if (cs.alive[c] && blocks.computes_contact(a, b))
      work[blocks.owned[a] ? a : b] += costs_.contact + costs_.subcontact * subcontacts[c];
  }
  double mine = 0.0;
  for (unsigned int i = 0; i < n; ++i)
    mine += work[i];
  // Every rank's work, added in rank order on every rank: the decisions
  // below are collective, so every rank must reach them from the same bits.
  std::vector<double> per_rank(std::size_t(ranks), 0.0);
  MPI_Allgather(&mine, 1, MPI_DOUBLE, per_rank.data(), 1, MPI_DOUBLE, comm);
  double total = 0.0;
  for (double w : per_rank)
    total += w;
  const double largest_now = *std::max_element(per_rank.begin(), per_rank.end());
  measured_ = total > 0.0 ? largest_now * ranks / total : 1.0;
  const bool after_rebalance = just_rebalanced_;
  just_rebalanced_ = false;
  if (measured_ <= threshold_ || measured_ <= waiting_above_)
    return false;
  if (after_rebalance)
  {
    // The last regions did not hold (the work moves faster than the checks
    // come, as blocks tumble): try again only once it has grown.
    last_try_ = measured_;
    wait();
    return false;
  }

  // The same cell space cut again by the owned blocks' centroids and work,
  // each rank passing only its own: the ranks add their cell slabs' work
  // level by level (CellPartition's sum_over_processes), so that no rank
  // gathers the model's blocks.
  std::vector<Vec3> point;
  std::vector<double> block_work;
  std::vector<int> stays; // a deformable block's rank, -1 for the others
  for (unsigned int i = 0; i < n; ++i)
    if (blocks.owned[i] && !solver.removed(i))
    {
      point.push_back(local.centroid[i]);
      block_work.push_back(work[i]);
      stays.push_back(solver.is_deformable(i) ? rank : -1);
    }
  auto regions = std::make_unique<CellPartition>(
      domain_, domain_.lo, cell_size_, point, block_work, static_cast<unsigned int>(ranks),
      [comm](std::vector<double>& numbers) { sum_exactly_over_ranks(numbers, comm); });
  // The work each rank would have: a deformable block's stays with its owner.
  std::vector<double> expected(std::size_t(ranks), 0.0);
  for (std::size_t k = 0; k < point.size(); ++k)
    expected[stays[k] >= 0 ? std::size_t(stays[k]) : regions->owner(point[k])] += block_work[k];
  sum_exactly_over_ranks(expected, comm);
  total = 0.0;
  for (double w : expected)
    total += w;
  const double largest = *std::max_element(expected.begin(), expected.end());
  const double after = total > 0.0 ? largest * ranks / total : 1.0;
  last_try_ = measured_;
  if (!(after < 0.9 * measured_))
  {
    wait();
    return false;
  }
  pending_expected_ = after;
  next = std::move(regions);
  return true;
}

void RankBalance::taken()
{
  ++rebalances_;
  before_ = last_try_;
  expected_ = pending_expected_;
  waiting_above_ = 0.0; // new regions: any later imbalance is new too
  just_rebalanced_ = true;
}

void RankBalance::declined()
{
  ++refused_;
  wait();
}

std::vector<double> RankBalance::numbers() const
{
  return {double(rebalances_),
          measured_,
          before_,
          expected_,
          waiting_above_,
          last_try_,
          double(just_rebalanced_),
          double(refused_),
          double(check_soon_)};
}

void RankBalance::set_numbers(const std::vector<double>& numbers)
{
  if (numbers.size() != 9)
    throw std::invalid_argument("RankBalance: the saved state is not whole");
  rebalances_ = static_cast<unsigned long>(numbers[0]);
  measured_ = numbers[1];
  before_ = numbers[2];
  expected_ = numbers[3];
  waiting_above_ = numbers[4];
  last_try_ = numbers[5];
  just_rebalanced_ = numbers[6] != 0.0;
  refused_ = static_cast<unsigned long>(numbers[7]);
  check_soon_ = numbers[8] != 0.0;
}

} // namespace talus
