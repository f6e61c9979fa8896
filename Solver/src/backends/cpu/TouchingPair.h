// RockDEM engine: the force of one touching particle pair, written once for a vector type
// V (dem/ContactLawLanes.h): the CPU backend's scalar pair loop runs it on Eigen's Vector3d,
// its AVX2 kernel (TouchingPairsAvx2.cpp) on dem::Lane3 of four doubles per lane (four
// pairs at once) with the same operations in the same order, so both give the same bits
// (and the Vulkan backend's GLSL twin the same again). No Eigen here: the AVX2 translation
// unit includes this header. SI units.
#pragma once

#include "dem/ContactLawLanes.h"

#include <cstddef>
#include <cstdint>

namespace dem {

/// What the pair law reads of one pair (i < j), per lane; V is the vector type
/// (dem/ContactLawLanes.h), S its lane type. The vectors are references (to the scalar
/// loop's arrays, or to the kernel's lanes): copied into the structure, the scalar loop's
/// Vector3d inputs went through memory once more per pair (+1.5 % instructions).
template <class V, class S = typename VecOps<V>::Scalar> struct TouchingPairInput {
  const V& branch;   ///< m, from i to j (minimum image)
  S distance;        ///< m, |branch| > 0
  S overlap;         ///< m, r_i + r_j - distance > 0
  S radiusI, radiusJ;
  const V& velocityI;  ///< m/s, half-step velocities
  const V& velocityJ;
  const V& spinI;      ///< rad/s
  const V& spinJ;
  const V& lastForceI; ///< N, the forces of the last step
  const V& lastForceJ;
  S inverseMassI, inverseMassJ;  ///< 1/kg
  S normalStiffness, normalDamping, tangentialStiffness; ///< dem::ContactConstants
};

/// What it gives: the normal (unit, from i to j), the normal force magnitude, the force on
/// i (j gets the opposite), and n x Ft with the two arms: the torques about the centres are
/// armI (n x Ft) and armJ (n x Ft), which the gather multiplies out (dem::PairResult). The
/// spring (m) is updated in place.
template <class V, class S = typename VecOps<V>::Scalar> struct TouchingPairResult {
  V normal;
  S normalForce;
  V force;
  V normalCrossFt;
  S armI, armJ;
};

/// The pair law of a touching pair: relative velocity at the contact point, the normal
/// response of `hertz` (else linear) with the velocity predicted to the full step for its
/// damping, the Mindlin-Coulomb spring with the half-step slip over `dt`, the torques.
/// `predict` (s) is half the step (0 outside a real step, as `dt`).
template <class V, class S = typename VecOps<V>::Scalar>
ROCKDEM_INLINE_LAW TouchingPairResult<V> touchingPairForce(const TouchingPairInput<V>& in, bool hertz,
                                                           const S& friction, const S& dt,
                                                           const S& predict, V& spring)
{
  using O = VecOps<V>;
  const V normal = O::divided(in.branch, in.distance);
  const S armI = in.radiusI - 0.5 * in.overlap; // m, centre to contact point
  const S armJ = in.radiusJ - 0.5 * in.overlap;
  // Slip over the step uses the half-step velocities (exact for the displacement
  // increment); the viscous damping uses the full-step velocities, predicted from the
  // last forces, so that restitution does not drift with the number of steps per impact.
  const V relativeVelocity = in.velocityI - in.velocityJ +
    O::cross(in.spinI, O::scaled(armI, normal)) + O::cross(in.spinJ, O::scaled(armJ, normal));
  const V predictedVelocity = relativeVelocity +
    O::scaled(predict, O::scaled(in.inverseMassI, in.lastForceI) - O::scaled(in.inverseMassJ, in.lastForceJ));
  const S approachSpeed = O::dot(predictedVelocity, normal);
  const NormalResponseLanes<S> response = hertz
    ? hertzMindlinResponseLanes(in.normalStiffness, in.normalDamping, in.tangentialStiffness,
                                in.overlap, approachSpeed)
    : linearResponseLanes(in.normalStiffness, in.normalDamping, in.tangentialStiffness,
                          in.overlap, approachSpeed);
  const S fn = response.force;
  const V slip = O::scaled(dt, inPlaneLanes(relativeVelocity, normal));
  const V ft = mindlinCoulombForceLanes(response.tangentialStiffness, friction, fn, normal, slip, spring);
  const V normalCrossFt = O::cross(normal, ft);
  const S minusFn = -fn;
  return { normal, fn, O::scaled(minusFn, normal) + ft, normalCrossFt, armI, armJ };
}

/// The pair arrays of the CPU backend as plain doubles (a Vec3 is three doubles), for the
/// AVX2 kernel, which includes no Eigen.
struct TouchingPairArrays {
  const double* position;    ///< 3 per particle
  const double* velocity;    ///< 3 per particle
  const double* spin;        ///< 3 per particle
  const double* lastForce;   ///< 3 per particle
  const double* radius;
  const double* inverseMass;
  const std::uint32_t* pairI;
  const std::uint32_t* pairJ;
  const double* constants;   ///< dem::ContactConstants: 3 per pair
  double* spring;            ///< 3 per pair
  double* result;            ///< dem::PairResult: 8 per pair (force, n x Ft, armI, armJ)
  double* normal;            ///< 1 per pair
  std::uint8_t* live;        ///< 1 per pair
  std::uint8_t* touching;    ///< 1 per particle
  bool hertz;
  double friction;
  double dt;
  double predict;
};

/// A pair whose squared distance d2 exceeds kApart * (r_i + r_j)^2, each product rounded,
/// does not touch, and the square root would have said so too: with s = r_i + r_j (a
/// double) and u = 2^-53, the two roundings leave the right-hand side above
/// (1 + 2^-50)(1 - u)^2 s^2 > s^2, so sqrt(d2) > s exactly, its correctly rounded value is
/// >= s, and the overlap s - distance is <= 0. Pairs between the bounds take the square
/// root, so the rejection changes no bit.
constexpr double kApart = 1.0 + 0x1p-50;

/// True when this CPU runs the AVX2 kernels (these pairs, and the bonds of IntactBond.h) and
/// ROCKDEM_CPU_SIMD is not 0 (the variable forces the scalar pair and bond loops, for tests
/// and comparisons). The processor is asked once per
/// process, the variable at every call (the CPU backend calls it when it is made).
bool touchingPairsAvx2Enabled();

/// Entries that `list` and `ended` must hold beyond last - first for scanPairsAvx2: each
/// group of four pairs writes four entries and keeps those it lists.
constexpr std::size_t kScanSlack = 4;

/// The pair loop's test of pairs [first, last), four at a time with AVX2, as the scalar loop
/// tests them: appends the pairs that touch to `list` (their count returned) and those that
/// do not touch but may hold state (live) to `ended` (`endedCount`), which the caller
/// clears. Both arrays hold last - first + kScanSlack entries. Plain differences of
/// positions only.
std::size_t scanPairsAvx2(const TouchingPairArrays& arrays, std::size_t first, std::size_t last,
                          std::uint32_t* list, std::uint32_t* ended, std::size_t& endedCount);

/// Evaluates the touching pairs `list[0..count)` (pair indices; each pair touches: distance
/// > 0 and overlap > 0, plain differences of positions, no rolling resistance) four at a
/// time with AVX2 and stores their results as the scalar loop does. Only call it when
/// touchingPairsAvx2Enabled().
void touchingPairsAvx2(const TouchingPairArrays& arrays, const std::uint32_t* list,
                       std::size_t count);

} // namespace dem
