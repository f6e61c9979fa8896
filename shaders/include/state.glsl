// RockDEM shaders: the device-resident state of the Vulkan backend. Every kernel gets the
// address of the parameter block (params_fields.h) in its push constants and reaches all
// arrays through buffer device addresses, so no per-binding range limit applies.
// Layout of the control arrays: CTL_* (uint counters and flags), WALL_* (16 doubles per
// wall), CLOCK_* and IND_* (VkDispatchIndirectCommand triples). SI units.
#ifndef ROCKDEM_STATE_GLSL
#define ROCKDEM_STATE_GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require

#include "vec.glsl"

layout(buffer_reference, std430, buffer_reference_align = 8) buffer Doubles { double v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer Uints { uint v[]; };

#define ROCKDEM_ADDR(type, name) type name;
#define ROCKDEM_SCALAR(type, name) type name;
#define ROCKDEM_ARRAY(type, name, count) type name[count];
layout(buffer_reference, std430, buffer_reference_align = 8) buffer Params {
#include "params_fields.h"
};
#undef ROCKDEM_ADDR
#undef ROCKDEM_SCALAR
#undef ROCKDEM_ARRAY

#include "control.h"

dvec3 load3(Doubles a, uint i)
{
  return dvec3(a.v[3u * i], a.v[3u * i + 1u], a.v[3u * i + 2u]);
}

void store3(Doubles a, uint i, dvec3 x)
{
  a.v[3u * i] = x.x;
  a.v[3u * i + 1u] = x.y;
  a.v[3u * i + 2u] = x.z;
}

/// The item of this invocation in a per-item kernel (local size GROUP_SIZE), dispatched as
/// (x, y) workgroups: x at most DISPATCH_X (above the smallest maxComputeWorkGroupCount).
uint itemIndex()
{
  return gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * GROUP_SIZE;
}

/// Writes the indirect arguments for `items` invocations of a per-item kernel.
void setItems(Params p, uint slot, uint items)
{
  const uint groups = (items + GROUP_SIZE - 1u) / GROUP_SIZE;
  p.indirect.v[slot] = min(groups, DISPATCH_X);
  p.indirect.v[slot + 1u] = groups == 0u ? 0u : (groups + DISPATCH_X - 1u) / DISPATCH_X;
  p.indirect.v[slot + 2u] = 1u;
}

/// Writes the indirect arguments for `groups` workgroups of a tiled kernel (x only).
void setGroups(Params p, uint slot, uint groups)
{
  p.indirect.v[slot] = groups;
  p.indirect.v[slot + 1u] = 1u;
  p.indirect.v[slot + 2u] = 1u;
}

/// True once a kernel of this submission stopped it (a list outgrew its capacity): every
/// later kernel then does nothing, and the host resumes after growing the list.
bool halted(Params p)
{
  return p.ctl.v[CTL_HALTED] != 0u;
}

#endif
