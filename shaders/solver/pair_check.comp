#version 460
// RockDEM neighbour build (one invocation): does the new list fit? If not, the submission
// halts (HALT_PAIRS, with the size needed) before anything is overwritten, and the host
// grows the lists and resumes. Otherwise the counts change to the new list's and the
// indirect arguments of the copy, fill and pair kernels are set.
#include "state.glsl"
layout(local_size_x = 1) in;
layout(push_constant) uniform Push { Params p; } push;

void main()
{
  Params p = push.p;
  if (halted(p)) {
    return;
  }
  const uint pairs = p.halfScan.v[p.n];
  const uint entries = p.fullScan.v[p.n];
  if (pairs > p.pairCapacity || entries > p.adjacencyCapacity) {
    p.ctl.v[CTL_NEED_PAIRS] = pairs;
    p.ctl.v[CTL_HALTED] = HALT_PAIRS;
    return;
  }
  const uint old = p.ctl.v[CTL_PAIRS];
  p.ctl.v[CTL_OLD_PAIRS] = old;
  p.ctl.v[CTL_PAIRS] = pairs;
  p.ctl.v[CTL_ADJACENCY] = entries;
  p.ctl.v[CTL_REBUILDS] += 1u;
  setItems(p, IND_FULL_COPY, max(old, p.n + 1u));
  setItems(p, IND_NEW_PAIRS, pairs);
  setItems(p, IND_PAIRS, pairs);
}
