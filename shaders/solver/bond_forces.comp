#version 460
// RockDEM step: each intact bond once (CpuBackend::computeBondForces): incremental force
// and moments (dem::incrementBond), the failure test (dem::bondStresses,
// dem::softenedBondFailure, with the tension-softening damage),
// and a bond that fails is broken for good with its time, place and orientation. One
// invocation per bond.
#include "geometry.glsl"
#include "bond_laws.glsl"
layout(local_size_x = 64) in;
layout(push_constant) uniform Push { Params p; } push;

void main()
{
  Params p = push.p;
  const uint k = itemIndex();
  if (k >= p.bondCount || halted(p) || p.bondFailure.v[k] != BOND_INTACT) {
    return;
  }
  const uint i = p.bondI.v[k];
  const uint j = p.bondJ.v[k];
  const bool planar = p.planar != 0u;
  const double dt = p.dt;
  const dvec3 xi = load3(p.position, i);
  const dvec3 branch = minimumImage(p, xi, load3(p.position, j));
  const double distance = norm3(branch);
  const dvec3 normal = branch / distance;
  const double ri = p.radius.v[i];
  const double rj = p.radius.v[j];
  const double armI = distance * ri / (ri + rj);
  const double armJ = distance - armI;
  const double bondRadius = p.bondRadius.v[k];
  const BondSection section = bondSection(bondRadius, planar, p.sizeZ);
  const dvec3 wi = load3(p.angularVelocity, i);
  const dvec3 wj = load3(p.angularVelocity, j);
  const dvec3 relativeVelocity = load3(p.velocity, i) - load3(p.velocity, j) +
    cross3(wi, armI * normal) + cross3(wj, armJ * normal);
  const dvec3 relativeSpin = wi - wj;
  double normalForce = p.bondNormalForce.v[k];
  dvec3 shearForce = load3(p.bondShearForce, k);
  double twistingMoment = p.bondTwistingMoment.v[k];
  dvec3 bendingMoment = load3(p.bondBendingMoment, k);
  incrementBond(section, p.bondKn.v[k], p.bondKs.v[k], planar, normal, relativeVelocity,
                relativeSpin, dt, normalForce, shearForce, twistingMoment, bendingMoment);
  const BondStresses stresses =
    bondStresses(section, bondRadius, normalForce, shearForce, twistingMoment, bendingMoment,
                 p.bondMomentContribution.v[k]);
  double damage = p.bondDamage.v[k];
  const uint failure = softenedBondFailure(stresses, p.bondTensileStrength.v[k], p.bondCohesion.v[k],
                                           p.bondTanFriction.v[k], p.bondSoftening.v[k], damage);
  p.bondDamage.v[k] = damage;
  if (failure != BOND_INTACT) {
    if (p.countDissipation != 0u) {
      // the energy its springs held, which breaking takes out of the model
      p.breakEnergy.v[k] = (1.0LF - damage) * bondStoredEnergy(section, p.bondKn.v[k], p.bondKs.v[k], normalForce,
                                                                shearForce, twistingMoment, bendingMoment);
    }
    // dem::Bonds::markBroken
    p.bondFailure.v[k] = failure;
    p.bondFailureTime.v[k] = p.clock.v[CLOCK_TIME] + dt;
    store3(p.bondFailurePosition, k, xi + armI * normal);
    store3(p.bondFailureNormal, k, normal);
    p.bondNormalForce.v[k] = 0.0LF;
    store3(p.bondShearForce, k, dvec3(0.0LF));
    p.bondTwistingMoment.v[k] = 0.0LF;
    store3(p.bondBendingMoment, k, dvec3(0.0LF));
    store3(p.bondForce, k, dvec3(0.0LF));
    store3(p.bondTorqueI, k, dvec3(0.0LF));
    store3(p.bondTorqueJ, k, dvec3(0.0LF));
    return;
  }
  p.bondNormalForce.v[k] = normalForce;
  store3(p.bondShearForce, k, shearForce);
  p.bondTwistingMoment.v[k] = twistingMoment;
  store3(p.bondBendingMoment, k, bendingMoment);
  const dvec3 twist = twistingMoment * normal;
  dvec3 force = normalForce * normal + shearForce;
  dvec3 torqueI = armI * cross3(normal, shearForce) + twist + bendingMoment;
  dvec3 torqueJ = armJ * cross3(normal, shearForce) - twist - bendingMoment;
  if (damage > 0.0LF) { // tension softening: the bond applies (1 - D) of its elastic state
    const double share = 1.0LF - damage;
    force *= share;
    torqueI *= share;
    torqueJ *= share;
  }
  store3(p.bondForce, k, force);
  store3(p.bondTorqueI, k, torqueI);
  store3(p.bondTorqueJ, k, torqueJ);
}
