#pragma once

// A scalar function of model time that drives a boundary or a load: an
// input motion (a recorded velocity or acceleration, a harmonic shaking, a
// pulse) or a load that varies in time.

#include <limits>
#include <string>
#include <vector>

namespace talus
{

/// f(t) of model time t (s), evaluated once per step for each boundary or
/// load that has one; what multiplies the entry's constant ('Velocity',
/// 'Force', 'Pressure', 'Traction') is `scale(t)`:
/// - value input: scale(t) = f(t);
/// - acceleration input: f(t) is an acceleration (m/s^2) and scale(t) is its
///   integral from the start of the record (m/s), in closed form for each
///   kind (exact for the linearly interpolated table), with the baseline
///   correction if asked (see `baseline`).
/// The kinds of f:
/// - none: 1 (the constant input of old);
/// - table: samples (time, value) linearly interpolated; before the first
///   time the first value, after the last time the last value (a value
///   input) or 0 (an acceleration input: the record is all the shaking);
/// - harmonic: amplitude sin(2 pi frequency (t - start) + phase) for start
///   <= t <= end, 0 outside;
/// - pulse: a half sine, amplitude sin(pi (t - start) / duration) for start
///   <= t <= start + duration, 0 outside.
struct TimeFunction
{
  enum class Kind
  {
    none,
    table,
    harmonic,
    pulse
  };
  Kind kind = Kind::none;
  bool acceleration = false; ///< f is an acceleration whose integral is the scale

  std::vector<double> time;  ///< table: sample times (s), increasing
  std::vector<double> value; ///< table: f at those times

  double amplitude = 1.0;
  double frequency = 1.0;                               ///< harmonic (Hz)
  double phase = 0.0;                                   ///< harmonic (rad)
  double start = 0.0;                                   ///< harmonic and pulse (s)
  double end = std::numeric_limits<double>::infinity(); ///< harmonic (s); pulse: start + duration

  /// Baseline correction of an acceleration input: the constant
  /// acceleration `baseline` = v(T) / (T - T0) is taken off over the record
  /// [T0, T] (table: its first and last time; harmonic: start to end;
  /// pulse: the pulse), that is the straight line from 0 at T0 to the
  /// uncorrected final velocity v(T) at T is removed from the integrated
  /// velocity, so that the velocity is 0 from the end of the record on and
  /// the base does not drift away afterwards. 0: no correction.
  double baseline = 0.0;

  bool varies() const { return kind != Kind::none; }

  /// The input f(t) itself (m/s^2 for an acceleration input).
  double input(double t) const;

  /// What multiplies the entry's constant at model time t (see above).
  double scale(double t) const;

  /// The record's first and last time (s) over which an acceleration is
  /// integrated and a baseline taken off (infinite end: no end).
  double record_start() const;
  double record_end() const;

  /// Makes this an acceleration input; with `correct_baseline`, sets
  /// `baseline` from the uncorrected final velocity (the record must end).
  void integrate_acceleration(bool correct_baseline);

private:
  double integral(double t) const;         ///< uncorrected integral of f from the record's start
  std::vector<double> integral_at_sample_; ///< table: the integral at each sample time
};

/// Reads a time table from a CSV file: one sample a line, "time, value"
/// (two numbers, s and the input's unit); empty lines, lines starting with
/// '#' and a first line that is not numbers (a header) are skipped; at
/// least two samples, times strictly increasing. Throws InputError naming
/// the file, the line and what is wrong.
TimeFunction read_time_table(const std::string& path);

} // namespace talus
