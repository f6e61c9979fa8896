#version 460
// RockDEM radix sort, pass part 2 (one workgroup): exclusive prefix sum of the histogram
// in (digit, tile) order, so that each tile knows where its keys of each digit go.
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

shared uint sums[256];

void main()
{
  Params p = push.p;
  if (halted(p)) {
    return;
  }
  const uint t = gl_LocalInvocationID.x;
  const uint total = 16u * p.sortTiles;
  const uint chunk = (total + 255u) / 256u;
  const uint first = t * chunk;
  const uint last = min(first + chunk, total);
  uint sum = 0u;
  for (uint k = first; k < last; ++k) {
    sum += p.histogram.v[k];
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
    const uint c = p.histogram.v[k];
    p.histogram.v[k] = running;
    running += c;
  }
}
