#version 460
// RockDEM neighbour build: the cell key of each particle (its size class's grid) and its
// slot, the input of the radix sort. One invocation per particle.
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
  p.keysA.v[i] = cellKey(p, p.sizeClass.v[i], wrapped(p, load3(p.position, i)));
  p.valuesA.v[i] = i;
}
