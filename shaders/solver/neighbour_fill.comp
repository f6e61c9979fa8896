#version 460
// RockDEM neighbour build: each particle's neighbours, sorted by slot (its gather order),
// and its pairs (the neighbours above it) with their contact constants and a cleared
// state; the particle's position becomes its position at the build. One invocation per
// particle.
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
  const uint base = p.adjacencyStart.v[i];
  const uint count = p.adjacencyStart.v[i + 1u] - base;
  searchNeighbours(p, p.valuesA, i, true, base);
  // Insertion sort of the (short) list.
  for (uint a = 1u; a < count; ++a) {
    const uint value = p.partners.v[base + a];
    uint b = a;
    while (b > 0u && p.partners.v[base + b - 1u] > value) {
      p.partners.v[base + b] = p.partners.v[base + b - 1u];
      --b;
    }
    p.partners.v[base + b] = value;
  }
  const uint pairBase = p.pairStart.v[i];
  const uint pairs = p.pairStart.v[i + 1u] - pairBase;
  const uint below = count - pairs;
  const ContactModel cm = contactModel(p, false, 0u);
  const bool planar = p.planar != 0u;
  for (uint t = 0u; t < pairs; ++t) {
    const uint j = p.partners.v[base + below + t];
    const uint k = pairBase + t;
    p.pairI.v[k] = i;
    p.pairJ.v[k] = j;
    storeConstants(p.pairConstants, k, contactConstants(cm,
      pairProperties(cm, p.radius.v[i], massOf(p, i), p.radius.v[j], massOf(p, j), planar, p.sizeZ)));
    store3(p.pairSpring, k, dvec3(0.0LF));
    if (p.rolling != 0u) {
      store3(p.pairRolling, k, dvec3(0.0LF));
    }
    store3(p.pairForce, k, dvec3(0.0LF));
    store3(p.pairTorqueI, k, dvec3(0.0LF));
    store3(p.pairTorqueJ, k, dvec3(0.0LF));
    p.pairNormal.v[k] = 0.0LF;
  }
  store3(p.positionAtBuild, i, load3(p.position, i));
}
