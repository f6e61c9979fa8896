#version 460
// RockDEM neighbour build: keep the old pair list (starts, partners, springs) for the
// history carried over, and install the new list starts. One invocation per item of
// max(old pairs, N + 1).
#include "state.glsl"
layout(local_size_x = 64) in;
layout(push_constant) uniform Push { Params p; } push;

void main()
{
  Params p = push.p;
  const uint k = itemIndex();
  if (halted(p)) {
    return;
  }
  if (k <= p.n) {
    p.oldPairStart.v[k] = p.pairStart.v[k];
    p.pairStart.v[k] = p.halfScan.v[k];
    p.adjacencyStart.v[k] = p.fullScan.v[k];
  }
  if (k < p.ctl.v[CTL_OLD_PAIRS]) {
    p.oldPairJ.v[k] = p.pairJ.v[k];
    store3(p.oldPairSpring, k, load3(p.pairSpring, k));
    if (p.rolling != 0u) {
      store3(p.oldPairRolling, k, load3(p.pairRolling, k));
    }
  }
}
