// RockDEM shaders: the model box as the step sees it (minimum image, periodic wrap,
// particle masses), mirroring dem::minimumImage and the CPU backend's helpers. SI units.
#ifndef ROCKDEM_GEOMETRY_GLSL
#define ROCKDEM_GEOMETRY_GLSL

#include "state.glsl"
#include "contact_laws.glsl"

dvec3 origin(Params p)
{
  return dvec3(p.originX, p.originY, p.originZ);
}

dvec3 boxSize(Params p)
{
  return dvec3(p.sizeX, p.sizeY, p.sizeZ);
}

/// dem::minimumImage: b - a, with the nearest copy across a periodic axis; z = 0 in 2D.
dvec3 minimumImage(Params p, dvec3 a, dvec3 b)
{
  dvec3 s = b - a;
  const dvec3 size = boxSize(p);
  for (int k = 0; k < 3; ++k) {
    if ((p.periodicMask & (1u << k)) != 0u) {
      s[k] -= size[k] * roundEven(s[k] / size[k]);
    }
  }
  if (p.planar != 0u) {
    s.z = 0.0LF;
  }
  return s;
}

/// The CPU backend's MinimumImage: the plain difference in a box without periodic axes
/// (and not a 2D section).
dvec3 separationOf(Params p, dvec3 a, dvec3 b)
{
  return p.plain != 0u ? b - a : minimumImage(p, a, b);
}

/// A particle's mass as the contact laws take it: infinite for a fixed one.
double massOf(Params p, uint i)
{
  return p.inverseMass.v[i] > 0.0LF ? p.mass.v[i] : infinity();
}

/// The contact model of the particle pairs (wall = false) or of the walls (side walls
/// frictionless during a press test; the platens, the walls on the test axis, with the
/// test's Platen Friction, which the host sets to the walls' friction outside a test).
ContactModel contactModel(Params p, bool wall, uint wallAxis)
{
  ContactModel m;
  m.law = p.law;
  m.dampingCoefficient = p.dampingCoefficient;
  m.friction = wall ? (wallAxis == p.axis ? p.platenFriction : p.wallFriction) : p.friction;
  m.rollingFriction = wall ? p.wallRollingFriction : p.rollingFriction;
  m.youngsModulus = p.youngsModulus;
  m.poissonsRatio = p.poissonsRatio;
  return m;
}

ContactConstants loadConstants(Doubles a, uint k)
{
  ContactConstants c;
  c.normalStiffness = a.v[3u * k];
  c.normalDamping = a.v[3u * k + 1u];
  c.tangentialStiffness = a.v[3u * k + 2u];
  return c;
}

void storeConstants(Doubles a, uint k, ContactConstants c)
{
  a.v[3u * k] = c.normalStiffness;
  a.v[3u * k + 1u] = c.normalDamping;
  a.v[3u * k + 2u] = c.tangentialStiffness;
}

#endif
