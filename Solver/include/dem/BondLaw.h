// RockDEM engine: the incremental update of a parallel bond (Potyondy & Cundall 2004;
// PHYSICS.md section 3). With dem::bondSection, dem::bondStresses and dem::bondFailure
// (dem/Bonds.h) it is the bond's force law; the GLSL twin is shaders/include/bond_laws.glsl
// (same operations in the same order; VulkanLaws.SameBitsAsTheCppLawsOnTheDevice requires identical bits). SI units.
#pragma once

#include "dem/Bonds.h"
#include "dem/ContactLaws.h"

namespace dem {

/// One step of an intact bond: its normal force (N, positive in tension), shear force (N,
/// in the bond plane), twisting moment (N m, 3D only) and bending moment (N m) follow the
/// relative motion of its ends over `dt` (s). `normal`: unit bond axis from A to B;
/// `relativeVelocity`: velocity of A's contact point relative to B's (m/s);
/// `relativeSpin`: A's angular velocity minus B's (rad/s); kn, ks: stiffness per unit
/// area (Pa/m). The stored shear force and bending moment are first turned into the
/// current bond plane.
inline void incrementBond(const BondSection& section, double kn, double ks, bool planar,
                          const Vec3& normal, const Vec3& relativeVelocity,
                          const Vec3& relativeSpin, double dt, double& normalForce,
                          Vec3& shearForce, double& twistingMoment, Vec3& bendingMoment)
{
  incrementBondLanes<Vec3>(section, kn, ks, planar, normal, relativeVelocity, relativeSpin, dt, normalForce,
                           shearForce, twistingMoment, bendingMoment); // written once, in dem/BondLawLanes.h
}

/// Elastic energy (J) an intact bond's springs hold (PHYSICS.md section 3): F = k A u for the
/// normal and shear forces, M = k J theta (twist, ks) and M = k I theta (bending, kn), so
/// each holds F^2 / (2 k A) or M^2 / (2 k J|I); kn, ks in Pa/m. A softened bond holds
/// (1 - D) of it (the caller's factor). GLSL twin in bond_laws.glsl.
inline double bondStoredEnergy(const BondSection& section, double kn, double ks, double normalForce,
                               const Vec3& shearForce, double twistingMoment, const Vec3& bendingMoment)
{
  double stored = 0.5 * normalForce * normalForce / (kn * section.area) +
    0.5 * shearForce.squaredNorm() / (ks * section.area) +
    0.5 * bendingMoment.squaredNorm() / (kn * section.inertia);
  if (section.polar > 0.0) {
    stored += 0.5 * twistingMoment * twistingMoment / (ks * section.polar);
  }
  return stored;
}

} // namespace dem
