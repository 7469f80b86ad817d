#pragma once

#include <talus/contact/block_decomposition.h>
#include <talus/contact/cell_partition.h>
#include <talus/model/block_model.h>

#include <mpi.h>

#include <memory>
#include <vector>

namespace talus
{

class RigidSolver;

/// What a step costs, in microseconds on the machine the README's tables
/// name (2-core AMD EPYC, benchmark_rigid_cycle at n = 30 and
/// benchmark_zone_cycle, 2026-11-24): a block's motion (2 % of 3.41 us a
/// block-step), a contact's common-plane update (64 % of it over 12.0
/// contacts a block), a sub-contact's forces (34 % over 42.2 sub-contacts
/// a block), a zone's update (between the elastic 0.038 and the
/// Mohr-Coulomb 0.083 us). Only their ratios matter: they weigh the work
/// the regions balance.
struct StepCosts
{
  double block = 0.068, contact = 0.18, subcontact = 0.028, zone = 0.06;
};

/// Keeps the ranks' work even as a run changes it (issue 24: "a rebalance
/// when the work becomes uneven"): blocks pile up in one region, a stage
/// excavates another, contacts form where blocks settle. After the run's
/// first step, after a stage's excavation and then every `interval` steps
/// each rank weighs the work of its own blocks (StepCosts: each
/// block, its zones, and the contacts its rank computes
/// (RankBlocks::computes_contact) with their sub-contacts, each on its
/// block owned here). One MPI_Allgather brings every
/// rank's total to every rank, added there in rank order, so that all
/// ranks decide from the same bits; the largest over the mean is the
/// imbalance. Above `threshold`, the ranks cut the same cell space again
/// by the owned blocks' centroids and work (CellPartition), each rank
/// passing only its own blocks: the work of each region's cell slabs is
/// added over the ranks level by level of the bisection (one
/// MPI_Allreduce of integers per level, a few hundred numbers per region:
/// sum_exactly_over_ranks), so every rank makes the same cuts and none
/// gathers the model's blocks. A deformable block stays with its owner (BlockMigration), so its
/// work stays there. The new regions are taken when they lower the largest
/// work over the mean by a tenth; otherwise, and when the first check
/// after new regions finds the work uneven again, the ranks wait until the
/// imbalance grows by another twentieth before they try again.
/// Adds `numbers` element by element over the ranks of `comm`, giving
/// every rank the same sums, bit for bit: each number is rounded to a
/// multiple of 2^-24 (in the work's unit, us a step) and the integers are
/// added (MPI_Allreduce), which no order of the ranks can change. Collective.
void sum_exactly_over_ranks(std::vector<double>& numbers, MPI_Comm comm);

/// The imbalance above which the regions are cut again (RankBalance):
/// 1.15, or the environment's TALUS_REBALANCE_THRESHOLD (a number above 1,
/// or 0 for never: a benchmark compares the two); another value is an
/// InputError naming the variable.
double rebalance_threshold();

class RankBalance
{
public:
  /// `threshold` 0: never rebalance.
  RankBalance(const Box& domain, const Vec3& cell_size, double threshold = 1.15,
              unsigned long interval = 100);

  /// Collective. On a step that is a multiple of the interval, or the
  /// first after check_soon(), when the work is uneven: the new regions in `next` and true (the
  /// caller keeps them, migrates, then calls taken() or declined()). `zones_of_block`: per global
  /// block, its zones (may be empty: no deformable blocks).
  bool choose(const RigidSolver& solver, const RankBlocks& blocks, const BlockModel& local,
              const std::vector<double>& zones_of_block, MPI_Comm comm,
              std::unique_ptr<CellPartition>& next);

  /// The next choose() checks whatever its step: the run's first step
  /// (the start's regions count blocks and zones, not these costs, and no
  /// contact is known before it) and the first after a stage excavated
  /// blocks, whose new imbalance is then not taken for regions that did
  /// not hold, nor kept waiting. Every rank must call it at the same point.
  void check_soon()
  {
    check_soon_ = true;
    just_rebalanced_ = false;
    waiting_above_ = 0.0;
  }
  /// The blocks moved to the new regions: counted, and the next check
  /// looks at whether they held.
  void taken();
  /// The new regions could not be taken (BlockMigration refused them): the
  /// ranks wait as after regions that would not have helped.
  void declined();

  /// Rebalances made; the imbalance (largest work over the mean) measured
  /// before the last rebalance and expected after it; the imbalance the
  /// last check measured.
  unsigned long rebalances() const { return rebalances_; }
  /// Never rebalances (threshold 0).
  bool off() const { return threshold_ == 0.0; }
  /// New regions that BlockMigration refused (declined()).
  unsigned long refused() const { return refused_; }
  double before() const { return before_; }
  double expected() const { return expected_; }
  double measured() const { return measured_; }

  /// The counters and the hysteresis, in a checkpoint (rank_checkpoint.cc).
  std::vector<double> numbers() const;
  void set_numbers(const std::vector<double>& numbers);

private:
  Box domain_;
  Vec3 cell_size_;
  double threshold_;
  unsigned long interval_;
  StepCosts costs_;
  unsigned long rebalances_ = 0, refused_ = 0;
  double measured_ = 1.0, before_ = 1.0, expected_ = 1.0, pending_expected_ = 1.0;
  double waiting_above_ = 0.0;   ///< no new try until the imbalance exceeds this
  double last_try_ = 0.0;        ///< the imbalance when regions were last chosen
  bool just_rebalanced_ = false; ///< the next check is the first after new regions
  bool check_soon_ = true;       ///< the next choose() checks, whatever its step
  void wait() { waiting_above_ = 1.05 * last_try_; }
};

} // namespace talus
