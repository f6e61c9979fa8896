// RockDEM shaders: the contact force laws, the GLSL mirror of dem/ContactLaws.h (PHYSICS.md
// section 1). Each function performs the same operations in the same order as its C++
// twin, so that both give the same bits (checked by the parity test, VulkanLaws.SameBitsAsTheCppLawsOnTheDevice).
// SI units: m, kg, s, N, Pa. Overlap > 0 in contact; approach speed > 0 approaching.
#ifndef ROCKDEM_CONTACT_LAWS_GLSL
#define ROCKDEM_CONTACT_LAWS_GLSL

#include "vec.glsl"

const double PI = 3.14159265358979323846LF;
const uint LAW_HERTZ_MINDLIN = 0u;
const uint LAW_LINEAR = 1u;

/// dem::ContactModel (the fields the step uses).
struct ContactModel {
  uint law;
  double dampingCoefficient;
  double friction;
  double rollingFriction;
  double youngsModulus;
  double poissonsRatio;
};

/// dem::PairProperties.
struct PairProperties {
  double effectiveModulus;
  double effectiveShearModulus;
  double effectiveRadius;
  double effectiveMass;
  double linearNormalStiffness;
  double linearShearStiffness;
};

/// dem::ContactConstants.
struct ContactConstants {
  double normalStiffness;
  double normalDamping;
  double tangentialStiffness;
};

/// dem::NormalResponse.
struct NormalResponse {
  double elasticForce;
  double force;
  double stiffness;
  double tangentialStiffness;
};

double shearModulus(double youngsModulus, double poissonsRatio)
{
  return youngsModulus / (2.0LF * (1.0LF + poissonsRatio));
}

double linearStiffness(double youngsModulus, double contactRadius, double springLength,
                       bool section2D, double slab)
{
  const double area = section2D ? 2.0LF * contactRadius * slab : PI * contactRadius * contactRadius;
  return area * youngsModulus / springLength;
}

double shearToNormalRatio(double poissonsRatio)
{
  return 2.0LF * (1.0LF - poissonsRatio) / (2.0LF - poissonsRatio);
}

/// dem::pairProperties.
PairProperties pairProperties(ContactModel model, double radiusA, double massA, double radiusB,
                              double massB, bool section2D, double slab)
{
  const double nu = model.poissonsRatio;
  const double E = model.youngsModulus;
  PairProperties p;
  p.effectiveModulus = E / (2.0LF * (1.0LF - nu * nu));
  p.effectiveShearModulus = shearModulus(E, nu) / (2.0LF * (2.0LF - nu));
  p.effectiveRadius = radiusA * radiusB / (radiusA + radiusB);
  if (isinf(massA)) {
    p.effectiveMass = massB;
  } else if (isinf(massB)) {
    p.effectiveMass = massA;
  } else {
    p.effectiveMass = massA * massB / (massA + massB);
  }
  p.linearNormalStiffness =
    linearStiffness(E, stdMin(radiusA, radiusB), radiusA + radiusB, section2D, slab);
  p.linearShearStiffness = p.linearNormalStiffness * shearToNormalRatio(nu);
  return p;
}

/// dem::wallProperties.
PairProperties wallProperties(ContactModel model, double radius, double mass, bool section2D,
                              double slab)
{
  const double nu = model.poissonsRatio;
  const double E = model.youngsModulus;
  PairProperties p;
  p.effectiveModulus = E / (1.0LF - nu * nu);
  p.effectiveShearModulus = shearModulus(E, nu) / (2.0LF - nu);
  p.effectiveRadius = radius;
  p.effectiveMass = mass;
  p.linearNormalStiffness = linearStiffness(E, radius, radius, section2D, slab);
  p.linearShearStiffness = p.linearNormalStiffness * shearToNormalRatio(nu);
  return p;
}

/// dem::contactConstants.
ContactConstants contactConstants(ContactModel model, PairProperties pair)
{
  ContactConstants c;
  const bool damped = !isinf(pair.effectiveMass) && !isnan(pair.effectiveMass) &&
    model.dampingCoefficient > 0.0LF;
  if (model.law == LAW_HERTZ_MINDLIN) {
    const double rootRadius = sqrt(pair.effectiveRadius);
    c.normalStiffness = 4.0LF / 3.0LF * pair.effectiveModulus * rootRadius;
    c.normalDamping = damped ? model.dampingCoefficient * sqrt(pair.effectiveMass * c.normalStiffness) : 0.0LF;
    c.tangentialStiffness = 8.0LF * pair.effectiveShearModulus * rootRadius;
  } else {
    c.normalStiffness = pair.linearNormalStiffness;
    c.normalDamping = damped
      ? 2.0LF * model.dampingCoefficient * sqrt(pair.effectiveMass * pair.linearNormalStiffness)
      : 0.0LF;
    c.tangentialStiffness = pair.linearShearStiffness;
  }
  return c;
}

/// dem::normalStiffness (used by the rolling spring).
double normalStiffness(ContactModel model, PairProperties pair, double overlap)
{
  if (model.law == LAW_HERTZ_MINDLIN) {
    return 2.0LF * pair.effectiveModulus * sqrt(pair.effectiveRadius * stdMax(overlap, 0.0LF));
  }
  return pair.linearNormalStiffness;
}

/// dem::hertzMindlinResponse: Hertz with Tsuji-type damping, cut off at zero.
NormalResponse hertzMindlinResponse(ContactConstants c, double overlap, double approachSpeed)
{
  const double root = sqrt(overlap);
  const double elastic = c.normalStiffness * overlap * root;
  const double viscous = c.normalDamping * sqrt(root) * approachSpeed;
  const double force = elastic + viscous;
  NormalResponse r;
  r.elasticForce = elastic;
  r.force = force > 0.0LF ? force : 0.0LF;
  r.stiffness = 1.5LF * c.normalStiffness * root;
  r.tangentialStiffness = c.tangentialStiffness * root;
  return r;
}

/// dem::linearResponse: linear spring-dashpot, cut off at zero.
NormalResponse linearResponse(ContactConstants c, double overlap, double approachSpeed)
{
  const double elastic = c.normalStiffness * overlap;
  const double force = elastic + c.normalDamping * approachSpeed;
  NormalResponse r;
  r.elasticForce = elastic;
  r.force = force > 0.0LF ? force : 0.0LF;
  r.stiffness = c.normalStiffness;
  r.tangentialStiffness = c.tangentialStiffness;
  return r;
}

/// dem::normalResponse.
NormalResponse normalResponse(uint law, ContactConstants c, double overlap, double approachSpeed)
{
  return law == LAW_HERTZ_MINDLIN ? hertzMindlinResponse(c, overlap, approachSpeed)
                                  : linearResponse(c, overlap, approachSpeed);
}

/// dem::inPlane: v without its component along the unit normal n.
dvec3 inPlane(dvec3 v, dvec3 n)
{
  return v - dot3(v, n) * n;
}

/// dem::rotateIntoPlane: a stored in-plane vector turned into the plane normal to n,
/// keeping its length.
dvec3 rotateIntoPlane(dvec3 v, dvec3 n)
{
  const double length2 = squaredNorm3(v);
  if (length2 == 0.0LF) {
    return dvec3(0.0LF);
  }
  const dvec3 projected = inPlane(v, n);
  const double projected2 = squaredNorm3(projected);
  return projected2 > 0.0LF ? projected * sqrt(length2 / projected2) : dvec3(0.0LF);
}

/// dem::mindlinCoulombForce: the incremental tangential spring (m, updated in place),
/// capped at mu Fn; returns the tangential force on particle A (N).
dvec3 mindlinCoulombForce(double kt, double friction, double normalForceMagnitude, dvec3 n,
                          dvec3 slipIncrement, inout dvec3 spring)
{
  spring = rotateIntoPlane(spring, n) + slipIncrement;
  const double limit = friction * normalForceMagnitude;
  const double trial2 = kt * kt * squaredNorm3(spring);
  if (trial2 > limit * limit) {
    const double trial = sqrt(trial2);
    spring *= (kt > 0.0LF && trial > 0.0LF) ? limit / trial : 0.0LF;
  }
  return -kt * spring;
}

/// dem::rollingTorque: elastic-plastic rolling resistance (Ai et al. 2011, model A); the
/// rolling spring (N m) is updated in place; returns the torque on A (N m).
dvec3 rollingTorque(ContactModel model, PairProperties pair, double overlap,
                    double normalForceMagnitude, dvec3 n, dvec3 rollIncrement, inout dvec3 spring)
{
  if (model.rollingFriction <= 0.0LF) {
    spring = dvec3(0.0LF);
    return dvec3(0.0LF);
  }
  const double R = pair.effectiveRadius;
  const double kr = 2.25LF * normalStiffness(model, pair, overlap) * model.rollingFriction *
    model.rollingFriction * R * R;
  spring = rotateIntoPlane(spring, n) - kr * rollIncrement;
  const double limit = model.rollingFriction * R * normalForceMagnitude;
  const double magnitude = norm3(spring);
  if (magnitude > limit) {
    spring *= magnitude > 0.0LF ? limit / magnitude : 0.0LF;
  }
  return spring;
}

/// dem::cundallDamping: Cundall local damping of one degree of freedom,
/// F - alpha |F| sign(v), with sign(0) = 0.
double cundallDamping(double force, double velocity, double alpha)
{
  const double damping = copySign(alpha * abs(force), velocity);
  return force - (velocity != 0.0LF ? damping : 0.0LF);
}

/// dem::cundallDampingWork: the work (J) Cundall damping takes from a particle in a step dt.
double cundallDampingWork(dvec3 force, dvec3 damped, dvec3 velocity, dvec3 torque, dvec3 dampedTorque,
                          dvec3 spin, double dt)
{
  return (dot3(force - damped, velocity) + dot3(torque - dampedTorque, spin)) * dt;
}

#endif
