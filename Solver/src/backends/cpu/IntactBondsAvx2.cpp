// RockDEM engine: the CPU backend's intact bonds, four at a time with AVX2 (doubles).
//
// Compiled with -mavx2 -mno-fma -ffp-contract=off (Solver/CMakeLists.txt) and called only
// when the processor has AVX2 (touchingPairsAvx2Enabled, in CpuBackend.cpp). The step is
// dem::bondAxis, dem::advanceBond and dem::bondLoads (IntactBond.h) with the law of
// dem/BondLawLanes.h, instantiated here with a lane type of four doubles: each lane
// performs the operations of the scalar loop in the same order without fused
// multiply-adds, so each bond's results are the scalar loop's bits. A group of four in
// which a bond breaks stores nothing and goes back to the scalar loop, which records the
// failure (rare: a bond breaks once).
//
// This file includes no Eigen and no other header with inline functions shared with the
// default build (Avx2Lanes.h says why).
#include "backends/cpu/Avx2Lanes.h"
#include "backends/cpu/IntactBond.h"

#include <cmath>
#include <cstring>

namespace dem {
namespace {

using Ops = LaneOps<F64x4>;

/// Bonds scanned at a time: the list of those stepped here lives on the stack.
constexpr std::size_t kScanBlock = 256;

/// One double per lane stored to a[idx[0..lanes)].
inline void scatter1(double* a, const std::uint32_t* idx, F64x4 v, int lanes)
{
  alignas(32) double lane[4];
  _mm256_store_pd(lane, (__m256d)v);
  for (int l = 0; l < lanes; ++l) {
    a[idx[l]] = lane[l];
  }
}

/// tan(friction angle) per lane, computed once for a run of equal angles (most bonds of a
/// rock share one angle; the tangent was about 6 % of a cemented specimen's step). The
/// scalar bond loop keeps the same two values itself: a non-template function shared with
/// it from a header would be compiled here with AVX2 too, and that copy could be the one
/// the linker keeps (Avx2Lanes.h).
struct TanCache {
  double angle = std::nan("");
  double tangent = 0.0;
  F64x4 of(const double* frictionAngle, const std::uint32_t* idx)
  {
    alignas(32) double lane[4];
    for (int l = 0; l < 4; ++l) {
      const double phi = frictionAngle[idx[l]];
      if (!(phi == angle)) {
        angle = phi;
        tangent = std::tan(phi);
      }
      lane[l] = tangent;
    }
    return (F64x4)_mm256_load_pd(lane);
  }
};

/// Bonds [first, last) sorted, four at a time and without a branch per bond: the intact,
/// brittle and undamaged ones to `list`, the other intact ones to `rest` (both advanced by
/// the number kept; each holds last - first + 4 entries). Returns the count listed.
std::size_t scanBonds(const IntactBondArrays& a, std::size_t first, std::size_t last, std::uint32_t* list,
                      std::uint32_t* rest, std::size_t& restCount)
{
  std::size_t listed = 0;
  for (std::size_t k = first; k < last; k += 4) {
    const int lanes = last - k >= 4 ? 4 : static_cast<int>(last - k);
    const unsigned validBits = (1u << lanes) - 1u;
    std::uint32_t failure4 = 0; // the lanes' failure bytes
    alignas(32) double softening[4] = { 0.0, 0.0, 0.0, 0.0 };
    alignas(32) double damage[4] = { 0.0, 0.0, 0.0, 0.0 };
    std::memcpy(&failure4, a.failure + k, static_cast<std::size_t>(lanes));
    std::memcpy(softening, a.softening + k, sizeof(double) * static_cast<std::size_t>(lanes));
    std::memcpy(damage, a.damage + k, sizeof(double) * static_cast<std::size_t>(lanes));
    const unsigned intactBits = zeroByteLanes(failure4) & validBits;
    // The scalar loop's tests: softening when the ratio is > 0, the share applied when damage > 0.
    const F64x4 zero = Ops::broadcast(0.0);
    const I64x4 special = ((F64x4)_mm256_load_pd(softening) > zero) | ((F64x4)_mm256_load_pd(damage) > zero);
    const unsigned specialBits = static_cast<unsigned>(_mm256_movemask_pd((__m256d)special));
    appendLanes(list, listed, k, intactBits & ~specialBits);
    appendLanes(rest, restCount, k, intactBits & specialBits);
  }
  return listed;
}

} // namespace

std::size_t intactBondsAvx2(const IntactBondArrays& a, std::size_t first, std::size_t last, std::uint32_t* rest)
{
  const F64x4 dt = Ops::broadcast(a.dt);
  TanCache tanFriction;
  std::size_t restCount = 0;
  std::uint32_t list[kScanBlock + 4];
  for (std::size_t blockStart = first; blockStart < last; blockStart += kScanBlock) {
    const std::size_t blockEnd = last - blockStart > kScanBlock ? blockStart + kScanBlock : last;
    const std::size_t count = scanBonds(a, blockStart, blockEnd, list, rest, restCount);
    for (std::size_t group = 0; group < count; group += 4) {
      const int lanes = count - group >= 4 ? 4 : static_cast<int>(count - group);
      // The bonds of the lanes; a last, partial group repeats its last bond in the unused
      // lanes (computed, never stored).
      std::uint32_t k[4], i[4], j[4];
      for (int l = 0; l < 4; ++l) {
        k[l] = list[group + static_cast<std::size_t>(l < lanes ? l : lanes - 1)];
        i[l] = a.bondI[k[l]];
        j[l] = a.bondJ[k[l]];
      }
      V3 branch = gather3(a.position, j) - gather3(a.position, i); // dem::minimumImage, no periodic axis
      if (a.planar) {
        branch.z = F64x4{};
      }
      const BondAxis<V3> axis = bondAxis(branch, gather1(a.radius, i), gather1(a.radius, j));
      const F64x4 bondRadius = gather1(a.bondRadius, k);
      const BondSectionLanes<F64x4> section = bondSectionLanes(bondRadius, a.planar, a.slab);
      F64x4 normalForce = gather1(a.normalForce, k);
      V3 shearForce = gather3(a.shearForce, k);
      F64x4 twistingMoment = gather1(a.twistingMoment, k);
      V3 bendingMoment = gather3(a.bendingMoment, k);
      advanceBond(axis, section, gather1(a.normalStiffness, k), gather1(a.shearStiffness, k), a.planar,
                  gather3(a.velocity, i), gather3(a.velocity, j), gather3(a.spin, i), gather3(a.spin, j), dt,
                  normalForce, shearForce, twistingMoment, bendingMoment);
      const BondStressesLanes<F64x4> stresses = bondStressesLanes<V3>(
        section, bondRadius, normalForce, shearForce, twistingMoment, bendingMoment, gather1(a.momentContribution, k));
      const I64x4 fails = failsInTensionLanes(stresses, gather1(a.tensileStrength, k)) |
        failsInShearLanes(stresses, gather1(a.cohesion, k), tanFriction.of(a.frictionAngle, k));
      const unsigned validBits = (1u << lanes) - 1u;
      if ((static_cast<unsigned>(_mm256_movemask_pd((__m256d)fails)) & validBits) != 0) {
        // A bond of the group breaks: the scalar loop steps all of them from their stored state.
        for (int l = 0; l < lanes; ++l) {
          rest[restCount++] = k[l];
        }
        continue;
      }
      const BondLoads<V3> loads = bondLoads(axis, normalForce, shearForce, twistingMoment, bendingMoment);
      scatter1(a.normalForce, k, normalForce, lanes);
      scatter3(a.shearForce, k, shearForce, lanes);
      scatter1(a.twistingMoment, k, twistingMoment, lanes);
      scatter3(a.bendingMoment, k, bendingMoment, lanes);
      scatter3(a.force, k, loads.force, lanes);
      scatter3(a.torqueI, k, loads.torqueI, lanes);
      scatter3(a.torqueJ, k, loads.torqueJ, lanes);
    }
  }
  return restCount;
}

} // namespace dem
