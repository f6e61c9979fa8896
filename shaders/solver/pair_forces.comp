#version 460
// RockDEM step: the force of each neighbour pair, once (CpuBackend::computeForces, part 1):
// Hertz-Mindlin or linear normal response with damping on the predicted full-step
// velocity, Mindlin-Coulomb tangential spring, rolling resistance when Rolling Friction is
// set. A pair that stopped touching has its force and history cleared. One invocation per
// pair.
#include "geometry.glsl"
layout(local_size_x = 64) in;
layout(push_constant) uniform Push { Params p; } push;

void main()
{
  Params p = push.p;
  const uint k = itemIndex();
  if (k >= p.ctl.v[CTL_PAIRS] || halted(p)) {
    return;
  }
  const uint i = p.pairI.v[k];
  const uint j = p.pairJ.v[k];
  const bool rolling = p.rolling != 0u;
  const double ri = p.radius.v[i];
  const double rj = p.radius.v[j];
  const dvec3 branch = separationOf(p, load3(p.position, i), load3(p.position, j));
  const double distance = norm3(branch);
  const double overlap = ri + rj - distance;
  if (overlap <= 0.0LF || distance == 0.0LF) {
    if (p.pairNormal.v[k] != 0.0LF || !isZero3(load3(p.pairSpring, k)) ||
        (rolling && !isZero3(load3(p.pairRolling, k)))) {
      store3(p.pairForce, k, dvec3(0.0LF));
      store3(p.pairTorqueI, k, dvec3(0.0LF));
      store3(p.pairTorqueJ, k, dvec3(0.0LF));
      p.pairNormal.v[k] = 0.0LF;
      store3(p.pairSpring, k, dvec3(0.0LF));
      if (rolling) {
        store3(p.pairRolling, k, dvec3(0.0LF));
      }
    }
    return;
  }
  const double dt = p.dt;
  const double predict = 0.5LF * dt;
  const dvec3 normal = branch / distance;
  const double armI = ri - 0.5LF * overlap;
  const double armJ = rj - 0.5LF * overlap;
  const dvec3 wi = load3(p.angularVelocity, i);
  const dvec3 wj = load3(p.angularVelocity, j);
  const dvec3 relativeVelocity = load3(p.velocity, i) - load3(p.velocity, j) +
    cross3(wi, armI * normal) + cross3(wj, armJ * normal);
  const dvec3 predictedVelocity = relativeVelocity +
    predict * (p.inverseMass.v[i] * load3(p.force, i) - p.inverseMass.v[j] * load3(p.force, j));
  const double approachSpeed = dot3(predictedVelocity, normal);
  const ContactModel cm = contactModel(p, false, 0u);
  const NormalResponse response = normalResponse(cm.law, loadConstants(p.pairConstants, k), overlap, approachSpeed);
  const double fn = response.force;
  const dvec3 slip = inPlane(relativeVelocity, normal) * dt;
  dvec3 spring = load3(p.pairSpring, k);
  const dvec3 ft = mindlinCoulombForce(response.tangentialStiffness, cm.friction, fn, normal, slip, spring);
  store3(p.pairSpring, k, spring);
  dvec3 torqueI = armI * cross3(normal, ft);
  dvec3 torqueJ = armJ * cross3(normal, ft);
  if (rolling) {
    const PairProperties pair =
      pairProperties(cm, ri, massOf(p, i), rj, massOf(p, j), p.planar != 0u, p.sizeZ);
    const dvec3 roll = inPlane(wi - wj, normal) * dt;
    dvec3 rollingSpring = load3(p.pairRolling, k);
    const dvec3 mr = rollingTorque(cm, pair, overlap, fn, normal, roll, rollingSpring);
    store3(p.pairRolling, k, rollingSpring);
    torqueI += mr;
    torqueJ -= mr;
  }
  store3(p.pairForce, k, -fn * normal + ft);
  store3(p.pairTorqueI, k, torqueI);
  store3(p.pairTorqueJ, k, torqueJ);
  p.pairNormal.v[k] = fn;
}
