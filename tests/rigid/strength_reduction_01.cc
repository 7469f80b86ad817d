// The strength-reduction search alone (strength_reduction.h), with a fake
// trial that is stable exactly when F < 1.37: from F = 1 (stable) the
// bracket is [1, 2] after two trials; bisection halves its width of 1 until
// it is at most 0.005 of its stable end: 1/2^7 = 0.0078 is 0.0057 of 1.367,
// 1/2^8 = 0.0039 is 0.0029 of it, so 8 bisections, 10 trials, and F = the
// middle of [1.3671875, 1.37109375] = 1.369140625. From F = 4 (unstable)
// the bracket is [1, 2] after halving twice (4, 2 unstable, 1 stable): 3 +
// 8 = 11 trials. A fake stable at every F stops at the largest factor,
// 100, after 1, 2, 4, ..., 64, 100 (8 trials) with found = false; one
// unstable at every F stops at the smallest, 0.01 (1, 1/2, ..., 1/64, 0.01:
// 8 trials). The judging of a trial: an equilibrium (its displacement
// converged) is stable; a trial at its target ratio whose displacement
// still grows steadily (creep) is not, nor one that never reached it.

#include <talus/solver/strength_reduction.h>

#include <cmath>
#include <cstdio>

#include "../tests.h"

using namespace talus;

StrengthReductionTrial fake(double f, double limit)
{
  StrengthReductionTrial t;
  t.factor = f;
  t.stable = f < limit;
  return t;
}

int main()
{
  StrengthReductionSettings s;
  const double limit = 1.37;
  const auto stable_below = [&](double f) { return fake(f, limit); };

  StrengthReductionResult r = find_factor_of_safety(stable_below, s);
  std::printf("from F = 1: found %s, %zu trials (expected 10): %s\n", r.found ? "yes" : "no",
              r.trials.size(), talus_test::verdict(r.found && r.trials.size() == 10));
  talus_test::check("factor of safety", r.factor(), 1.369140625, 1e-12);
  std::printf("within the tolerance of 1.37: %s; bracket brackets it: %s\n",
              talus_test::verdict(std::abs(r.factor() - limit) <= s.tolerance * limit),
              talus_test::verdict(r.stable_factor < limit && r.unstable_factor >= limit));
  std::printf("trials:");
  for (const StrengthReductionTrial& t : r.trials)
    std::printf(" %.9g%s", t.factor, t.stable ? "s" : "u");
  std::printf("\n");

  s.initial_factor = 4.0;
  r = find_factor_of_safety(stable_below, s);
  std::printf("from F = 4: found %s, %zu trials (expected 11), F within the tolerance: %s\n",
              r.found ? "yes" : "no", r.trials.size(),
              talus_test::verdict(r.found && r.trials.size() == 11 &&
                                  std::abs(r.factor() - limit) <= s.tolerance * limit));

  s.initial_factor = 1.0;
  r = find_factor_of_safety([](double f) { return fake(f, 1e9); }, s);
  std::printf(
      "stable at every factor: found %s after %zu trials (last F = %g): %s\n",
      r.found ? "yes" : "no", r.trials.size(), r.trials.back().factor,
      talus_test::verdict(!r.found && r.trials.size() == 8 && r.trials.back().factor == 100));
  std::printf("  message: %s\n", r.failure.c_str());
  r = find_factor_of_safety([](double f) { return fake(f, 0.0); }, s);
  std::printf(
      "unstable at every factor: found %s after %zu trials (last F = %g): %s\n",
      r.found ? "yes" : "no", r.trials.size(), r.trials.back().factor,
      talus_test::verdict(!r.found && r.trials.size() == 8 && r.trials.back().factor == 0.01));

  // Judging: 1000 steps to the target; displacement converging
  // geometrically (equilibrium) or growing linearly (creep).
  DisplacementWatch settled, creeping;
  for (unsigned long n = 0; n <= 1000; n += 10)
  {
    settled.add(n, 1e-3 * (1.0 - std::exp(-double(n) / 80.0)));
    creeping.add(n, 1e-4 + 1e-6 * double(n));
  }
  const StrengthReductionTrial a = judge_trial(1.0, true, 1000, 8e-6, settled, 0.0);
  const StrengthReductionTrial b = judge_trial(1.0, true, 1000, 8e-6, creeping, 0.0);
  const StrengthReductionTrial c = judge_trial(1.0, false, 1000, 3e-3, settled, 0.0);
  std::printf("equilibrium: %s (growth %.1e of the displacement): %s\n",
              a.stable ? "stable" : "unstable", a.late_growth / a.displacement,
              talus_test::verdict(a.stable));
  std::printf("creeping at the target ratio: %s (growth %.2f of the displacement): %s\n",
              b.stable ? "stable" : "unstable", b.late_growth / b.displacement,
              talus_test::verdict(!b.stable));
  std::printf("target ratio not reached: %s: %s\n", c.stable ? "stable" : "unstable",
              talus_test::verdict(!c.stable));
  // At rest: 1e-12 m of round-off grown by half is below a rest
  // displacement of 1e-6 m.
  DisplacementWatch noise;
  noise.add(0, 0.0);
  noise.add(15, 1e-12);
  noise.add(18, 1.5e-12);
  std::printf("round-off at rest: %s: %s\n",
              judge_trial(1.0, true, 18, 9e-6, noise, 1e-6).stable ? "stable" : "unstable",
              talus_test::verdict(judge_trial(1.0, true, 18, 9e-6, noise, 1e-6).stable));
  std::printf("%s\n%s\n%s\n", trial_line(a).c_str(), trial_line(b).c_str(), trial_line(c).c_str());
}
