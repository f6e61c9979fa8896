// RockDEM engine: the CPU backend's touching pairs, four at a time with AVX2 (doubles).
//
// Compiled with -mavx2 -ffp-contract=off (Solver/CMakeLists.txt) and called only when the
// processor has AVX2 (touchingPairsAvx2Enabled, in CpuBackend.cpp). The law is
// dem::touchingPairForce (TouchingPair.h), instantiated here with a lane type of four
// doubles: each lane performs the operations of the scalar loop in the same order, and
// no multiply-add is fused (AVX2 does not imply FMA, and contraction is off), so each
// pair's results are the scalar loop's bits.
//
// This file includes no Eigen and no other header with inline functions shared with the
// default build: an out-of-line copy of such a function compiled here with AVX2 could be
// the one the linker keeps for the whole program. Its own functions are in an anonymous
// namespace or are templates instantiated with the AVX2 lane type only.
#include "backends/cpu/TouchingPair.h"

#include <immintrin.h>

#include <cstring>

namespace dem {
namespace {

typedef double F64x4 __attribute__((vector_size(32)));
using I64x4 = decltype(F64x4{} < F64x4{}); // the lanes' comparison masks

/// For a 4-bit set of lanes, those lanes in increasing order (the rest of the row unused):
/// the scan's lists without a branch per lane.
struct alignas(16) LaneList {
  std::uint32_t lane[4];
};
constexpr LaneList kLanesOf[16] = {
  { { 0, 0, 0, 0 } }, { { 0, 0, 0, 0 } }, { { 1, 0, 0, 0 } }, { { 0, 1, 0, 0 } },
  { { 2, 0, 0, 0 } }, { { 0, 2, 0, 0 } }, { { 1, 2, 0, 0 } }, { { 0, 1, 2, 0 } },
  { { 3, 0, 0, 0 } }, { { 0, 3, 0, 0 } }, { { 1, 3, 0, 0 } }, { { 0, 1, 3, 0 } },
  { { 2, 3, 0, 0 } }, { { 0, 2, 3, 0 } }, { { 1, 2, 3, 0 } }, { { 0, 1, 2, 3 } },
};

} // namespace

template <> struct LaneOps<F64x4> {
  using Mask = I64x4;
  static F64x4 broadcast(double x) { return F64x4{ x, x, x, x }; }
  static F64x4 sqrt(F64x4 x) { return (F64x4)_mm256_sqrt_pd((__m256d)x); }
  static F64x4 select(Mask m, F64x4 a, F64x4 b) { return m ? a : b; }
  static Mask both(Mask a, Mask b) { return a & b; }
  static bool any(Mask m) { return _mm256_movemask_pd((__m256d)m) != 0; }
  static bool all(Mask m) { return _mm256_movemask_pd((__m256d)m) == 0xf; }
};

namespace {

using Ops = LaneOps<F64x4>;
using V3 = Lane3<F64x4>;

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

} // namespace

std::size_t scanPairsAvx2(const TouchingPairArrays& a, std::size_t first, std::size_t last,
                          std::uint32_t* list, std::uint32_t* ended, std::size_t& endedCount)
{
  // The scalar loop's test, lane by lane: d2 > kApart (r_i + r_j)^2 (apart), else the
  // distance sqrt(d2) and the overlap r_i + r_j - distance; a pair touches unless it is
  // apart, its overlap is <= 0 or its distance is 0 (a NaN distance touches, as there).
  const F64x4 apartFactor = Ops::broadcast(kApart);
  std::size_t listed = 0;
  endedCount = 0;
  for (std::size_t k = first; k < last; k += 4) {
    const int lanes = last - k >= 4 ? 4 : static_cast<int>(last - k);
    const std::uint32_t* i = a.pairI + k;
    const std::uint32_t* j = a.pairJ + k;
    std::uint32_t padI[4], padJ[4];
    if (lanes < 4) { // the last pair repeated in the unused lanes (their results unused)
      for (int l = 0; l < 4; ++l) {
        padI[l] = i[l < lanes ? l : lanes - 1];
        padJ[l] = j[l < lanes ? l : lanes - 1];
      }
      i = padI;
      j = padJ;
    }
    const V3 branch = gather3(a.position, j) - gather3(a.position, i);
    const F64x4 reach = gather1(a.radius, i) + gather1(a.radius, j);
    const F64x4 distance2 = VecOps<V3>::squaredNorm(branch);
    const I64x4 apart = distance2 > apartFactor * (reach * reach);
    // The square root is taken in every lane (a lane that is apart ignores it): a branch on
    // "all four apart" was mispredicted about one group in ten.
    const F64x4 distance = Ops::sqrt(distance2);
    const F64x4 overlap = reach - distance;
    const I64x4 notTouching = apart | (overlap <= 0.0) | (distance == 0.0);
    // The lanes that touch go to `list`, those apart that may hold state to `ended`, in
    // lane order and without a branch per lane (the lanes' outcomes are data, and a branch
    // on each was mispredicted about one pair in four): each group writes four entries
    // and advances by the number it keeps (the lists have kScanSlack entries to spare).
    const unsigned validBits = (1u << lanes) - 1u;
    const unsigned apartBits = static_cast<unsigned>(_mm256_movemask_pd((__m256d)notTouching)) & validBits;
    const unsigned touchBits = ~apartBits & validBits;
    std::uint32_t live4 = 0; // the lanes' live bytes
    if (lanes == 4) {
      std::memcpy(&live4, a.live + k, 4);
    } else {
      for (int l = 0; l < lanes; ++l) {
        live4 |= static_cast<std::uint32_t>(a.live[k + static_cast<std::size_t>(l)]) << (8 * l);
      }
    }
    const unsigned deadBits = static_cast<unsigned>(
      _mm_movemask_epi8(_mm_cmpeq_epi8(_mm_cvtsi32_si128(static_cast<int>(live4)), _mm_setzero_si128())));
    const unsigned endBits = apartBits & ~deadBits & validBits;
    const __m128i base = _mm_set1_epi32(static_cast<int>(k));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(list + listed),
                     _mm_add_epi32(base, _mm_load_si128(reinterpret_cast<const __m128i*>(kLanesOf[touchBits].lane))));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(ended + endedCount),
                     _mm_add_epi32(base, _mm_load_si128(reinterpret_cast<const __m128i*>(kLanesOf[endBits].lane))));
    listed += static_cast<std::size_t>(__builtin_popcount(touchBits));
    endedCount += static_cast<std::size_t>(__builtin_popcount(endBits));
  }
  return listed;
}

void touchingPairsAvx2(const TouchingPairArrays& a, const std::uint32_t* list, std::size_t count)
{
  const F64x4 friction = Ops::broadcast(a.friction);
  const F64x4 dt = Ops::broadcast(a.dt);
  const F64x4 predict = Ops::broadcast(a.predict);
  for (std::size_t first = 0; first < count; first += 4) {
    const int lanes = count - first >= 4 ? 4 : static_cast<int>(count - first);
    // The pairs of the lanes; a last, partial group repeats its last pair in the unused
    // lanes (computed, never stored).
    std::uint32_t k[4], i[4], j[4];
    for (int l = 0; l < 4; ++l) {
      k[l] = list[first + (l < lanes ? l : lanes - 1)];
      i[l] = a.pairI[k[l]];
      j[l] = a.pairJ[k[l]];
    }
    const V3 positionI = gather3(a.position, i);
    const V3 positionJ = gather3(a.position, j);
    const V3 branch = positionJ - positionI; // plain differences (the caller checks the domain)
    const F64x4 radiusI = gather1(a.radius, i);
    const F64x4 radiusJ = gather1(a.radius, j);
    const F64x4 distance = Ops::sqrt(VecOps<V3>::squaredNorm(branch));
    const F64x4 overlap = (radiusI + radiusJ) - distance;
    const V3 velocityI = gather3(a.velocity, i);
    const V3 velocityJ = gather3(a.velocity, j);
    const V3 spinI = gather3(a.spin, i);
    const V3 spinJ = gather3(a.spin, j);
    const V3 lastForceI = gather3(a.lastForce, i);
    const V3 lastForceJ = gather3(a.lastForce, j);
    const V3 constants = gather3(a.constants, k);
    const TouchingPairInput<V3> in{ branch, distance, overlap, radiusI, radiusJ, velocityI,
      velocityJ, spinI, spinJ, lastForceI, lastForceJ, gather1(a.inverseMass, i),
      gather1(a.inverseMass, j), constants.x, constants.y, constants.z };
    V3 spring = gather3(a.spring, k);
    const TouchingPairResult<V3> r = touchingPairForce(in, a.hertz, friction, dt, predict, spring);
    scatter3(a.spring, k, spring, lanes);
    scatter3(a.force, k, r.force, lanes);
    scatter3(a.torqueI, k, r.torqueI, lanes);
    scatter3(a.torqueJ, k, r.torqueJ, lanes);
    alignas(32) double fn[4];
    _mm256_store_pd(fn, (__m256d)r.normalForce);
    for (int l = 0; l < lanes; ++l) {
      a.normal[k[l]] = fn[l];
      a.live[k[l]] = 1;
      if (fn[l] != 0.0) {
        // Two threads may mark the same particle: both write 1.
        __atomic_store_n(&a.touching[i[l]], std::uint8_t{ 1 }, __ATOMIC_RELAXED);
        __atomic_store_n(&a.touching[j[l]], std::uint8_t{ 1 }, __ATOMIC_RELAXED);
      }
    }
  }
}

} // namespace dem
