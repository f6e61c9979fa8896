#version 460
// RockDEM law parity check: every force law of the step (contact_laws.glsl,
// bond_laws.glsl, servo_law.glsl) on a list of cases, for VulkanLaws.SameBitsAsTheCppLawsOnTheDevice, which runs the
// C++ twins (dem/ContactLaws.h, dem/BondLaw.h, dem/Bonds.h, dem/WallControl.h) on the same
// inputs and requires the same bits. Case layout: PARITY_* in parity_layout.h. One
// invocation per case.
#include "state.glsl"
#include "bond_laws.glsl"
#include "servo_law.glsl"
#include "parity_layout.h"
layout(local_size_x = 64) in;
layout(push_constant) uniform Push { Doubles cases; Doubles results; uint count; } push;

double in_(uint c, uint k)
{
  return push.cases.v[PARITY_IN * c + k];
}

dvec3 in3(uint c, uint k)
{
  return dvec3(in_(c, k), in_(c, k + 1u), in_(c, k + 2u));
}

void out_(uint c, uint k, double x)
{
  push.results.v[PARITY_OUT * c + k] = x;
}

void out3(uint c, uint k, dvec3 x)
{
  out_(c, k, x.x);
  out_(c, k + 1u, x.y);
  out_(c, k + 2u, x.z);
}

void main()
{
  const uint c = gl_GlobalInvocationID.x;
  if (c >= push.count) {
    return;
  }
  ContactModel cm;
  cm.law = uint(in_(c, IN_LAW));
  cm.dampingCoefficient = in_(c, IN_DAMPING);
  cm.friction = in_(c, IN_FRICTION);
  cm.rollingFriction = in_(c, IN_ROLLING);
  cm.youngsModulus = in_(c, IN_YOUNG);
  cm.poissonsRatio = in_(c, IN_POISSON);
  const bool planar = in_(c, IN_PLANAR) != 0.0LF;
  const double slab = in_(c, IN_SLAB);
  const double overlap = in_(c, IN_OVERLAP);
  const double approach = in_(c, IN_APPROACH);
  const dvec3 n = in3(c, IN_NORMAL);

  const PairProperties pair = pairProperties(cm, in_(c, IN_RA), in_(c, IN_MA), in_(c, IN_RB),
                                             in_(c, IN_MB), planar, slab);
  out_(c, OUT_PAIR + 0u, pair.effectiveModulus);
  out_(c, OUT_PAIR + 1u, pair.effectiveShearModulus);
  out_(c, OUT_PAIR + 2u, pair.effectiveRadius);
  out_(c, OUT_PAIR + 3u, pair.effectiveMass);
  out_(c, OUT_PAIR + 4u, pair.linearNormalStiffness);
  out_(c, OUT_PAIR + 5u, pair.linearShearStiffness);
  const ContactConstants constants = contactConstants(cm, pair);
  out_(c, OUT_CONSTANTS + 0u, constants.normalStiffness);
  out_(c, OUT_CONSTANTS + 1u, constants.normalDamping);
  out_(c, OUT_CONSTANTS + 2u, constants.tangentialStiffness);
  const PairProperties wall = wallProperties(cm, in_(c, IN_RA), in_(c, IN_MA), planar, slab);
  out_(c, OUT_WALL + 0u, wall.effectiveModulus);
  out_(c, OUT_WALL + 1u, wall.effectiveShearModulus);
  out_(c, OUT_WALL + 2u, wall.effectiveRadius);
  out_(c, OUT_WALL + 3u, wall.effectiveMass);
  out_(c, OUT_WALL + 4u, wall.linearNormalStiffness);
  out_(c, OUT_WALL + 5u, wall.linearShearStiffness);
  const ContactConstants wallConstants = contactConstants(cm, wall);
  out_(c, OUT_WALL_CONSTANTS + 0u, wallConstants.normalStiffness);
  out_(c, OUT_WALL_CONSTANTS + 1u, wallConstants.normalDamping);
  out_(c, OUT_WALL_CONSTANTS + 2u, wallConstants.tangentialStiffness);
  out_(c, OUT_NORMAL_STIFFNESS, normalStiffness(cm, pair, overlap));
  if (overlap > 0.0LF) {
    const NormalResponse r = normalResponse(cm.law, constants, overlap, approach);
    out_(c, OUT_RESPONSE + 0u, r.elasticForce);
    out_(c, OUT_RESPONSE + 1u, r.force);
    out_(c, OUT_RESPONSE + 2u, r.stiffness);
    out_(c, OUT_RESPONSE + 3u, r.tangentialStiffness);
    dvec3 spring = in3(c, IN_SPRING);
    const dvec3 ft = mindlinCoulombForce(r.tangentialStiffness, cm.friction, r.force, n,
                                         in3(c, IN_SLIP), spring);
    out3(c, OUT_TANGENTIAL, ft);
    out3(c, OUT_SPRING, spring);
    dvec3 rollingSpring = in3(c, IN_ROLL_SPRING);
    const dvec3 mr = rollingTorque(cm, pair, overlap, r.force, n, in3(c, IN_ROLL), rollingSpring);
    out3(c, OUT_ROLLING, mr);
    out3(c, OUT_ROLL_SPRING, rollingSpring);
  }
  out3(c, OUT_ROTATED, rotateIntoPlane(in3(c, IN_SPRING), n));
  out_(c, OUT_CUNDALL, cundallDamping(in_(c, IN_CUNDALL_FORCE), in_(c, IN_CUNDALL_VELOCITY), in_(c, IN_CUNDALL_ALPHA)));

  const double bondRadius = in_(c, IN_BOND_RADIUS);
  const BondSection section = bondSection(bondRadius, planar, slab);
  out_(c, OUT_SECTION + 0u, section.area);
  out_(c, OUT_SECTION + 1u, section.inertia);
  out_(c, OUT_SECTION + 2u, section.polar);
  double normalForce = in_(c, IN_BOND_FN);
  dvec3 shearForce = in3(c, IN_BOND_FS);
  double twistingMoment = in_(c, IN_BOND_MT);
  dvec3 bendingMoment = in3(c, IN_BOND_MB);
  incrementBond(section, in_(c, IN_BOND_KN), in_(c, IN_BOND_KS), planar, n, in3(c, IN_BOND_VELOCITY),
                in3(c, IN_BOND_SPIN), in_(c, IN_DT), normalForce, shearForce, twistingMoment, bendingMoment);
  out_(c, OUT_BOND_STATE + 0u, normalForce);
  out3(c, OUT_BOND_STATE + 1u, shearForce);
  out_(c, OUT_BOND_STATE + 4u, twistingMoment);
  out3(c, OUT_BOND_STATE + 5u, bendingMoment);
  const BondStresses stresses =
    bondStresses(section, bondRadius, normalForce, shearForce, twistingMoment, bendingMoment,
                 in_(c, IN_BOND_BETA));
  out_(c, OUT_STRESSES + 0u, stresses.sigmaMax);
  out_(c, OUT_STRESSES + 1u, stresses.tauMax);
  out_(c, OUT_STRESSES + 2u, stresses.compressive);
  out_(c, OUT_FAILURE, double(bondFailure(stresses, in_(c, IN_BOND_SIGMA), in_(c, IN_BOND_COHESION),
                                          in_(c, IN_BOND_TAN_PHI))));
  double damage = in_(c, IN_BOND_DAMAGE);
  out_(c, OUT_SOFTENED_FAILURE, double(softenedBondFailure(stresses, in_(c, IN_BOND_SIGMA), in_(c, IN_BOND_COHESION),
                                                           in_(c, IN_BOND_TAN_PHI), in_(c, IN_BOND_SOFTENING), damage)));
  out_(c, OUT_DAMAGE, damage);
  out_(c, OUT_BOND_ENERGY, bondStoredEnergy(section, in_(c, IN_BOND_KN), in_(c, IN_BOND_KS), normalForce, shearForce,
                                            twistingMoment, bendingMoment));
  {
    const dvec3 force = in3(c, IN_BOND_FS);
    const dvec3 velocity = in3(c, IN_BOND_VELOCITY);
    const dvec3 torque = in3(c, IN_BOND_MB);
    const dvec3 spin = in3(c, IN_BOND_SPIN);
    const double alpha = in_(c, IN_CUNDALL_ALPHA);
    dvec3 damped, dampedTorque;
    for (int k = 0; k < 3; ++k) {
      damped[k] = cundallDamping(force[k], velocity[k], alpha);
      dampedTorque[k] = cundallDamping(torque[k], spin[k], alpha);
    }
    out_(c, OUT_DAMPING_WORK, cundallDampingWork(force, damped, velocity, torque, dampedTorque, spin, in_(c, IN_DT)));
  }
  out_(c, OUT_SERVO, servoWallVelocity(in_(c, IN_SERVO_ELASTIC), in_(c, IN_SERVO_STIFFNESS),
                                       in_(c, IN_SERVO_AREA), in_(c, IN_SERVO_TARGET), in_(c, IN_SERVO_ALPHA),
                                       in_(c, IN_DT), in_(c, IN_SERVO_MAX_SPEED), int(in_(c, IN_SERVO_SIDE))));
}
