#version 460
// RockDEM radix sort, pass part 3: each tile writes its keys (and values) to their places,
// keeping the order of equal digits (stable): invocation t owns items 4t .. 4t+3 of the
// tile; its offset for a digit is the tile's offset plus the count of that digit in the
// items of invocations 0 .. t-1. One workgroup per tile.
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

shared uint counts[16][256];

void main()
{
  const uint t = gl_LocalInvocationID.x;
  const uint tile = gl_WorkGroupID.x;
  const uint tiles = gl_NumWorkGroups.x;
  if (halted(push.p)) {
    return;
  }
  uint keys[4];
  uint digits[4];
  uint items = 0u;
  for (uint d = 0u; d < 16u; ++d) {
    counts[d][t] = 0u;
  }
  for (uint k = 0u; k < 4u; ++k) {
    const uint index = tile * SORT_TILE + 4u * t + k;
    if (index < push.count) {
      keys[k] = push.keysIn.v[index];
      digits[k] = (keys[k] >> push.shift) & 15u;
      counts[digits[k]][t] += 1u;
      items = k + 1u;
    }
  }
  barrier();
  if (t < 16u) {
    uint running = push.p.histogram.v[t * tiles + tile];
    for (uint k = 0u; k < 256u; ++k) {
      const uint c = counts[t][k];
      counts[t][k] = running;
      running += c;
    }
  }
  barrier();
  for (uint k = 0u; k < items; ++k) {
    const uint index = tile * SORT_TILE + 4u * t + k;
    const uint destination = counts[digits[k]][t];
    counts[digits[k]][t] = destination + 1u;
    push.keysOut.v[destination] = keys[k];
    push.valuesOut.v[destination] = push.valuesIn.v[index];
  }
}
