#pragma once

// Shared by the .cc tests. Tests print what they check to standard output,
// which the test runner compares with name_NN.output (numdiff tolerances).
// Kept free of deal.II headers so that a test compiles in seconds.

#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>

namespace talus_test
{

/// Prints "name: computed (expected), relative error e" and whether it is
/// within `tolerance`; the expected output holds the line, so a loss of
/// accuracy changes the output and fails the test.
inline void check(const std::string& name, double computed, double expected, double tolerance)
{
  const double scale = std::max(std::abs(expected), 1e-300);
  const double error = std::abs(computed - expected) / (expected == 0.0 ? 1.0 : scale);
  std::printf("%s: %.10g (exact %.10g, relative error %.1e) %s\n", name.c_str(), computed, expected,
              error, error <= tolerance ? "OK" : "WRONG");
}

} // namespace talus_test
