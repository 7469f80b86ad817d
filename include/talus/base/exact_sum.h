#pragma once

#include <array>
#include <cstdint>
#include <cstring>

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

  /// Inline, from the bits of x (a few integer operations): the energy
  /// account adds several terms per block and step.
  void add(double x)
  {
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    const unsigned int biased = static_cast<unsigned int>(bits >> 52) & 0x7ffu;
    if (biased == 0x7ffu)
    {
      add_special(x);
      return;
    }
    // |x| = m 2^(bit - 1074): a normal number's 53-bit significand at
    // biased exponent - 1, a subnormal's at bit 0.
    std::uint64_t m = bits & ((std::uint64_t(1) << 52) - 1);
    unsigned int bit = 0;
    if (biased != 0)
    {
      m |= std::uint64_t(1) << 52;
      bit = biased - 1;
    }
    else if (m == 0)
      return; // a zero
    const unsigned int w = bit / 32, shift = bit % 32;
    // m shifted spans at most three words (53 + 31 bits); the top one is
    // word 65 at most.
    const std::int64_t d0 = static_cast<std::int64_t>((m << shift) & 0xffffffffu);
    const std::int64_t d1 = static_cast<std::int64_t>((m >> (32 - shift)) & 0xffffffffu);
    const std::int64_t d2 = static_cast<std::int64_t>((m >> 32) >> (32 - shift));
    if (bits >> 63)
    {
      word_[w] -= d0;
      word_[w + 1] -= d1;
      word_[w + 2] -= d2;
    }
    else
    {
      word_[w] += d0;
      word_[w + 1] += d1;
      word_[w + 2] += d2;
    }
    if (++since_normalized_ >= (1u << 30))
      normalize();
  }
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

  /// Zero again.
  void clear() { *this = ExactSum(); }

private:
  /// An infinite or NaN term.
  void add_special(double x);

  std::array<std::int64_t, n_words> word_{};
  /// Terms that were +infinity, -infinity and NaN.
  std::array<std::int64_t, 3> special_{};
  unsigned int since_normalized_ = 0;
};

} // namespace talus
