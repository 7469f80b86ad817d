#include <talus/solver/strength_reduction.h>

#include <algorithm>
#include <cstdio>

namespace talus
{

StrengthReductionResult
find_factor_of_safety(const std::function<StrengthReductionTrial(double factor)>& trial,
                      const StrengthReductionSettings& s)
{
  StrengthReductionResult r;
  const auto run = [&](double f)
  {
    r.trials.push_back(trial(f));
    r.trials.back().factor = f;
    return r.trials.back().stable;
  };
  char text[300];
  // The bracket: double F while stable, halve it while unstable.
  double f = std::clamp(s.initial_factor, s.smallest_factor, s.largest_factor);
  if (run(f))
  {
    r.stable_factor = f;
    while (true)
    {
      if (f >= s.largest_factor)
      {
        std::snprintf(text, sizeof text,
                      "the model is stable at every factor tried (up to F = %g): its strengths "
                      "are more than %g times what it needs, or nothing can move",
                      s.largest_factor, s.largest_factor);
        r.failure = text;
        return r;
      }
      f = std::min(2.0 * f, s.largest_factor);
      if (!run(f))
        break;
      r.stable_factor = f;
    }
    r.unstable_factor = f;
  }
  else
  {
    r.unstable_factor = f;
    while (true)
    {
      if (f <= s.smallest_factor)
      {
        std::snprintf(text, sizeof text,
                      "the model is unstable at every factor tried (down to F = %g, the "
                      "strengths multiplied by %g): something moves whatever the strength of "
                      "the joints (a block with no support, or 'Steps' too few to reach "
                      "'Target ratio')",
                      s.smallest_factor, 1.0 / s.smallest_factor);
        r.failure = text;
        return r;
      }
      f = std::max(0.5 * f, s.smallest_factor);
      if (run(f))
        break;
      r.unstable_factor = f;
    }
    r.stable_factor = f;
  }
  // Bisection: the stable end stays stable, the unstable end unstable.
  while (r.unstable_factor - r.stable_factor > s.tolerance * r.stable_factor)
  {
    const double mid = 0.5 * (r.stable_factor + r.unstable_factor);
    (run(mid) ? r.stable_factor : r.unstable_factor) = mid;
  }
  r.found = true;
  return r;
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
