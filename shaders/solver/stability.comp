#version 460
// RockDEM stability check (the CPU backend's stability()): the first particle with a
// non-finite position or velocity, the particles outside the walls on a walled axis and
// the first of them (integer atomics: min and count, independent of scheduling), and each
// particle's kinetic energy for the fixed-order sum (reduce_sum). One invocation per
// particle.
#include "state.glsl"
layout(local_size_x = 64) in;
layout(push_constant) uniform Push { Params p; } push;

void main()
{
  Params p = push.p;
  const uint i = itemIndex();
  if (i >= p.n) {
    return;
  }
  const dvec3 x = load3(p.position, i);
  const dvec3 v = load3(p.velocity, i);
  const dvec3 w = load3(p.angularVelocity, i);
  if (!allFinite3(x) || !allFinite3(v) || !allFinite3(w)) {
    atomicMin(p.ctl.v[CTL_NONFINITE], i);
  }
  for (uint k = 0u; k < 3u; ++k) {
    const uint low = WALL_STRIDE * (2u * k);
    const uint high = WALL_STRIDE * (2u * k + 1u);
    if (p.walls.v[low + WALL_ACTIVE] != 0.0LF &&
        (x[k] < p.walls.v[low + WALL_POSITION] || x[k] > p.walls.v[high + WALL_POSITION])) {
      atomicAdd(p.ctl.v[CTL_ESCAPED], 1u);
      atomicMin(p.ctl.v[CTL_FIRST_ESCAPED], i);
      break;
    }
  }
  p.kinetic.v[i] = 0.5LF * p.mass.v[i] * squaredNorm3(v) + 0.5LF * p.inertia.v[i] * squaredNorm3(w);
}
