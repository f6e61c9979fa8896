#version 460
// RockDEM radix sort (least significant digit first, 4 bits per pass, stable), pass part
// 1: the digit histogram of each tile of 1024 keys. Integer counts only: the result does
// not depend on scheduling. No inter-workgroup communication within a dispatch (no
// forward-progress assumption). One workgroup per tile.
#include "state.glsl"
layout(local_size_x = 256) in;
layout(push_constant) uniform Push {
  Params p;
  Uints keysIn;
  Uints valuesIn;
  Uints keysOut;
  Uints valuesOut;
  uint shift;
  uint count;
} push;

shared uint counts[16];

void main()
{
  const uint t = gl_LocalInvocationID.x;
  const uint tile = gl_WorkGroupID.x;
  const uint tiles = gl_NumWorkGroups.x;
  if (halted(push.p)) {
    return;
  }
  if (t < 16u) {
    counts[t] = 0u;
  }
  barrier();
  for (uint k = 0u; k < 4u; ++k) {
    const uint index = tile * SORT_TILE + 4u * t + k;
    if (index < push.count) {
      atomicAdd(counts[(push.keysIn.v[index] >> push.shift) & 15u], 1u);
    }
  }
  barrier();
  if (t < 16u) {
    push.p.histogram.v[t * tiles + tile] = counts[t];
  }
}
