#pragma once

#include <chrono>

namespace talus
{

/// Wall time since `start` (s), for the timings runs and benchmarks print.
inline double seconds_since(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace talus
