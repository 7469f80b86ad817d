// ExactSum: a sum of doubles whose value does not depend on the order of
// its terms or on how partial sums are merged (the global sums of a model
// split among ranks), rounded once from the exact sum.
//
// Known exact sums: 1e100 + 1 - 1e100 = 1 in every order (plain addition
// gives 0 in some); ten times 0.1 rounds to 1 (plain addition gives
// 0.9999999999999999); 400,000 random doubles from 1e-300 to 1e300 with
// their negatives and the integers 1 to 1000 sum to 500,500 exactly; ties
// round to even, and a bit far below a tie rounds up; subnormals add
// exactly; infinities and NaN as in plain addition. Then 10^6 random terms
// summed in their order, reversed, shuffled and as seven merged partial
// sums give the same bits.

#include <talus/base/exact_sum.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "../tests.h"

using namespace talus;

namespace
{

double exact(const std::vector<double>& terms)
{
  ExactSum s;
  for (double x : terms)
    s += x;
  return s.value();
}

double plain(const std::vector<double>& terms)
{
  double s = 0.0;
  for (double x : terms)
    s += x;
  return s;
}

bool same_bits(double a, double b)
{
  return std::memcmp(&a, &b, sizeof a) == 0;
}

void report(const char* what, bool holds)
{
  std::printf("%s: %s\n", what, talus_test::verdict(holds));
}

} // namespace

int main()
{
  std::mt19937_64 random(24);
  {
    std::vector<double> t{1e100, 1.0, -1e100};
    std::sort(t.begin(), t.end());
    bool all = true, plain_wrong = false;
    do
    {
      all &= exact(t) == 1.0;
      plain_wrong |= plain(t) != 1.0;
    } while (std::next_permutation(t.begin(), t.end()));
    report("1e100 + 1 - 1e100 = 1 in all six orders", all);
    report("  (plain addition misses it in some)", plain_wrong);
  }
  {
    const std::vector<double> t(10, 0.1);
    report("ten times 0.1 rounds to 1", exact(t) == 1.0);
    report("  (plain addition gives 0.9999999999999999)", plain(t) == 0.9999999999999999);
  }
  {
    std::vector<double> t;
    std::uniform_real_distribution<double> exponent(-300.0, 300.0), unit(1.0, 10.0);
    for (int i = 0; i < 200000; ++i)
    {
      const double x = unit(random) * std::pow(10.0, exponent(random));
      t.push_back(x);
      t.push_back(-x);
    }
    for (int i = 1; i <= 1000; ++i)
      t.push_back(i);
    std::shuffle(t.begin(), t.end(), random);
    report("400,000 terms that cancel and 1 + 2 + ... + 1000 give 500500 exactly",
           exact(t) == 500500.0);
    for (double& x : t)
      x = -x;
    report("  and their negatives -500500", exact(t) == -500500.0);
  }
  {
    const double half_ulp = std::ldexp(1.0, -53);
    report("1 + 2^-53 (a tie) rounds to even: 1", exact({1.0, half_ulp}) == 1.0);
    report("1 + 2^-53 + 2^-200 rounds up: 1 + 2^-52",
           exact({1.0, half_ulp, std::ldexp(1.0, -200)}) == 1.0 + std::ldexp(1.0, -52));
    report("-(1 + 2^-53 + 2^-200) rounds down: -(1 + 2^-52)",
           exact({-1.0, -half_ulp, -std::ldexp(1.0, -200)}) == -1.0 - std::ldexp(1.0, -52));
    const double tiny = std::numeric_limits<double>::denorm_min();
    report("three least subnormals are 3 of them", exact({tiny, tiny, tiny}) == 3 * tiny);
    const double least_normal = std::numeric_limits<double>::min();
    report("least normal - least subnormal + least subnormal",
           exact({least_normal, -tiny, tiny}) == least_normal);
    report("largest double + largest double overflows to infinity",
           std::isinf(
               exact({std::numeric_limits<double>::max(), std::numeric_limits<double>::max()})));
    const double inf = std::numeric_limits<double>::infinity();
    report("1 + infinity = infinity, infinity - infinity and NaN are NaN",
           exact({1.0, inf}) == inf && std::isnan(exact({inf, -inf})) &&
               std::isnan(exact({1.0, std::nan("")})));
    report("nothing, and 0 - 0, are 0", exact({}) == 0.0 && exact({0.0, -0.0}) == 0.0);
  }
  {
    std::vector<double> t(1000000);
    std::uniform_real_distribution<double> exponent(-30.0, 30.0), unit(-1.0, 1.0);
    for (double& x : t)
      x = unit(random) * std::pow(10.0, exponent(random));
    const double forward = exact(t);
    bool same = true;
    std::vector<double> r(t.rbegin(), t.rend());
    same &= same_bits(exact(r), forward);
    for (int k = 0; k < 3; ++k)
    {
      std::shuffle(r.begin(), r.end(), random);
      same &= same_bits(exact(r), forward);
    }
    // Seven partial sums (uneven pieces, as ranks would hold), merged in
    // two orders.
    std::vector<ExactSum> part(7);
    for (std::size_t i = 0; i < r.size(); ++i)
      part[(i * i) % 7] += r[i];
    ExactSum up, down;
    for (int k = 0; k < 7; ++k)
    {
      up += part[k];
      down += part[6 - k];
    }
    same &= same_bits(up.value(), forward) && same_bits(down.value(), forward);
    double plain_forward = plain(t),
           plain_reversed = plain(std::vector<double>(t.rbegin(), t.rend()));
    report("10^6 terms in order, reversed, shuffled and as merged partial sums: the same bits",
           same);
    report("  (plain addition differs between orders)", !same_bits(plain_forward, plain_reversed));
    std::fprintf(stderr, "exact %.17g, plain %.17g and %.17g\n", forward, plain_forward,
                 plain_reversed);
  }
}
