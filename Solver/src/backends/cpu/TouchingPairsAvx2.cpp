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
// default build (Avx2Lanes.h says why).
#include "backends/cpu/Avx2Lanes.h"
#include "backends/cpu/TouchingPair.h"

#include <cstring>

namespace dem {
namespace {
using Ops = LaneOps<F64x4>;

/// Lanes a, b, c, d transposed: row l holds (a[l], b[l], c[l], d[l]).
inline void transpose4(const F64x4& a, const F64x4& b, const F64x4& c, const F64x4& d, __m256d row[4])
{
  const __m256d ab02 = _mm256_unpacklo_pd((__m256d)a, (__m256d)b); // a0 b0 a2 b2
  const __m256d ab13 = _mm256_unpackhi_pd((__m256d)a, (__m256d)b); // a1 b1 a3 b3
  const __m256d cd02 = _mm256_unpacklo_pd((__m256d)c, (__m256d)d);
  const __m256d cd13 = _mm256_unpackhi_pd((__m256d)c, (__m256d)d);
  row[0] = _mm256_permute2f128_pd(ab02, cd02, 0x20);
  row[1] = _mm256_permute2f128_pd(ab13, cd13, 0x20);
  row[2] = _mm256_permute2f128_pd(ab02, cd02, 0x31);
  row[3] = _mm256_permute2f128_pd(ab13, cd13, 0x31);
}

/// The first `lanes` lanes' results stored to their dem::PairResult rows (8 doubles each,
/// 64-byte aligned: force, n x Ft, armI, armJ), two aligned stores per row.
inline void storeResults(double* rows, const std::uint32_t* k, const TouchingPairResult<V3>& r, int lanes)
{
  __m256d lo[4], hi[4];
  transpose4(r.force.x, r.force.y, r.force.z, r.normalCrossFt.x, lo);
  transpose4(r.normalCrossFt.y, r.normalCrossFt.z, r.armI, r.armJ, hi);
  for (int l = 0; l < lanes; ++l) {
    double* row = rows + 8 * static_cast<std::size_t>(k[l]);
    _mm256_store_pd(row, lo[l]);
    _mm256_store_pd(row + 4, hi[l]);
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
    const unsigned endBits = apartBits & ~zeroByteLanes(live4) & validBits;
    appendLanes(list, listed, k, touchBits);
    appendLanes(ended, endedCount, k, endBits);
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
    storeResults(a.result, k, r, lanes);
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
