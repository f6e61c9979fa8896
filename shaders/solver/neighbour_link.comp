#version 460
// RockDEM neighbour build: the gather list entries, 2 x pair (+1 when the particle is j of
// the pair), in the order of its sorted neighbours; a pair below the particle is found by
// binary search in that neighbour's pair list. Then the tangential and rolling history of
// the pairs that were already in the old list is carried over (push.carry = 1, one
// invocation per new pair; binary search in the old list of i).
#include "state.glsl"
layout(local_size_x = 64) in;
layout(push_constant) uniform Push { Params p; uint carry; } push;

/// Index of `value` in the sorted list[first, last), or ~0u.
uint find(Uints list, uint first, uint last, uint value)
{
  while (first < last) {
    const uint middle = first + (last - first) / 2u;
    const uint m = list.v[middle];
    if (m < value) {
      first = middle + 1u;
    } else if (m > value) {
      last = middle;
    } else {
      return middle;
    }
  }
  return ~0u;
}

void main()
{
  Params p = push.p;
  if (halted(p)) {
    return;
  }
  if (push.carry != 0u) {
    const uint k = itemIndex();
    if (k >= p.ctl.v[CTL_PAIRS]) {
      return;
    }
    const uint i = p.pairI.v[k];
    const uint o = find(p.oldPairJ, p.oldPairStart.v[i], p.oldPairStart.v[i + 1u], p.pairJ.v[k]);
    if (o != ~0u) {
      store3(p.pairSpring, k, load3(p.oldPairSpring, o));
      if (p.rolling != 0u) {
        store3(p.pairRolling, k, load3(p.oldPairRolling, o));
      }
    }
    return;
  }
  const uint i = itemIndex();
  if (i >= p.n) {
    return;
  }
  const uint base = p.adjacencyStart.v[i];
  const uint count = p.adjacencyStart.v[i + 1u] - base;
  const uint pairBase = p.pairStart.v[i];
  const uint below = count - (p.pairStart.v[i + 1u] - pairBase);
  for (uint t = 0u; t < count; ++t) {
    const uint partner = p.partners.v[base + t];
    if (t >= below) {
      p.adjacency.v[base + t] = 2u * (pairBase + t - below);
    } else {
      const uint k = find(p.pairJ, p.pairStart.v[partner], p.pairStart.v[partner + 1u], i);
      p.adjacency.v[base + t] = 2u * k + 1u;
    }
  }
}
