// RockDEM engine: the lane type of the CPU backend's AVX2 kernels (four doubles), its
// LaneOps (dem/ContactLawLanes.h) and the loads and stores of Vec3 arrays by index.
//
// Included only by the translation units compiled with -mavx2 -mno-fma -ffp-contract=off
// (TouchingPairsAvx2.cpp, IntactBondsAvx2.cpp): no Eigen and no header with inline
// functions shared with the default build (an out-of-line copy of such a function compiled
// with AVX2 could be the one the linker keeps for the whole program). The functions here
// are inline and exist only in those units.
#pragma once

#include "dem/ContactLawLanes.h"

#include <immintrin.h>

#include <cstddef>
#include <cstdint>

namespace dem {

typedef double F64x4 __attribute__((vector_size(32)));
using I64x4 = decltype(F64x4{} < F64x4{}); // the lanes' comparison masks

template <> struct LaneOps<F64x4> {
  using Mask = I64x4;
  static F64x4 broadcast(double x) { return F64x4{ x, x, x, x }; }
  static F64x4 sqrt(F64x4 x) { return (F64x4)_mm256_sqrt_pd((__m256d)x); }
  static F64x4 abs(F64x4 x) { return (F64x4)_mm256_andnot_pd(_mm256_set1_pd(-0.0), (__m256d)x); }
  static F64x4 select(Mask m, F64x4 a, F64x4 b) { return m ? a : b; }
  static Mask both(Mask a, Mask b) { return a & b; }
  static bool any(Mask m) { return _mm256_movemask_pd((__m256d)m) != 0; }
  static bool all(Mask m) { return _mm256_movemask_pd((__m256d)m) == 0xf; }
};

using V3 = Lane3<F64x4>; // three components of four lanes

/// One double per lane: a[idx[0..3]].
inline F64x4 gather1(const double* a, const std::uint32_t* idx)
{
  return (F64x4)_mm256_set_pd(a[idx[3]], a[idx[2]], a[idx[1]], a[idx[0]]);
}

/// Three doubles per lane (a Vec3 array): a[3 idx .. 3 idx + 2], transposed into x, y, z.
/// x and y come in as one 128-bit load per lane (never past the row's third double).
inline V3 gather3(const double* a, const std::uint32_t* idx)
{
  const double* r0 = a + 3 * static_cast<std::size_t>(idx[0]);
  const double* r1 = a + 3 * static_cast<std::size_t>(idx[1]);
  const double* r2 = a + 3 * static_cast<std::size_t>(idx[2]);
  const double* r3 = a + 3 * static_cast<std::size_t>(idx[3]);
  const __m256d xy02 = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(r0)), _mm_loadu_pd(r2), 1);
  const __m256d xy13 = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(r1)), _mm_loadu_pd(r3), 1);
  const __m256d x = _mm256_unpacklo_pd(xy02, xy13); // r0.x r1.x r2.x r3.x
  const __m256d y = _mm256_unpackhi_pd(xy02, xy13); // r0.y r1.y r2.y r3.y
  const __m256d z = _mm256_set_pd(r3[2], r2[2], r1[2], r0[2]);
  return { (F64x4)x, (F64x4)y, (F64x4)z };
}

/// The first `lanes` lanes of v stored to a[3 idx .. 3 idx + 2].
inline void scatter3(double* a, const std::uint32_t* idx, const V3& v, int lanes)
{
  const __m256d lo = _mm256_unpacklo_pd((__m256d)v.x, (__m256d)v.y); // x0 y0 x2 y2
  const __m256d hi = _mm256_unpackhi_pd((__m256d)v.x, (__m256d)v.y); // x1 y1 x3 y3
  alignas(32) double z[4];
  _mm256_store_pd(z, (__m256d)v.z);
  double* r0 = a + 3 * static_cast<std::size_t>(idx[0]);
  _mm_storeu_pd(r0, _mm256_castpd256_pd128(lo));
  r0[2] = z[0];
  if (lanes == 4) {
    double* r1 = a + 3 * static_cast<std::size_t>(idx[1]);
    double* r2 = a + 3 * static_cast<std::size_t>(idx[2]);
    double* r3 = a + 3 * static_cast<std::size_t>(idx[3]);
    _mm_storeu_pd(r1, _mm256_castpd256_pd128(hi));
    _mm_storeu_pd(r2, _mm256_extractf128_pd(lo, 1));
    _mm_storeu_pd(r3, _mm256_extractf128_pd(hi, 1));
    r1[2] = z[1];
    r2[2] = z[2];
    r3[2] = z[3];
    return;
  }
  if (lanes > 1) {
    double* r1 = a + 3 * static_cast<std::size_t>(idx[1]);
    _mm_storeu_pd(r1, _mm256_castpd256_pd128(hi));
    r1[2] = z[1];
  }
  if (lanes > 2) {
    double* r2 = a + 3 * static_cast<std::size_t>(idx[2]);
    _mm_storeu_pd(r2, _mm256_extractf128_pd(lo, 1));
    r2[2] = z[2];
  }
}

/// For a 4-bit set of lanes, those lanes in increasing order (the rest of the row unused):
/// the scan's lists without a branch per lane.
struct alignas(16) LaneList {
  std::uint32_t lane[4];
};
inline constexpr LaneList kLanesOf[16] = {
  { { 0, 0, 0, 0 } }, { { 0, 0, 0, 0 } }, { { 1, 0, 0, 0 } }, { { 0, 1, 0, 0 } },
  { { 2, 0, 0, 0 } }, { { 0, 2, 0, 0 } }, { { 1, 2, 0, 0 } }, { { 0, 1, 2, 0 } },
  { { 3, 0, 0, 0 } }, { { 0, 3, 0, 0 } }, { { 1, 3, 0, 0 } }, { { 0, 1, 3, 0 } },
  { { 2, 3, 0, 0 } }, { { 0, 2, 3, 0 } }, { { 1, 2, 3, 0 } }, { { 0, 1, 2, 3 } },
};


/// Appends k + l for each lane l set in `bits` (a 4-bit set), in increasing order, to
/// list[count...] without a branch per lane: writes four entries and advances `count` by
/// the number kept (the list needs four entries to spare).
inline void appendLanes(std::uint32_t* list, std::size_t& count, std::size_t k, unsigned bits)
{
  const __m128i base = _mm_set1_epi32(static_cast<int>(k));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(list + count),
                   _mm_add_epi32(base, _mm_load_si128(reinterpret_cast<const __m128i*>(kLanesOf[bits].lane))));
  count += static_cast<std::size_t>(__builtin_popcount(bits));
}

/// The lanes (a 4-bit set) whose byte in `bytes` (lane l in byte l) is zero.
inline unsigned zeroByteLanes(std::uint32_t bytes)
{
  return static_cast<unsigned>(_mm_movemask_epi8(
           _mm_cmpeq_epi8(_mm_cvtsi32_si128(static_cast<int>(bytes)), _mm_setzero_si128()))) & 0xfu;
}

} // namespace dem
