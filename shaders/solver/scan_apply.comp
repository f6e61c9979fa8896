#version 460
// RockDEM exclusive prefix sum, part 3: result[i] = sum of data[0 .. i-1], block by block.
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
  uint values[4];
  uint sum = 0u;
  for (uint k = 0u; k < 4u; ++k) {
    values[k] = base + k < push.count ? push.data.v[base + k] : 0u;
    sum += values[k];
  }
  sums[t] = sum;
  barrier();
  if (t == 0u) {
    uint running = push.blocks.v[gl_WorkGroupID.x];
    for (uint k = 0u; k < 256u; ++k) {
      const uint s = sums[k];
      sums[k] = running;
      running += s;
    }
  }
  barrier();
  uint running = sums[t];
  for (uint k = 0u; k < 4u; ++k) {
    if (base + k < push.count) {
      push.result.v[base + k] = running;
    }
    running += values[k];
  }
}
