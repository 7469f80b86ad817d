#include <talus/base/archive.h>
#include <talus/solver/strength_reduction.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>

namespace talus
{

FactorSearch::FactorSearch(const StrengthReductionSettings& s) : s_(s)
{
  f_ = std::clamp(s.initial_factor, s.smallest_factor, s.largest_factor);
}

bool FactorSearch::next(double& factor) const
{
  factor = f_;
  return phase_ != Phase::done;
}

void FactorSearch::bisect_or_finish()
{
  // Bisection: the stable end stays stable, the unstable end unstable.
  phase_ = Phase::bisect;
  if (r_.unstable_factor - r_.stable_factor > s_.tolerance * r_.stable_factor)
    f_ = 0.5 * (r_.stable_factor + r_.unstable_factor);
  else
  {
    r_.found = true;
    phase_ = Phase::done;
  }
}

void FactorSearch::add(const StrengthReductionTrial& trial)
{
  const double f = f_;
  r_.trials.push_back(trial);
  r_.trials.back().factor = f;
  const bool stable = trial.stable;
  char text[300];
  if (first_) // the first trial sets the direction of the bracket's search
  {
    first_ = false;
    phase_ = stable ? Phase::up : Phase::down;
  }
  else if (phase_ == Phase::bisect)
  {
    (stable ? r_.stable_factor : r_.unstable_factor) = f;
    bisect_or_finish();
    return;
  }
  // The bracket: double F while stable, halve it while unstable.
  if (phase_ == Phase::up)
  {
    if (!stable)
    {
      r_.unstable_factor = f;
      bisect_or_finish();
      return;
    }
    r_.stable_factor = f;
    if (f >= s_.largest_factor)
    {
      std::snprintf(text, sizeof text,
                    "the model is stable at every factor tried (up to F = %g): its strengths "
                    "are more than %g times what it needs, or nothing can move",
                    s_.largest_factor, s_.largest_factor);
      r_.failure = text;
      phase_ = Phase::done;
      return;
    }
    f_ = std::min(2.0 * f, s_.largest_factor);
  }
  else if (phase_ == Phase::down)
  {
    if (stable)
    {
      r_.stable_factor = f;
      bisect_or_finish();
      return;
    }
    r_.unstable_factor = f;
    if (f <= s_.smallest_factor)
    {
      std::snprintf(text, sizeof text,
                    "the model is unstable at every factor tried (down to F = %g, the "
                    "strengths multiplied by %g): something moves whatever the strength of "
                    "the joints (a block with no support, or 'Steps' too few to reach "
                    "'Target ratio')",
                    s_.smallest_factor, 1.0 / s_.smallest_factor);
      r_.failure = text;
      phase_ = Phase::done;
      return;
    }
    f_ = std::max(0.5 * f, s_.smallest_factor);
  }
}

StrengthReductionResult
find_factor_of_safety(const std::function<StrengthReductionTrial(double factor)>& trial,
                      const StrengthReductionSettings& s)
{
  FactorSearch search(s);
  for (double f; search.next(f);)
    search.add(trial(f));
  return search.result();
}

namespace
{
/// One rank's trial of a round, as bytes (none: the rank ran no trial).
std::string record_bytes(const RankTrial* t)
{
  CheckpointWriter out;
  out.put(static_cast<unsigned char>(t != nullptr));
  if (t == nullptr)
    return out.bytes();
  const StrengthReductionTrial& r = t->trial;
  out.put(r.factor);
  out.put(static_cast<unsigned char>(r.stable));
  out.put(static_cast<unsigned char>(r.reached_target));
  out.put(r.steps);
  out.put(r.ratio);
  out.put(r.displacement);
  out.put(r.late_growth);
  out.put(r.note);
  return out.bytes();
}

RankTrial read_record(const std::string& bytes)
{
  CheckpointReader in(bytes, "a trial of the factor of safety from another rank");
  RankTrial t;
  unsigned char has = 0, stable = 0, reached = 0;
  in.get(has);
  if (!has)
    return t;
  StrengthReductionTrial& r = t.trial;
  in.get(r.factor);
  in.get(stable);
  in.get(reached);
  r.stable = stable != 0;
  r.reached_target = reached != 0;
  in.get(r.steps);
  in.get(r.ratio);
  in.get(r.displacement);
  in.get(r.late_growth);
  in.get(r.note);
  return t;
}

/// Returns when every rank of `comm` has come here, polling every
/// millisecond: a rank whose trial ended first sleeps, where MPI's
/// blocking collectives would spin and take a core from the ranks still
/// running theirs (or from anything else on the machine).
void wait_for_all(MPI_Comm comm)
{
  MPI_Request request;
  MPI_Ibarrier(comm, &request);
  for (int done = 0;;)
  {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done)
      return;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

/// Every rank's bytes, on every rank (`to` < 0) or on rank `to` alone
/// (empty elsewhere).
std::vector<std::string> gather(const std::string& mine, MPI_Comm comm, int to = -1)
{
  int ranks = 1, rank = 0;
  MPI_Comm_size(comm, &ranks);
  MPI_Comm_rank(comm, &rank);
  std::vector<int> sizes(static_cast<std::size_t>(ranks)), at(sizes.size(), 0);
  const int size = static_cast<int>(mine.size());
  MPI_Allgather(&size, 1, MPI_INT, sizes.data(), 1, MPI_INT, comm);
  for (std::size_t r = 1; r < sizes.size(); ++r)
    at[r] = at[r - 1] + sizes[r - 1];
  std::string all(to < 0 || rank == to ? static_cast<std::size_t>(at.back() + sizes.back()) : 0,
                  '\0');
  if (to < 0)
    MPI_Allgatherv(mine.data(), size, MPI_CHAR, all.data(), sizes.data(), at.data(), MPI_CHAR,
                   comm);
  else
  {
    MPI_Gatherv(mine.data(), size, MPI_CHAR, all.data(), sizes.data(), at.data(), MPI_CHAR, to,
                comm);
    if (rank != to)
      return std::vector<std::string>(sizes.size());
  }
  std::vector<std::string> each;
  for (std::size_t r = 0; r < sizes.size(); ++r)
    each.push_back(all.substr(static_cast<std::size_t>(at[r]), static_cast<std::size_t>(sizes[r])));
  return each;
}
} // namespace

StrengthReductionResult find_factor_of_safety_on_ranks(
    const std::function<RankTrial(double factor)>& trial, const StrengthReductionSettings& s,
    MPI_Comm comm,
    const std::function<void(const StrengthReductionTrial&, int rank, const std::string& payload)>&
        taken,
    std::vector<unsigned int>* rounds)
{
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  FactorSearch search(s);
  // A node of a round's tree: the search as it would stand, the rank that
  // runs its next trial (-1: none) and the nodes after an unstable [0] and
  // a stable [1] outcome of it.
  struct Node
  {
    FactorSearch search;
    double factor = 0.0;
    int rank = -1;
    int after[2] = {-1, -1};
  };
  for (double f; search.next(f);)
  {
    // Breadth first from the search as it stands, one trial per rank: every
    // node's factor is what the serial search computes on that path.
    std::vector<Node> tree{Node{search}};
    int given = 0;
    for (std::size_t n = 0; n < tree.size() && given < ranks; ++n)
    {
      double g = 0.0;
      if (!tree[n].search.next(g))
        continue;
      tree[n].factor = g;
      tree[n].rank = given++;
      for (int stable = 0; stable < 2; ++stable)
      {
        StrengthReductionTrial guess;
        guess.stable = stable != 0;
        Node child{tree[n].search};
        child.search.add(guess);
        tree[n].after[stable] = static_cast<int>(tree.size());
        tree.push_back(std::move(child));
      }
    }
    RankTrial mine;
    const Node* run = nullptr;
    for (const Node& n : tree)
      if (n.rank == rank)
        run = &n;
    if (run != nullptr)
    {
      mine = trial(run->factor);
      mine.trial.factor = run->factor;
    }
    wait_for_all(comm);
    // The records to every rank; the payloads (for the output) to rank 0.
    const std::vector<std::string> records = gather(record_bytes(run ? &mine : nullptr), comm);
    const std::vector<std::string> payloads = gather(mine.payload, comm, 0);
    // The trials the serial search runs, as far as this round ran them.
    unsigned int took = 0;
    for (int n = 0; n >= 0 && tree[static_cast<std::size_t>(n)].rank >= 0;)
    {
      const Node& node = tree[static_cast<std::size_t>(n)];
      RankTrial t = node.rank == rank ? mine : read_record(records[node.rank]);
      t.payload = payloads[node.rank];
      search.add(t.trial);
      ++took;
      if (taken)
        taken(search.result().trials.back(), node.rank, t.payload);
      n = node.after[t.trial.stable ? 1 : 0];
    }
    if (rounds)
      rounds->push_back(took);
  }
  return search.result();
}

void DisplacementWatch::add(unsigned long step, double largest_displacement)
{
  samples_.emplace_back(step, largest_displacement);
}

double DisplacementWatch::late_growth() const
{
  if (samples_.size() < 2)
    return 0.0;
  const unsigned long end = samples_.back().first;
  // The last sample at or before 3/4 of the way (the first sample is at
  // the start, so there is one).
  auto it = std::upper_bound(samples_.begin(), samples_.end(), 3 * end / 4,
                             [](unsigned long step, const std::pair<unsigned long, double>& s)
                             { return step < s.first; });
  if (it != samples_.begin())
    --it;
  return samples_.back().second - it->second;
}

StrengthReductionTrial judge_trial(double factor, bool reached_target, unsigned long steps,
                                   double ratio, const DisplacementWatch& watch,
                                   double rest_displacement)
{
  StrengthReductionTrial t;
  t.factor = factor;
  t.reached_target = reached_target;
  t.steps = steps;
  t.ratio = ratio;
  t.displacement = watch.last();
  t.late_growth = watch.late_growth();
  t.stable = reached_target &&
             t.late_growth <= std::max(creep_fraction * t.displacement, rest_displacement);
  return t;
}

std::string trial_line(const StrengthReductionTrial& t)
{
  char text[400];
  if (t.stable)
    std::snprintf(text, sizeof text,
                  "Trial F = %.6g: stable, ratio %.2g at step %lu, largest "
                  "displacement %.3g m",
                  t.factor, t.ratio, t.steps, t.displacement);
  else if (!t.note.empty())
    std::snprintf(text, sizeof text, "Trial F = %.6g: unstable, %s at step %lu", t.factor,
                  t.note.c_str(), t.steps);
  else if (t.reached_target)
    std::snprintf(text, sizeof text,
                  "Trial F = %.6g: unstable, ratio %.2g at step %lu but the largest displacement "
                  "(%.3g m) grew by %.2g %% over the last quarter of the steps (creeping)",
                  t.factor, t.ratio, t.steps, t.displacement,
                  t.displacement > 0.0 ? 100.0 * t.late_growth / t.displacement : 0.0);
  else
    std::snprintf(text, sizeof text,
                  "Trial F = %.6g: unstable, ratio %.2g at the step limit %lu, largest "
                  "displacement %.3g m",
                  t.factor, t.ratio, t.steps, t.displacement);
  return text;
}

} // namespace talus
