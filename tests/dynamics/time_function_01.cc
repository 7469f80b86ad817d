// The time functions of input motions (issue 23, talus/model/time_history.h):
// a table read from a CSV file (comment, header, CR LF line ends) gives its
// samples exactly, linear interpolation between them, the first value
// before and the last after; the harmonic and the half-sine pulse give
// their formulas (0 outside their span); an acceleration input integrates
// in closed form (a table exactly for its linear interpolation, checked
// against a fine trapezoid sum; the harmonic and the pulse against theirs),
// and the baseline correction of a record with a net velocity brings the
// velocity after the record to zero to round-off (uncorrected it ends at
// the record's net velocity). Before issue 23 there was no such header.

#include <talus/base/exceptions.h>
#include <talus/model/time_history.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "../tests.h"

namespace
{
constexpr double pi = 3.14159265358979323846;

/// Largest |f - g| over [t0, t1] in n + 1 points.
template <typename F, typename G>
double largest_difference(F f, G g, double t0, double t1, int n = 2000)
{
  double worst = 0.0;
  for (int k = 0; k <= n; ++k)
  {
    const double t = t0 + (t1 - t0) * k / n;
    worst = std::max(worst, std::abs(f(t) - g(t)));
  }
  return worst;
}

/// The integral of `a` from t0 to t by a fine trapezoid sum (t up to the
/// end of the record: a jump there would cost it half a step).
template <typename F>
double trapezoid(F a, double t0, double t, int n = 200000)
{
  if (t <= t0)
    return 0.0;
  const double h = (t - t0) / n;
  double sum = 0.5 * (a(t0) + a(t));
  for (int k = 1; k < n; ++k)
    sum += a(t0 + k * h);
  return sum * h;
}

void report(const char* what, double error, double tolerance)
{
  std::fprintf(stderr, "%s: error %.3g\n", what, error);
  std::printf("%s within %.0e: %s\n", what, tolerance, talus_test::verdict(error <= tolerance));
}
} // namespace

int main()
{
  // A table with a comment, a header and Windows line ends.
  {
    std::FILE* f = std::fopen("time_table.csv", "w");
    std::fputs("# a record\r\ntime (s), acceleration (m/s^2)\r\n0.5, 1\r\n1.0, 3\r\n\r\n"
               "2.0, -1\r\n2.5, 2\r\n",
               f);
    std::fclose(f);
  }
  talus::TimeFunction table = talus::read_time_table("time_table.csv");
  const double samples[4][2] = {{0.5, 1.0}, {1.0, 3.0}, {2.0, -1.0}, {2.5, 2.0}};
  double sample_error = 0.0;
  for (const auto& s : samples)
    sample_error = std::max(sample_error, std::abs(table.input(s[0]) - s[1]));
  report("table: the samples", sample_error, 1e-15);
  report("table: between samples (1.5 s: 1, 2.25 s: 0.5)",
         std::max(std::abs(table.scale(1.5) - 1.0), std::abs(table.scale(2.25) - 0.5)), 1e-15);
  report("table: the first value before, the last after",
         std::max(std::abs(table.scale(0.0) - 1.0), std::abs(table.scale(9.0) - 2.0)), 0.0);

  talus::TimeFunction harmonic;
  harmonic.kind = talus::TimeFunction::Kind::harmonic;
  harmonic.amplitude = 2.0;
  harmonic.frequency = 3.0;
  harmonic.phase = 30.0 * pi / 180.0;
  harmonic.start = 0.2;
  harmonic.end = 1.2;
  const auto harmonic_formula = [](double t)
  { return t < 0.2 || t > 1.2 ? 0.0 : 2.0 * std::sin(2.0 * pi * 3.0 * (t - 0.2) + pi / 6.0); };
  report(
      "harmonic: 2 sin(2 pi 3 (t - 0.2) + 30 deg) on [0.2, 1.2], 0 outside",
      largest_difference([&](double t) { return harmonic.scale(t); }, harmonic_formula, 0.0, 1.5),
      1e-13);
  talus::TimeFunction pulse;
  pulse.kind = talus::TimeFunction::Kind::pulse;
  pulse.amplitude = 4.0;
  pulse.start = 0.1;
  pulse.end = 0.6;
  const auto pulse_formula = [](double t)
  { return t < 0.1 || t > 0.6 ? 0.0 : 4.0 * std::sin(pi * (t - 0.1) / 0.5); };
  report("pulse: 4 sin(pi (t - 0.1) / 0.5) on [0.1, 0.6], 0 outside",
         largest_difference([&](double t) { return pulse.scale(t); }, pulse_formula, 0.0, 1.0),
         1e-13);

  // Acceleration inputs: the velocity is the integral.
  talus::TimeFunction table_velocity = table;
  table_velocity.integrate_acceleration(false);
  const auto table_acceleration = [&](double t)
  { return t < 0.5 || t > 2.5 ? 0.0 : table.input(t); };
  report("table acceleration: its integral",
         largest_difference([&](double t) { return table_velocity.scale(t); },
                            [&](double t)
                            { return trapezoid(table_acceleration, 0.5, std::min(t, 2.5)); },
                            0.0, 3.0, 300),
         1e-9);
  talus::TimeFunction harmonic_velocity = harmonic;
  harmonic_velocity.integrate_acceleration(false);
  report("harmonic acceleration: its integral",
         largest_difference([&](double t) { return harmonic_velocity.scale(t); },
                            [&](double t)
                            { return trapezoid(harmonic_formula, 0.2, std::min(t, 1.2)); },
                            0.0, 1.5, 300),
         1e-9);
  talus::TimeFunction pulse_velocity = pulse;
  pulse_velocity.integrate_acceleration(false);
  report("pulse acceleration: its integral",
         largest_difference([&](double t) { return pulse_velocity.scale(t); },
                            [&](double t)
                            { return trapezoid(pulse_formula, 0.1, std::min(t, 0.6)); },
                            0.0, 1.0, 300),
         1e-9);

  // Baseline correction: the table's record has a net velocity of 2.25 m/s.
  const double net = table_velocity.scale(3.0);
  report("table acceleration: net velocity 2.25 m/s uncorrected", std::abs(net - 2.25), 1e-15);
  talus::TimeFunction corrected = table;
  corrected.integrate_acceleration(true);
  report("table acceleration, baseline corrected: velocity at and after the record's end",
         std::max(std::abs(corrected.scale(2.5)), std::abs(corrected.scale(7.0))), 1e-15);
  report("baseline corrected: the line v(T) (t - T0) / (T - T0) taken off (at 1.5 s)",
         std::abs(corrected.scale(1.5) - (table_velocity.scale(1.5) - 2.25 * (1.0 / 2.0))), 1e-15);
  talus::TimeFunction corrected_pulse = pulse;
  corrected_pulse.integrate_acceleration(true);
  report("pulse acceleration, baseline corrected: velocity after the pulse",
         std::abs(corrected_pulse.scale(0.9)), 1e-15);
}
