// RockDEM shaders: vector arithmetic in double precision, in the order Eigen evaluates it
// on the CPU (so that the device rounds exactly where the CPU does).
//   a.dot(b)        = (a.x b.x + a.y b.y) + a.z b.z
//   a.squaredNorm() = a.dot(a);  a.norm() = sqrt(a.squaredNorm())
//   a.cross(b)      = (a.y b.z - a.z b.y, a.z b.x - a.x b.z, a.x b.y - a.y b.x)
//   s * a, a + b, a - b: per component.
// Every floating-point operation carries NoContraction (added when the pipeline is
// created), so no driver fuses them into FMAs. SI units are the caller's.
#ifndef ROCKDEM_VEC_GLSL
#define ROCKDEM_VEC_GLSL

double dot3(dvec3 a, dvec3 b)
{
  return (a.x * b.x + a.y * b.y) + a.z * b.z;
}

double squaredNorm3(dvec3 a)
{
  return dot3(a, a);
}

double norm3(dvec3 a)
{
  return sqrt(squaredNorm3(a));
}

dvec3 cross3(dvec3 a, dvec3 b)
{
  return dvec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}

/// Eigen's isZero(0.0): every component is exactly zero (either sign).
bool isZero3(dvec3 a)
{
  return abs(a.x) <= 0.0LF && abs(a.y) <= 0.0LF && abs(a.z) <= 0.0LF;
}

/// Eigen's allFinite().
bool allFinite3(dvec3 a)
{
  return !(isinf(a.x) || isnan(a.x) || isinf(a.y) || isnan(a.y) || isinf(a.z) || isnan(a.z));
}

/// +infinity (a fixed particle's mass).
double infinity()
{
  return packDouble2x32(uvec2(0u, 0x7ff00000u));
}

/// std::copysign(x, s).
double copySign(double x, double s)
{
  uvec2 xb = unpackDouble2x32(x);
  const uvec2 sb = unpackDouble2x32(s);
  xb.y = (xb.y & 0x7fffffffu) | (sb.y & 0x80000000u);
  return packDouble2x32(xb);
}

/// std::min(a, b) and std::max(a, b) (the first argument when they compare equal or
/// either is NaN), unlike GLSL's min and max.
double stdMin(double a, double b)
{
  return (b < a) ? b : a;
}

double stdMax(double a, double b)
{
  return (a < b) ? b : a;
}

#endif
