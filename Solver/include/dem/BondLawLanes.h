// RockDEM engine: the parallel bond's law (Potyondy & Cundall 2004; PHYSICS.md section 3)
// written once for a 3-vector type V whose components are of a lane type S, as the contact
// laws are in dem/ContactLawLanes.h: Eigen's Vector3d with S = double (one bond: the Eigen
// functions dem::bondSection, dem::bondStresses, dem::bondFailure and dem::incrementBond
// call these), or dem::Lane3 of four doubles (four bonds at once, the CPU backend's AVX2
// bond kernel). Every lane performs the same IEEE operations in the same order as the
// double instance, without fused multiply-adds, so a lane gives the double's bits; the
// GLSL twin shaders/include/bond_laws.glsl performs the same operations in the same order.
//
// No Eigen here: the AVX2 translation unit includes this header. SI units as in dem/Bonds.h.
#pragma once

#include "dem/ContactLawLanes.h"

namespace dem {

/// Section properties of a bond (dem::BondSection is the double instance): 3D
/// A = pi Rb^2, I = pi Rb^4 / 4, J = pi Rb^4 / 2; 2D (slab t) A = 2 Rb t, I = 2/3 t Rb^3,
/// J = 0 (no twisting).
template <class S> struct BondSectionLanes {
  S area;    ///< m^2
  S inertia; ///< m^4, bending
  S polar;   ///< m^4, twisting (0 in 2D)
};

/// Peripheral stresses of a bond state (dem::BondStresses is the double instance), Pa.
template <class S> struct BondStressesLanes {
  S sigmaMax;
  S tauMax;
  S compressive; ///< sigma = -Fn / A (compression positive)
};

/// dem::bondSection per lane (Rb in m, slab thickness in m).
template <class S> inline BondSectionLanes<S> bondSectionLanes(const S& bondRadius, bool section2D, double slab)
{
  constexpr double pi = 3.14159265358979323846;
  const S R = bondRadius;
  if (section2D) {
    // Rectangle 2R x t through the slab: A = 2 R t, I = 2/3 t R^3, no twisting.
    return { 2.0 * R * slab, 2.0 / 3.0 * slab * R * R * R, S{} };
  }
  // Circle: A = pi R^2, I = pi R^4 / 4, J = pi R^4 / 2.
  const S R2 = R * R;
  return { pi * R2, 0.25 * pi * R2 * R2, 0.5 * pi * R2 * R2 };
}

/// dem::bondStresses per lane: sigma_max = Fn/A + beta |Mb| Rb / I (tension positive),
/// tau_max = |Fs|/A + beta |Mt| Rb / J (3D), beta the moment contribution factor.
template <class V, class S = typename VecOps<V>::Scalar>
inline BondStressesLanes<S> bondStressesLanes(const BondSectionLanes<S>& s, const S& bondRadius, const S& normalForce,
                                              const V& shearForce, const S& twistingMoment, const V& bendingMoment,
                                              const S& momentContribution)
{
  using O = VecOps<V>;
  using Ops = LaneOps<S>;
  const S beta = momentContribution;
  const S bending = Ops::sqrt(O::squaredNorm(bendingMoment)); // |Mb| (Eigen's norm())
  const S twisting = beta * Ops::abs(twistingMoment) * bondRadius / s.polar;
  return { normalForce / s.area + beta * bending * bondRadius / s.inertia,
           Ops::sqrt(O::squaredNorm(shearForce)) / s.area + Ops::select(s.polar > 0.0, twisting, S{}),
           -normalForce / s.area };
}

/// The brittle bond's tension test per lane: sigma_max >= sigma_c (Pa).
template <class S> inline auto failsInTensionLanes(const BondStressesLanes<S>& stresses, const S& tensileStrength)
{
  return stresses.sigmaMax >= tensileStrength;
}

/// Mohr-Coulomb per lane: the shear strength c + sigma tan(phi) grows with the compressive
/// normal stress (Pa; `tanFriction` = tan(phi)).
template <class S>
inline auto failsInShearLanes(const BondStressesLanes<S>& stresses, const S& cohesion, const S& tanFriction)
{
  return stresses.tauMax >= cohesion + stresses.compressive * tanFriction;
}

/// dem::incrementBond per lane: one step of an intact bond's normal force (N, tension
/// positive), shear force (N), twisting moment (N m, 3D only) and bending moment (N m) from
/// the relative motion of its ends over `dt` (s); kn, ks in Pa/m. The stored shear force
/// and bending moment are first turned into the current bond plane.
template <class V, class S = typename VecOps<V>::Scalar>
inline void incrementBondLanes(const BondSectionLanes<S>& section, const S& kn, const S& ks, bool planar,
                               const V& normal, const V& relativeVelocity, const V& relativeSpin, const S& dt,
                               S& normalForce, V& shearForce, S& twistingMoment, V& bendingMoment)
{
  using O = VecOps<V>;
  // dFn = kn A d(separation): positive (tension) when B moves away from A.
  normalForce = normalForce - kn * section.area * O::dot(relativeVelocity, normal) * dt;
  // dFs = -ks A (tangential displacement of A relative to B), in the rotated plane.
  const S shearArea = ks * section.area;
  shearForce = rotateIntoPlaneLanes(shearForce, normal) -
    O::scaled(dt, O::scaled(shearArea, inPlaneLanes(relativeVelocity, normal)));
  // dMt = -ks J d(theta twist) (3D); dMb = -kn I d(theta bend).
  if (!planar) {
    twistingMoment = twistingMoment - ks * section.polar * O::dot(relativeSpin, normal) * dt;
  }
  const S bendingInertia = kn * section.inertia;
  bendingMoment = rotateIntoPlaneLanes(bendingMoment, normal) -
    O::scaled(dt, O::scaled(bendingInertia, inPlaneLanes(relativeSpin, normal)));
}

} // namespace dem
