#pragma once

#include <cmath>

namespace talus
{

/// The time history of a stress wave put in through a quiet boundary: the
/// normal stress of the incident wave (Pa, positive pushing into the block)
/// at model time t. Harmonic: amplitude sin(2 pi f (t - start)) from
/// `start` until `end` (end <= start: for ever). Half-sine pulse:
/// amplitude sin(pi (t - start) / duration) for t in [start, start +
/// duration), zero outside. None: zero.
struct WaveSignal
{
  enum class Kind
  {
    none,
    harmonic,
    half_sine
  };
  Kind kind = Kind::none;
  double amplitude = 0.0; ///< Pa
  double frequency = 0.0; ///< Hz (harmonic)
  double start = 0.0;     ///< s
  double end = 0.0;       ///< s (harmonic; <= start: no end)
  double duration = 0.0;  ///< s (half-sine pulse)

  bool active() const { return kind != Kind::none && amplitude != 0.0; }

  double operator()(double t) const
  {
    const double s = t - start;
    switch (kind)
    {
    case Kind::harmonic:
      if (s < 0.0 || (end > start && t >= end))
        return 0.0;
      return amplitude * std::sin(2.0 * M_PI * frequency * s);
    case Kind::half_sine:
      if (s < 0.0 || s >= duration)
        return 0.0;
      return amplitude * std::sin(M_PI * s / duration);
    case Kind::none:
      break;
    }
    return 0.0;
  }
};

} // namespace talus
