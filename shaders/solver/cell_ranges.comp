#version 460
// RockDEM neighbour build: after the sort, the range [cellStart, cellEnd) of the sorted
// particles in each non-empty cell (push.clear = 1: first empty every cell; one
// invocation per cell. push.clear = 0: one invocation per sorted particle, which writes
// the start or end of its cell when it is the first or last there).
#include "state.glsl"
layout(local_size_x = 64) in;
layout(push_constant) uniform Push { Params p; uint clear; } push;

void main()
{
  Params p = push.p;
  const uint s = itemIndex();
  if (halted(p)) {
    return;
  }
  if (push.clear != 0u) {
    if (s < p.totalCells) {
      p.cellStart.v[s] = 0u;
      p.cellEnd.v[s] = 0u;
    }
    return;
  }
  if (s >= p.n) {
    return;
  }
  const uint key = p.keysA.v[s];
  if (s == 0u || p.keysA.v[s - 1u] != key) {
    p.cellStart.v[key] = s;
  }
  if (s + 1u == p.n || p.keysA.v[s + 1u] != key) {
    p.cellEnd.v[key] = s + 1u;
  }
}
