#version 460
// RockDEM fixed-order sum of doubles: each workgroup sums 1024 items, each invocation 4 in
// order, then a fixed binary tree over the 256 invocations; the host repeats it over the
// partial sums. The shape of the tree depends on the count only: the same bits whatever
// the scheduling (the CPU's sequential sum rounds differently; used for the kinetic
// energy of the stability check only).
#include "state.glsl"
layout(local_size_x = 256) in;
layout(push_constant) uniform Push { Params p; Doubles data; Doubles result; uint count; } push;

shared double sums[256];

void main()
{
  const uint t = gl_LocalInvocationID.x;
  const uint base = gl_WorkGroupID.x * 1024u + 4u * t;
  double sum = 0.0LF;
  for (uint k = 0u; k < 4u; ++k) {
    if (base + k < push.count) {
      sum += push.data.v[base + k];
    }
  }
  sums[t] = sum;
  barrier();
  for (uint stride = 128u; stride > 0u; stride >>= 1u) {
    if (t < stride) {
      sums[t] = sums[t] + sums[t + stride];
    }
    barrier();
  }
  if (t == 0u) {
    push.result.v[gl_WorkGroupID.x] = sums[0];
  }
}
