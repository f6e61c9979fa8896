// RockDEM shaders: the parallel bond (Potyondy & Cundall 2004; PHYSICS.md section 3), the
// GLSL mirror of dem/Bonds.h (bondSection, bondStresses, bondFailure, softeningDamage,
// softenedBondFailure) and dem/BondLaw.h
// (incrementBond). Same operations in the same order as the C++ (VulkanLaws.SameBitsAsTheCppLawsOnTheDevice).
// SI units: m, N, N m, Pa.
#ifndef ROCKDEM_BOND_LAWS_GLSL
#define ROCKDEM_BOND_LAWS_GLSL

#include "contact_laws.glsl"

const uint BOND_INTACT = 0u;
const uint BOND_TENSION = 1u;
const uint BOND_SHEAR = 2u;

/// dem::BondSection: area (m^2), bending inertia (m^4), polar inertia (m^4, 0 in 2D).
struct BondSection {
  double area;
  double inertia;
  double polar;
};

/// dem::bondSection.
BondSection bondSection(double bondRadius, bool section2D, double slab)
{
  const double R = bondRadius;
  BondSection s;
  if (section2D) {
    s.area = 2.0LF * R * slab;
    s.inertia = 2.0LF / 3.0LF * slab * R * R * R;
    s.polar = 0.0LF;
    return s;
  }
  const double R2 = R * R;
  s.area = PI * R2;
  s.inertia = 0.25LF * PI * R2 * R2;
  s.polar = 0.5LF * PI * R2 * R2;
  return s;
}

/// dem::BondStresses: peripheral tensile and shear stresses and the compressive stress, Pa.
struct BondStresses {
  double sigmaMax;
  double tauMax;
  double compressive;
};

/// dem::bondStresses, with beta the bond's Moment Contribution factor (dem::Bonds::momentContribution).
BondStresses bondStresses(BondSection s, double bondRadius, double normalForce, dvec3 shearForce,
                          double twistingMoment, dvec3 bendingMoment, double momentContribution)
{
  const double beta = momentContribution;
  BondStresses o;
  o.sigmaMax = normalForce / s.area + beta * norm3(bendingMoment) * bondRadius / s.inertia;
  o.tauMax = norm3(shearForce) / s.area +
    (s.polar > 0.0LF ? beta * abs(twistingMoment) * bondRadius / s.polar : 0.0LF);
  o.compressive = -normalForce / s.area;
  return o;
}

/// dem::failsInShear (Bonds.cpp), with tan(friction angle) given.
bool failsInShear(BondStresses stresses, double cohesion, double tanFrictionAngle)
{
  return stresses.tauMax >= cohesion + stresses.compressive * tanFrictionAngle;
}

/// dem::bondFailure, with tan(friction angle) given (the host computes std::tan once per
/// bond: GLSL has no double-precision tangent).
uint bondFailure(BondStresses stresses, double tensileStrength, double cohesion, double tanFrictionAngle)
{
  if (stresses.sigmaMax >= tensileStrength) {
    return BOND_TENSION;
  }
  if (failsInShear(stresses, cohesion, tanFrictionAngle)) {
    return BOND_SHEAR;
  }
  return BOND_INTACT;
}

/// dem::softeningDamage: tension-softening damage at an elastic peripheral stress of
/// stressRatio x the tensile strength, Softening Ratio r > 0.
double softeningDamage(double stressRatio, double softeningRatio)
{
  if (!(stressRatio > 1.0LF)) {
    return 0.0LF;
  }
  const double r = softeningRatio;
  if (stressRatio >= 1.0LF + r) {
    return 1.0LF;
  }
  return 1.0LF - (1.0LF + r - stressRatio) / (r * stressRatio);
}

/// dem::softenedBondFailure: the failure rule with tension softening (r = 0: bondFailure).
uint softenedBondFailure(BondStresses elastic, double tensileStrength, double cohesion, double tanFrictionAngle,
                         double softeningRatio, inout double damage)
{
  if (!(softeningRatio > 0.0LF)) {
    return bondFailure(elastic, tensileStrength, cohesion, tanFrictionAngle);
  }
  const double ratio = elastic.sigmaMax / tensileStrength;
  if (ratio >= 1.0LF + softeningRatio) {
    return BOND_TENSION;
  }
  damage = max(damage, softeningDamage(ratio, softeningRatio));
  if (failsInShear(elastic, cohesion, tanFrictionAngle)) {
    return BOND_SHEAR;
  }
  return BOND_INTACT;
}

/// dem::incrementBond: one step of the bond's force and moments from the relative motion
/// of its ends (normal from A to B, unit; relative velocity of the contact point of A to
/// B, m/s; relative spin, rad/s; dt, s). kn, ks: stiffness per unit area, Pa/m.
void incrementBond(BondSection section, double kn, double ks, bool planar, dvec3 normal,
                   dvec3 relativeVelocity, dvec3 relativeSpin, double dt, inout double normalForce,
                   inout dvec3 shearForce, inout double twistingMoment, inout dvec3 bendingMoment)
{
  normalForce -= kn * section.area * dot3(relativeVelocity, normal) * dt;
  shearForce = rotateIntoPlane(shearForce, normal) - ks * section.area * inPlane(relativeVelocity, normal) * dt;
  if (!planar) {
    twistingMoment -= ks * section.polar * dot3(relativeSpin, normal) * dt;
  }
  bendingMoment = rotateIntoPlane(bendingMoment, normal) - kn * section.inertia * inPlane(relativeSpin, normal) * dt;
}

/// dem::bondStoredEnergy: the elastic energy (J) of an intact bond's springs.
double bondStoredEnergy(BondSection section, double kn, double ks, double normalForce, dvec3 shearForce,
                        double twistingMoment, dvec3 bendingMoment)
{
  double stored = 0.5LF * normalForce * normalForce / (kn * section.area) +
    0.5LF * squaredNorm3(shearForce) / (ks * section.area) +
    0.5LF * squaredNorm3(bendingMoment) / (kn * section.inertia);
  if (section.polar > 0.0LF) {
    stored += 0.5LF * twistingMoment * twistingMoment / (ks * section.polar);
  }
  return stored;
}

#endif
