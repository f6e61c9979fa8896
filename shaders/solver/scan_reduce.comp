#version 460
// RockDEM exclusive prefix sum of a uint array (counts -> list starts), part 1: the sum of
// each block of 1024 items. Integer sums: the result does not depend on scheduling.
#include "state.glsl"
layout(local_size_x = 256) in;
layout(push_constant) uniform Push { Params p; Uints data; Uints result; Uints blocks; uint count; } push;

shared uint sums[256];

void main()
{
  if (halted(push.p)) {
    return;
  }
  const uint t = gl_LocalInvocationID.x;
  const uint base = gl_WorkGroupID.x * SCAN_BLOCK + 4u * t;
  uint sum = 0u;
  for (uint k = 0u; k < 4u; ++k) {
    if (base + k < push.count) {
      sum += push.data.v[base + k];
    }
  }
  sums[t] = sum;
  barrier();
  for (uint stride = 128u; stride > 0u; stride >>= 1u) {
    if (t < stride) {
      sums[t] += sums[t + stride];
    }
    barrier();
  }
  if (t == 0u) {
    push.blocks.v[gl_WorkGroupID.x] = sums[0];
  }
}
