#include <talus/base/exact_sum.h>

#include <cmath>
#include <cstring>
#include <limits>

namespace talus
{

namespace
{

/// Bit 0 of the fixed-point number is 2^-1074, the least subnormal.
constexpr int lowest_exponent = -1074;

/// GCC's 128-bit integer: its conversion to double rounds once, to nearest.
__extension__ using Wide = unsigned __int128;

} // namespace

void ExactSum::add_special(double x)
{
  ++special_[std::isnan(x) ? 2 : (x > 0.0 ? 0 : 1)];
}

ExactSum& ExactSum::operator+=(const ExactSum& other)
{
  ExactSum o = other;
  o.normalize();
  normalize();
  for (int k = 0; k < n_words; ++k)
    word_[k] += o.word_[k];
  for (int k = 0; k < 3; ++k)
    special_[k] += o.special_[k];
  normalize();
  return *this;
}

void ExactSum::normalize()
{
  for (int k = 0; k + 1 < n_words; ++k)
  {
    // Floor division by 2^32: the digit left is in [0, 2^32).
    const std::int64_t carry = word_[k] >> 32; // arithmetic shift: floor
    word_[k] -= carry * (std::int64_t(1) << 32);
    word_[k + 1] += carry;
  }
  since_normalized_ = 0;
}

double ExactSum::value() const
{
  if (special_[2] > 0 || (special_[0] > 0 && special_[1] > 0))
    return std::numeric_limits<double>::quiet_NaN();
  if (special_[0] > 0)
    return std::numeric_limits<double>::infinity();
  if (special_[1] > 0)
    return -std::numeric_limits<double>::infinity();
  ExactSum s = *this;
  s.normalize();
  // The sign is the top word's; a negative sum is negated digit by digit
  // (two's complement over the words), then normalised again.
  const bool negative = s.word_[n_words - 1] < 0;
  if (negative)
  {
    for (int k = 0; k < n_words; ++k)
      s.word_[k] = -s.word_[k];
    s.normalize();
  }
  int top = n_words - 1;
  while (top >= 0 && s.word_[top] == 0)
    --top;
  if (top < 0)
    return 0.0;
  // The leading three words (64 to 96 bits) hold more than the 53 bits of
  // a double and its rounding bit; any nonzero word below them sets the
  // lowest bit (a sticky bit), so that the one conversion below rounds as
  // the exact sum would.
  Wide lead = 0;
  for (int k = top; k > top - 3; --k)
    lead = (lead << 32) | static_cast<std::uint32_t>(k >= 0 ? s.word_[k] : 0);
  bool sticky = false;
  for (int k = top - 3; k >= 0; --k)
    sticky |= s.word_[k] != 0;
  if (sticky)
    lead |= 1;
  // Bit 0 of `lead` is 2^(32 (top - 2) - 1074). The conversion of a
  // 128-bit integer to double rounds to nearest even; ldexp is then exact
  // (or gives the subnormal the exact sum rounds to, the lead being
  // exact whenever the sum is that small).
  const double rounded = static_cast<double>(lead);
  const double sum = std::ldexp(rounded, 32 * (top - 2) + lowest_exponent);
  return negative ? -sum : sum;
}

} // namespace talus
