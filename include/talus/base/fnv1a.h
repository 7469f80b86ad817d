#pragma once

#include <cstddef>
#include <cstdint>

namespace talus
{

/// FNV-1a, 64 bits: a fingerprint, not a cryptographic hash. Hashing two
/// pieces in turn, the first's hash the second's seed, hashes the two
/// joined.
inline std::uint64_t fnv1a(const void* data, std::size_t size,
                           std::uint64_t seed = 14695981039346656037ull)
{
  std::uint64_t h = seed;
  const unsigned char* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i)
    h = (h ^ p[i]) * 1099511628211ull;
  return h;
}

} // namespace talus
