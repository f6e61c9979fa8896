#version 460
// RockDEM step, part 1 (CpuBackend::step): half kick with the forces of the last step,
// drift, periodic wrap, the skin criterion (CTL_STALE), and in a tension test the
// velocity of the particles attached to the moving platen (dem::controlWalls).
// One invocation per particle.
#include "geometry.glsl"
layout(local_size_x = 64) in;
layout(push_constant) uniform Push { Params p; } push;

const uint FLAG_ATTACHED_HIGH = 8u;

void main()
{
  Params p = push.p;
  const uint i = itemIndex();
  if (i >= p.n || halted(p)) {
    return;
  }
  const double dt = p.dt;
  const double halfStep = 0.5LF * dt;
  dvec3 v = load3(p.velocity, i);
  dvec3 w = load3(p.angularVelocity, i);
  v += (halfStep * p.inverseMass.v[i]) * load3(p.force, i);
  w += (halfStep * p.inverseInertia.v[i]) * load3(p.torque, i);
  if (p.planar != 0u) {
    v.z = 0.0LF;
    w.x = 0.0LF;
    w.y = 0.0LF;
  }
  const dvec3 move = dt * v;
  dvec3 x = load3(p.position, i) + move;
  store3(p.displacement, i, load3(p.displacement, i) + move);
  if (p.periodicMask != 0u) {
    const dvec3 lo = origin(p);
    const dvec3 length = boxSize(p);
    for (int k = 0; k < 3; ++k) {
      if ((p.periodicMask & (1u << k)) != 0u) {
        if (x[k] < lo[k]) {
          x[k] += length[k];
        } else if (x[k] >= lo[k] + length[k]) {
          x[k] -= length[k];
        }
      }
    }
  }
  store3(p.position, i, x);
  const double limit = 0.5LF * p.skin;
  if (squaredNorm3(separationOf(p, load3(p.positionAtBuild, i), x)) > limit * limit) {
    atomicOr(p.ctl.v[CTL_STALE], 1u);
  }
  if (p.tension != 0u && (p.flags.v[i] & FLAG_ATTACHED_HIGH) != 0u) {
    v = dvec3(0.0LF);
    v[p.axis] = p.platenMoving != 0u ? p.platenVelocity : 0.0LF;
  }
  store3(p.velocity, i, v);
  store3(p.angularVelocity, i, w);
}
