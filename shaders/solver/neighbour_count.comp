#version 460
// RockDEM neighbour build: how many neighbours each particle has (all of them: its gather
// list; those above it: its pairs). One invocation per particle; entry N stays 0 (the
// scans then end with the totals).
#include "grid.glsl"
layout(local_size_x = 64) in;
layout(push_constant) uniform Push { Params p; } push;

void main()
{
  Params p = push.p;
  const uint i = itemIndex();
  if (i >= p.n || halted(p)) {
    return;
  }
  const uvec2 counts = searchNeighbours(p, p.valuesA, i, false, 0u);
  p.fullCount.v[i] = counts.x;
  p.halfCount.v[i] = counts.y;
}
