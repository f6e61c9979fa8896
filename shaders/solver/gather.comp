#version 460
// RockDEM step (CpuBackend::computeForces, parts 3-4): per particle, in a fixed order, the
// forces of its pairs (by partner slot), its wall contacts (evaluated here), its intact
// bonds (bond order); gravity; Cundall local damping; the closing half kick. One
// invocation per particle: no floating-point atomics, the same sums as the CPU.
#include "geometry.glsl"
layout(local_size_x = 64) in;
layout(push_constant) uniform Push { Params p; } push;

double wallValue(Params p, uint w, uint field)
{
  return p.walls.v[WALL_STRIDE * w + field];
}

/// Wall entry e of particle i (the CPU backend's wallContact): adds its force and torque.
void wallContact(Params p, uint e, uint i, inout dvec3 force, inout dvec3 torque)
{
  const bool rolling = p.rolling != 0u;
  const uint w = p.wallIndex.v[e];
  const uint axis = w / 2u;
  const uint side = w % 2u;
  const double sideSign = side == 0u ? 1.0LF : -1.0LF;
  const double r = p.radius.v[i];
  const double distance = (p.position.v[3u * i + axis] - wallValue(p, w, WALL_POSITION)) * sideSign;
  const double overlap = wallValue(p, w, WALL_ACTIVE) != 0.0LF ? r - distance : 0.0LF;
  if (overlap <= 0.0LF) {
    if (p.wallTouching.v[e] != 0u || !isZero3(load3(p.wallSpring, e))) {
      p.wallTouching.v[e] = 0u;
      store3(p.wallForce, e, dvec3(0.0LF));
      p.wallNormal.v[e] = 0.0LF;
      p.wallStiffness.v[e] = 0.0LF;
      p.wallElastic.v[e] = 0.0LF;
      store3(p.wallSpring, e, dvec3(0.0LF));
      if (rolling) {
        store3(p.wallRolling, e, dvec3(0.0LF));
      }
    }
    return;
  }
  const double dt = p.dt;
  const double predict = 0.5LF * dt;
  // Wall::normal() points into the box; the contact normal points from the centre
  // towards the wall (its other components are -0.0, as on the CPU).
  dvec3 inward = dvec3(0.0LF);
  inward[axis] = side == 0u ? 1.0LF : -1.0LF;
  const dvec3 normal = -inward;
  const double arm = r - overlap;
  dvec3 wallVelocity = dvec3(0.0LF);
  wallVelocity[axis] = wallValue(p, w, WALL_VELOCITY);
  const dvec3 w_i = load3(p.angularVelocity, i);
  const dvec3 relativeVelocity = load3(p.velocity, i) - wallVelocity + cross3(w_i, arm * normal);
  const double approachSpeed =
    dot3(relativeVelocity + predict * p.inverseMass.v[i] * load3(p.force, i), normal);
  const ContactModel wallModel = contactModel(p, true, axis);
  const NormalResponse response =
    normalResponse(wallModel.law, loadConstants(p.wallConstants, e), overlap, approachSpeed);
  const double fn = response.force;
  const dvec3 slip = inPlane(relativeVelocity, normal) * dt;
  dvec3 spring = load3(p.wallSpring, e);
  const dvec3 ft = mindlinCoulombForce(response.tangentialStiffness, wallModel.friction, fn, normal, slip, spring);
  store3(p.wallSpring, e, spring);
  dvec3 contactTorque = arm * cross3(normal, ft);
  if (p.wallRollingOn != 0u) {
    const PairProperties pair = wallProperties(wallModel, r, massOf(p, i), p.planar != 0u, p.sizeZ);
    const dvec3 roll = inPlane(w_i, normal) * dt;
    dvec3 rollingSpring = load3(p.wallRolling, e);
    contactTorque += rollingTorque(wallModel, pair, overlap, fn, normal, roll, rollingSpring);
    store3(p.wallRolling, e, rollingSpring);
  } else if (rolling) {
    store3(p.wallRolling, e, dvec3(0.0LF));
  }
  const dvec3 wallForce = -fn * normal + ft;
  p.wallTouching.v[e] = 1u;
  store3(p.wallForce, e, wallForce);
  p.wallNormal.v[e] = fn;
  p.wallStiffness.v[e] = response.stiffness;
  p.wallElastic.v[e] = response.elasticForce;
  force += wallForce;
  torque += contactTorque;
}

void main()
{
  Params p = push.p;
  const uint i = itemIndex();
  if (i >= p.n || halted(p)) {
    return;
  }
  dvec3 force = p.mass.v[i] * dvec3(p.gravityX, p.gravityY, p.gravityZ);
  dvec3 torque = dvec3(0.0LF);
  const uint pairEnd = p.adjacencyStart.v[i + 1u];
  for (uint e = p.adjacencyStart.v[i]; e < pairEnd; ++e) {
    const uint entry = p.adjacency.v[e];
    const uint k = entry >> 1u;
    if (p.pairNormal.v[k] == 0.0LF) {
      continue;
    }
    if ((entry & 1u) != 0u) {
      force -= load3(p.pairForce, k);
      torque += load3(p.pairTorqueJ, k);
    } else {
      force += load3(p.pairForce, k);
      torque += load3(p.pairTorqueI, k);
    }
  }
  const uint wallEnd = p.wallStart.v[i + 1u];
  for (uint e = p.wallStart.v[i]; e < wallEnd; ++e) {
    wallContact(p, e, i, force, torque);
  }
  if (p.bondCount != 0u) {
    const uint bondEnd = p.bondAdjacencyStart.v[i + 1u];
    for (uint e = p.bondAdjacencyStart.v[i]; e < bondEnd; ++e) {
      const uint entry = p.bondAdjacency.v[e];
      const uint b = entry >> 1u;
      if (p.bondFailure.v[b] != 0u) {
        continue;
      }
      if ((entry & 1u) != 0u) {
        force -= load3(p.bondForce, b);
        torque += load3(p.bondTorqueJ, b);
      } else {
        force += load3(p.bondForce, b);
        torque += load3(p.bondTorqueI, b);
      }
    }
  }
  const bool planar = p.planar != 0u;
  if (planar) {
    force.z = 0.0LF;
    torque.x = 0.0LF;
    torque.y = 0.0LF;
  }
  store3(p.undampedForce, i, force);
  dvec3 damped = force;
  dvec3 dampedTorque = torque;
  const double alpha = p.alpha;
  const dvec3 v = load3(p.velocity, i);
  const dvec3 w = load3(p.angularVelocity, i);
  if (alpha > 0.0LF) {
    for (int c = 0; c < 3; ++c) {
      damped[c] = cundallDamping(force[c], v[c], alpha);
      dampedTorque[c] = cundallDamping(torque[c], w[c], alpha);
    }
  }
  store3(p.force, i, damped);
  store3(p.torque, i, dampedTorque);
  if (p.countDissipation != 0u && alpha > 0.0LF) {
    p.dampingWork.v[i] += cundallDampingWork(force, damped, v, torque, dampedTorque, w, p.dt);
  }
  const double invMass = p.inverseMass.v[i];
  if (invMass != 0.0LF) {
    const double halfStep = 0.5LF * p.dt;
    dvec3 v1 = v + (halfStep * invMass) * damped;
    dvec3 w1 = w + (halfStep * p.inverseInertia.v[i]) * dampedTorque;
    if (planar) {
      v1.z = 0.0LF;
      w1.x = 0.0LF;
      w1.y = 0.0LF;
    }
    store3(p.velocity, i, v1);
    store3(p.angularVelocity, i, w1);
  }
}
