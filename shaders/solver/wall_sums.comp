#version 460
// RockDEM step, end (CpuBackend::computeForces, part 5): each wall's reaction, contact
// stiffness (the servo's gain), elastic push and contact count, summed over its touching
// entries in slot order, one invocation per wall (the CPU's order, bit for bit); then the
// clock. One workgroup of 6 invocations.
#include "state.glsl"
layout(local_size_x = 6) in;
layout(push_constant) uniform Push { Params p; } push;

void main()
{
  Params p = push.p;
  if (halted(p)) {
    return;
  }
  const uint w = gl_LocalInvocationID.x;
  dvec3 reaction = dvec3(0.0LF);
  double stiffness = 0.0LF;
  double elastic = 0.0LF;
  uint contacts = 0u;
  const uint entries = p.ctl.v[CTL_WALL_ENTRIES];
  for (uint e = 0u; e < entries; ++e) {
    if (p.wallTouching.v[e] != 0u && p.wallIndex.v[e] == w) {
      reaction -= load3(p.wallForce, e);
      stiffness += p.wallStiffness.v[e];
      elastic += p.wallElastic.v[e];
      ++contacts;
    }
  }
  const uint base = WALL_STRIDE * w;
  p.walls.v[base + WALL_ELASTIC] = elastic;
  p.walls.v[base + WALL_FORCE] = reaction.x;
  p.walls.v[base + WALL_FORCE + 1u] = reaction.y;
  p.walls.v[base + WALL_FORCE + 2u] = reaction.z;
  p.walls.v[base + WALL_STIFFNESS] = stiffness;
  p.walls.v[base + WALL_CONTACTS] = double(contacts);
  if (w == 0u) {
    p.clock.v[CLOCK_TIME] = p.clock.v[CLOCK_TIME] + p.dt;
    p.ctl.v[CTL_STEPS_DONE] += 1u;
  }
}
