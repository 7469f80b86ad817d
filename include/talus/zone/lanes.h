#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

#if defined(__AVX__)
#include <immintrin.h>
#endif

namespace talus
{

/// W doubles handled by one vector instruction (GCC/Clang vector types):
/// the zone models work on W zones at once, one lane per zone. W is the
/// hardware's width (8 with AVX-512, else 4), as in the tet4 kernel.
#if defined(__AVX512F__)
constexpr unsigned int lane_count = 8;
#else
constexpr unsigned int lane_count = 4;
#endif
typedef double Lanes __attribute__((vector_size(lane_count * sizeof(double))));
/// Lane-wise comparison results (all bits set where true).
typedef std::int64_t LaneMask __attribute__((vector_size(lane_count * sizeof(double))));

inline Lanes broadcast(double x)
{
  return Lanes{} + x;
}

inline Lanes load_lanes(const double* p)
{
  Lanes v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

inline void store_lanes(double* p, const Lanes& v)
{
  std::memcpy(p, &v, sizeof v);
}

inline Lanes select(const LaneMask& where, const Lanes& yes, const Lanes& no)
{
  return where ? yes : no;
}

inline Lanes lane_abs(const Lanes& v)
{
  const LaneMask magnitude = LaneMask{} + INT64_MAX;
  return (Lanes)((LaneMask)v & magnitude);
}

/// |magnitude| with the sign of `sign`, lane by lane.
inline Lanes lane_copysign(const Lanes& magnitude, const Lanes& sign)
{
  const LaneMask sign_bit = LaneMask{} + INT64_MIN;
  return (Lanes)(((LaneMask)lane_abs(magnitude)) | ((LaneMask)sign & sign_bit));
}

inline Lanes lane_min(const Lanes& a, const Lanes& b)
{
  return a < b ? a : b;
}

inline Lanes lane_sqrt(const Lanes& v)
{
#if defined(__AVX512F__)
  return (Lanes)_mm512_maskz_sqrt_pd(
      0xff, (__m512d)v); // the plain form warns of an undefined source (GCC 12)
#elif defined(__AVX__)
  return (Lanes)_mm256_sqrt_pd((__m256d)v);
#else
  Lanes out;
  for (unsigned int l = 0; l < lane_count; ++l)
    out[l] = std::sqrt(v[l]);
  return out;
#endif
}

/// base[index[l]] lane by lane: one gather instruction where there is one
/// (an element-wise fallback goes through memory, which stalls the vector
/// load that follows). The masked forms: the plain ones make GCC 12 warn of
/// an uninitialised source.
inline Lanes gather_lanes(const double* base, const LaneMask& index)
{
#if defined(__AVX512F__)
  return (Lanes)_mm512_mask_i64gather_pd(_mm512_setzero_pd(), 0xff, (__m512i)index, base,
                                         sizeof(double));
#elif defined(__AVX2__)
  return (Lanes)_mm256_mask_i64gather_pd(_mm256_setzero_pd(), base, (__m256i)index,
                                         _mm256_castsi256_pd(_mm256_set1_epi64x(-1)),
                                         sizeof(double));
#else
  Lanes v;
  for (unsigned int l = 0; l < lane_count; ++l)
    v[l] = base[index[l]];
  return v;
#endif
}

/// True when any lane of the mask is set.
inline bool any(const LaneMask& m)
{
  for (unsigned int l = 0; l < lane_count; ++l)
    if (m[l] != 0)
      return true;
  return false;
}

} // namespace talus
