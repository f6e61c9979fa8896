// RockDEM engine: one intact bond's step, written once for a vector type V
// (dem/ContactLawLanes.h): the CPU backend's scalar bond loop runs it on Eigen's Vector3d,
// its AVX2 kernel (IntactBondsAvx2.cpp) on dem::Lane3 of four doubles (four bonds at once)
// with the same operations in the same order, so both give the same bits (and the Vulkan
// backend's shaders/solver/bond_forces.comp the same again). The law itself is
// dem/BondLawLanes.h. No Eigen here: the AVX2 translation unit includes this header. SI units.
#pragma once

#include "dem/BondLawLanes.h"

#include <cstddef>
#include <cstdint>

namespace dem {

/// Where a bond's ends meet: the unit axis from A to B and the arms from each centre to the
/// contact point, which divides the branch in the ratio of the radii (m).
template <class V, class S = typename VecOps<V>::Scalar> struct BondAxis {
  V normal;
  S armI, armJ;
};

/// The axis of a bond whose branch (m, from A to B, minimum image) and radii are given.
template <class V, class S = typename VecOps<V>::Scalar>
ROCKDEM_INLINE_LAW BondAxis<V> bondAxis(const V& branch, const S& radiusI, const S& radiusJ)
{
  using O = VecOps<V>;
  using Ops = LaneOps<S>;
  const S distance = Ops::sqrt(O::squaredNorm(branch)); // Eigen's norm()
  const S armI = distance * radiusI / (radiusI + radiusJ);
  return { O::divided(branch, distance), armI, distance - armI };
}

/// One step of an intact bond's forces and moments (dem::incrementBond) from the velocities
/// (m/s) and spins (rad/s) of its ends, A = i and B = j, over `dt` (s).
template <class V, class S = typename VecOps<V>::Scalar>
ROCKDEM_INLINE_LAW void advanceBond(const BondAxis<V>& axis, const BondSectionLanes<S>& section, const S& kn,
                                    const S& ks, bool planar, const V& velocityI, const V& velocityJ,
                                    const V& spinI, const V& spinJ, const S& dt, S& normalForce, V& shearForce,
                                    S& twistingMoment, V& bendingMoment)
{
  using O = VecOps<V>;
  const V relativeVelocity = velocityI - velocityJ + O::cross(spinI, O::scaled(axis.armI, axis.normal)) +
    O::cross(spinJ, O::scaled(axis.armJ, axis.normal));
  const V relativeSpin = spinI - spinJ;
  incrementBondLanes(section, kn, ks, planar, axis.normal, relativeVelocity, relativeSpin, dt, normalForce,
                     shearForce, twistingMoment, bendingMoment);
}

/// What a bond applies (before the softened share): the force on A (N; B gets the
/// opposite) and the torques about both centres (N m).
template <class V> struct BondLoads {
  V force;
  V torqueI, torqueJ;
};

/// The loads of a bond state: Fn n + Fs on A, the shear force's moment about each centre,
/// plus and minus the twisting and bending moments.
template <class V, class S = typename VecOps<V>::Scalar>
ROCKDEM_INLINE_LAW BondLoads<V> bondLoads(const BondAxis<V>& axis, const S& normalForce, const V& shearForce,
                                          const S& twistingMoment, const V& bendingMoment)
{
  using O = VecOps<V>;
  const V twist = O::scaled(twistingMoment, axis.normal);
  const V normalCrossShear = O::cross(axis.normal, shearForce);
  return { O::scaled(normalForce, axis.normal) + shearForce, O::scaled(axis.armI, normalCrossShear) + twist + bendingMoment,
           O::scaled(axis.armJ, normalCrossShear) - twist - bendingMoment };
}

/// The bond arrays of the CPU backend as plain doubles (a Vec3 is three doubles), for the
/// AVX2 kernel, which includes no Eigen.
struct IntactBondArrays {
  const double* position;        ///< 3 per particle
  const double* velocity;        ///< 3 per particle
  const double* spin;            ///< 3 per particle
  const double* radius;          ///< per particle
  const std::uint32_t* bondI;    ///< slot of end A
  const std::uint32_t* bondJ;    ///< slot of end B
  const std::uint8_t* failure;   ///< dem::BondFailure
  const double* bondRadius;
  const double* normalStiffness; ///< Pa/m
  const double* shearStiffness;  ///< Pa/m
  const double* tensileStrength; ///< Pa
  const double* cohesion;        ///< Pa
  const double* frictionAngle;   ///< rad
  const double* momentContribution;
  const double* softening;
  const double* damage;
  double* normalForce;           ///< 1 per bond
  double* shearForce;            ///< 3 per bond
  double* twistingMoment;        ///< 1 per bond
  double* bendingMoment;         ///< 3 per bond
  double* force;                 ///< 3 per bond
  double* torqueI;               ///< 3 per bond
  double* torqueJ;               ///< 3 per bond
  bool planar;
  double slab;                   ///< m
  double dt;                     ///< s
};

/// Entries that the `rest` list of intactBondsAvx2 holds beyond last - first.
constexpr std::size_t kBondScanSlack = 4;

/// The bond loop's step of bonds [first, last) four at a time with AVX2, on a real step
/// (state incremented, failure tested), with plain differences of positions and no
/// periodic axis: the intact bonds that are brittle (Softening Ratio 0) and undamaged are
/// stepped and their loads stored, as the scalar loop would, four at a time; those that the
/// scalar loop must step themselves (a softening or damaged bond, or one of a group of four in
/// which any bond breaks, whose state is left untouched) are written to `rest` (their count
/// returned; `rest` holds last - first + kBondScanSlack entries). Broken
/// bonds are skipped. Only call it when touchingPairsAvx2Enabled().
std::size_t intactBondsAvx2(const IntactBondArrays& arrays, std::size_t first, std::size_t last,
                            std::uint32_t* rest);

} // namespace dem
