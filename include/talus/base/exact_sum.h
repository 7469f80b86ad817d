#pragma once

#include <array>
#include <cstdint>

namespace talus
{

/// A sum of doubles that is exact until it is read, and then rounded once
/// (to nearest, ties to even): its value does not depend on the order of
/// the terms, nor on how they were split into partial sums and merged.
/// Global quantities of a model split among ranks (the mean weight behind
/// the unbalanced-force ratio, masses, energies) are summed with it, so
/// that a run gives the same bits on any number of ranks.
///
/// The terms are added into a fixed-point number that spans every double
/// (2^-1074 to 2^1024) in 32-bit digits held in 64-bit words, so that
/// about 2^31 terms can be added before the digits must carry. Partial
/// sums merge by adding their words (an MPI_SUM of words() across ranks
/// after normalize()).
class ExactSum
{
public:
  /// Words of 32 bits from 2^-1074 to above 2^1024, with room for the carry
  /// of 2^31 terms.
  static constexpr int n_words = 67;

  void add(double x);
  ExactSum& operator+=(double x)
  {
    add(x);
    return *this;
  }
  /// Adds another partial sum.
  ExactSum& operator+=(const ExactSum& other);

  /// The sum, rounded once to the nearest double. An infinite or NaN term
  /// makes it NaN or infinite as ordinary addition would.
  double value() const;

  /// Carries between words, so that each lies in [0, 2^32) but the last;
  /// the representation of a sum is then unique.
  void normalize();

  /// The words (normalised or not) and the count of non-finite terms, for
  /// a reduction across ranks.
  std::array<std::int64_t, n_words>& words() { return word_; }
  std::array<std::int64_t, 3>& special() { return special_; }

private:
  std::array<std::int64_t, n_words> word_{};
  /// Terms that were +infinity, -infinity and NaN.
  std::array<std::int64_t, 3> special_{};
  unsigned int since_normalized_ = 0;
};

} // namespace talus
