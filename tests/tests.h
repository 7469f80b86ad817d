#pragma once

// Shared by the .cc tests. Tests print what they check to standard output,
// which the test runner compares with name_NN.output (numdiff tolerances),
// and the figures behind a check to standard error, which it shows but does
// not compare. Kept free of deal.II headers so that a test compiles in
// seconds.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace talus_test
{

/// Under ctest, standard output goes to the file that deal.II's runner
/// compares (TALUS_TEST_OUTPUT, set by tests/CMakeLists.txt); the runner
/// otherwise compares standard output and standard error together. What a
/// test writes to standard error (steps to a convergence ratio, residuals,
/// the path of a collapse) depends on how the CPU rounds: the same code
/// built for AVX2 instead of AVX-512 takes 3,733 steps instead of 4,014 to
/// the same ratio. Run by hand, a test prints both to the terminal.
inline const bool standard_output_compared = []
{
  const char* file = std::getenv("TALUS_TEST_OUTPUT");
  return file != nullptr && std::freopen(file, "w", stdout) != nullptr;
}();

/// |computed - expected| / |expected| (the absolute error where expected is 0).
inline double relative_error(double computed, double expected)
{
  const double scale = std::max(std::abs(expected), 1e-300);
  return std::abs(computed - expected) / (expected == 0.0 ? 1.0 : scale);
}

/// "OK" where the check holds, else "WRONG" (which fails the comparison).
inline const char* verdict(bool holds)
{
  return holds ? "OK" : "WRONG";
}

/// "name: computed (exact expected, relative error e)" and then `end` to
/// `stream`.
inline void print_value(std::FILE* stream, const std::string& name, double computed,
                        double expected, const char* end)
{
  std::fprintf(stream, "%s: %.10g (exact %.10g, relative error %.1e)%s", name.c_str(), computed,
               expected, relative_error(computed, expected), end);
}

/// Prints "name: computed (expected), relative error e" and whether it is
/// within `tolerance`; the expected output holds the line, so a loss of
/// accuracy changes the output and fails the test.
inline void check(const std::string& name, double computed, double expected, double tolerance)
{
  print_value(stdout, name, computed, expected, " ");
  std::printf("%s\n", verdict(relative_error(computed, expected) <= tolerance));
}

/// For a value whose last digits follow the CPU's rounding (a static run
/// stopped at a ratio, a plastic or frictional path): prints "name: within
/// tolerance of expected" and whether it is, and the value itself with its
/// error to standard error, which is not compared (see above). check()
/// would print digits that differ between an AVX2 and an AVX-512 build.
inline void check_within(const std::string& name, double computed, double expected,
                         double tolerance)
{
  print_value(stderr, name, computed, expected, "\n");
  std::printf("%s: within %.2g of %.10g: %s\n", name.c_str(), tolerance, expected,
              verdict(relative_error(computed, expected) <= tolerance));
}

/// For a value whose last digits follow the CPU's rounding but whose error
/// is what the test reports (a discretization error found through a static
/// run or a plastic path): prints "name: relative error 9.0e-02" and
/// whether that is within `tolerance`, the error to two digits, and the
/// value with its error to standard error. Use it only where rounding moves
/// the error far less than the last printed digit, so that the two digits
/// are the same on every CPU and an accuracy regression still changes them.
inline void check_error(const std::string& name, double computed, double expected, double tolerance)
{
  print_value(stderr, name, computed, expected, "\n");
  const double error = relative_error(computed, expected);
  std::printf("%s: relative error %.1e %s\n", name.c_str(), error, verdict(error <= tolerance));
}

/// Largest deviation of any zone's stress (6 components a zone) from zone
/// 0's, over the largest stress component of zone 0: the patch tests'
/// measure of a uniform stress.
inline double stress_spread(const std::vector<double>& s)
{
  double scale = 0.0, spread = 0.0;
  for (int c = 0; c < 6; ++c)
    scale = std::max(scale, std::abs(s[c]));
  for (std::size_t z = 0; z < s.size() / 6; ++z)
    for (int c = 0; c < 6; ++c)
      spread = std::max(spread, std::abs(s[6 * z + c] - s[c]));
  return spread / scale;
}

} // namespace talus_test
