#pragma once

#include <mpi.h>

#include <functional>
#include <string>
#include <vector>

namespace talus
{

/// Factor of safety by strength reduction ('Mode = factor of safety'):
/// trials with the strengths divided by a factor F (tan(phi)/F, c/F, T/F),
/// each from the same initial state; the factor of safety is the F between
/// the largest stable and the smallest unstable trial. This file holds the
/// search and the judging of one trial, independent of the model
/// (factor_of_safety.h runs trials on a scene).
struct StrengthReductionSettings
{
  bool enabled = false;        ///< 'Mode = factor of safety'
  double tolerance = 0.005;    ///< the search stops when (unstable - stable) <= tolerance * stable
  double initial_factor = 1.0; ///< the first trial's F
  bool reduce_zone_strength = false; ///< also Mohr-Coulomb zones' c, tan(phi), T
  double smallest_factor = 0.01;     ///< the bracket is not sought below this F
  double largest_factor = 100.0;     ///< nor above this one
};

/// What one trial did and how it was judged.
struct StrengthReductionTrial
{
  double factor = 1.0;
  bool stable = false;
  bool reached_target = false; ///< the unbalanced-force ratio fell below 'Target ratio'
  unsigned long steps = 0;     ///< steps taken
  double ratio = 1.0;          ///< unbalanced-force ratio at the end
  double displacement = 0.0;   ///< m, the largest displacement at the end
  double late_growth = 0.0;    ///< m, its growth over the last quarter of the steps
  std::string note;            ///< why unstable beyond the ratio (a divergence), or empty
};

/// The outcome of the search.
struct StrengthReductionResult
{
  bool found = false;                         ///< a stable and an unstable trial bracket F
  double stable_factor = 0.0;                 ///< the largest stable F tried
  double unstable_factor = 0.0;               ///< the smallest unstable F tried
  std::vector<StrengthReductionTrial> trials; ///< in the order run
  std::string failure;                        ///< when not found: why (for the message)
  /// The factor of safety: the middle of the bracket.
  double factor() const { return 0.5 * (stable_factor + unstable_factor); }
};

/// The search of find_factor_of_safety one trial at a time: next() gives
/// the F of the trial it needs, add() takes that trial judged. A copy
/// answers "what next if this trial were stable (unstable)?", which the
/// search on ranks asks ahead of the trials.
class FactorSearch
{
public:
  explicit FactorSearch(const StrengthReductionSettings& settings);
  /// The F of the next trial; false when the search is over (result()).
  bool next(double& factor) const;
  /// The trial at next()'s F, judged.
  void add(const StrengthReductionTrial& trial);
  const StrengthReductionResult& result() const { return r_; }

private:
  enum class Phase
  {
    up,     ///< stable so far: doubling F
    down,   ///< unstable so far: halving F
    bisect, ///< bracketed
    done
  };
  StrengthReductionSettings s_;
  StrengthReductionResult r_;
  Phase phase_ = Phase::up;
  bool first_ = true;
  double f_ = 1.0; ///< the next trial's F
  void bisect_or_finish();
};

/// Finds the factor of safety with `trial` (runs one trial at F and judges
/// it): from `initial_factor`, doubles F while stable (halves it while
/// unstable) until one stable and one unstable trial exist, within
/// [smallest_factor, largest_factor]; then bisects until the bracket is
/// narrower than `tolerance` of its stable end.
StrengthReductionResult
find_factor_of_safety(const std::function<StrengthReductionTrial(double factor)>& trial,
                      const StrengthReductionSettings& settings);

/// A trial run on one rank of the search on ranks: its record and what the
/// rank adds for the output (`payload`, any bytes; empty for none).
struct RankTrial
{
  StrengthReductionTrial trial;
  std::string payload;
};

/// The search of find_factor_of_safety on the ranks of `comm`, each trial a
/// serial run of the whole model (`trial`, on the rank it is given to).
/// Each round the ranks run the next trial and those the search may need
/// after it (rank 0 the next one, then breadth first: the F after it if it
/// is unstable, if it is stable, ...), all ranks receive every rank's
/// record, and the search takes the trials it would have run in turn, as
/// far as they go. The trials taken, their order and the result are those
/// of the serial search; `taken` is called on every rank for each, in
/// order, with the rank that ran it and its payload (on rank 0; empty on
/// the others); the others are dropped. `rounds`, if given, gets the number of trials taken per
/// round.
StrengthReductionResult find_factor_of_safety_on_ranks(
    const std::function<RankTrial(double factor)>& trial, const StrengthReductionSettings& settings,
    MPI_Comm comm,
    const std::function<void(const StrengthReductionTrial&, int rank, const std::string& payload)>&
        taken,
    std::vector<unsigned int>* rounds = nullptr);

/// The largest displacement of a trial as it runs, to tell a clean
/// equilibrium from a creeping limit state (judge_trial).
class DisplacementWatch
{
public:
  /// The largest displacement (m) after `step` steps; steps ascending.
  void add(unsigned long step, double largest_displacement);
  /// The last value given (m).
  double last() const { return samples_.empty() ? 0.0 : samples_.back().second; }
  /// How much the largest displacement grew over the last quarter of the
  /// steps: from the last sample at or before 3/4 of the last step (m).
  double late_growth() const;

private:
  std::vector<std::pair<unsigned long, double>> samples_;
};

/// A trial is stable when its unbalanced-force ratio fell below the target
/// within the step limit (3DEC's and FLAC's test: equilibrium reached) and
/// its largest displacement grew by less than `creep_fraction` of itself
/// over the last quarter of the steps (a block creeping at the limit with
/// almost no unbalanced force, which local damping does not stop, is not
/// at rest). A clean equilibrium converges geometrically: its last quarter
/// adds some 1e-4 of the displacement; steady creep adds about a quarter.
/// A growth below `rest_displacement` (m) is rest whatever the fraction: a
/// model already at rest moves by round-off, 1e-12 m, which can grow by
/// half in a few steps.
constexpr double creep_fraction = 0.01;
StrengthReductionTrial judge_trial(double factor, bool reached_target, unsigned long steps,
                                   double ratio, const DisplacementWatch& watch,
                                   double rest_displacement);
/// The rest displacement of judge_trial for a scene: this fraction of the
/// contact tolerance (CTOL).
constexpr double rest_fraction_of_tolerance = 1e-3;

/// One summary line of a trial: "Trial F = 1.234: stable, ratio 8.2e-06 at
/// step 2345" or "Trial F = 2: unstable, ratio 0.0123 at the step limit 20000,
/// largest displacement 0.53 m".
std::string trial_line(const StrengthReductionTrial& trial);

} // namespace talus
