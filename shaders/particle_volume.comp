#version 450
// Volume of each particle: a sphere (4/3 pi r^3) or, in a 2D section, a disc through
// the slab (pi r^2 t). SI units: m^3. One invocation per particle.
layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer Radius { double radius[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Volume { double volume[]; };

layout(push_constant) uniform Params {
  uint count;          // number of particles
  uint section2D;      // 1: discs through a slab of thickness `slab`
  double slab;         // m
} params;

const double PI = 3.14159265358979323846LF;

void main()
{
  uint i = gl_GlobalInvocationID.x;
  if (i >= params.count) {
    return;
  }
  double r = radius[i];
  volume[i] = (params.section2D != 0u) ? PI * r * r * params.slab
                                       : (4.0LF / 3.0LF) * PI * r * r * r;
}
