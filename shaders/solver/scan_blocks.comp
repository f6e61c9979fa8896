#version 460
// RockDEM exclusive prefix sum, part 2 (one workgroup): the block sums become block offsets.
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
  const uint total = (push.count + SCAN_BLOCK - 1u) / SCAN_BLOCK;
  const uint chunk = (total + 255u) / 256u;
  const uint first = t * chunk;
  const uint last = min(first + chunk, total);
  uint sum = 0u;
  for (uint k = first; k < last; ++k) {
    sum += push.blocks.v[k];
  }
  sums[t] = sum;
  barrier();
  if (t == 0u) {
    uint running = 0u;
    for (uint k = 0u; k < 256u; ++k) {
      const uint s = sums[k];
      sums[k] = running;
      running += s;
    }
  }
  barrier();
  uint running = sums[t];
  for (uint k = first; k < last; ++k) {
    const uint s = push.blocks.v[k];
    push.blocks.v[k] = running;
    running += s;
  }
}
