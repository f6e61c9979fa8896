// RockDEM engine: contact force laws (PHYSICS.md section 1).
//
// One function per force law, named as in the references. SI units: m, kg, s, N, Pa.
// The laws the time step uses (pairProperties, wallProperties, contactConstants,
// normalStiffness, the responses, rotateIntoPlane, mindlinCoulombForce, rollingTorque,
// cundallDamping) have a GLSL twin in shaders/include/contact_laws.glsl that performs the
// same operations in the same order; VulkanLaws.SameBitsAsTheCppLawsOnTheDevice requires identical bits.
// Sign conventions: overlap delta > 0 while in contact; approach speed (d delta / dt)
// is positive while the surfaces approach. Normal forces are magnitudes along the
// contact normal, repulsive, never negative (no-tension cut-off: the contact ends
// when the force reaches zero, with no attraction).
#pragma once

#include "dem/ContactLawKind.h"
#include "dem/ContactLawLanes.h"
#include "dem/Model.h"

#include <cmath>

namespace dem {

/// Effective properties of one contact (PHYSICS.md section 1). A rigid wall has
/// infinite mass and radius: then E* = E/(1-nu^2), R* = R, m* = m.
struct PairProperties {
  double effectiveModulus = 0.0;       ///< E*, Pa
  double effectiveShearModulus = 0.0;  ///< G* (Mindlin), Pa
  double effectiveRadius = 0.0;        ///< R*, m
  double effectiveMass = 0.0;          ///< m*, kg
  double linearNormalStiffness = 0.0;  ///< kn of the linear law, N/m
  double linearShearStiffness = 0.0;   ///< kt of the linear law, N/m
};

/// The calibrated contact model for one material: law, damping coefficient that
/// delivers the requested restitution, friction and rolling resistance.
struct ContactModel {
  ContactLaw law = ContactLaw::HertzMindlin;
  double restitution = 0.5;        ///< requested coefficient of restitution, [0, 1]
  double dampingCoefficient = 0.0; ///< Hertz: c of Tsuji-type damping; linear: damping ratio zeta
  double friction = 0.5;           ///< Coulomb coefficient mu
  double rollingFriction = 0.0;    ///< rolling resistance coefficient mu_r
  double youngsModulus = 1e9;      ///< Pa
  double poissonsRatio = 0.25;     ///< -
};

/// Builds the contact model for a material: calibrates the damping coefficient so that
/// a head-on collision with the no-tension cut-off delivers material.restitution.
ContactModel makeContactModel(const Material& material, ContactLaw law);

/// Effective properties of a particle-particle contact. `section2D`, `slab` (m): the
/// linear law uses the disc-through-slab area 2 r t in 2D.
PairProperties pairProperties(const ContactModel& model, double radiusA, double massA,
                              double radiusB, double massB, bool section2D, double slab);
/// Effective properties of a particle-wall contact (rigid, flat wall).
PairProperties wallProperties(const ContactModel& model, double radius, double mass,
                              bool section2D, double slab);

/// Hertz elastic normal force, N: F = 4/3 E* sqrt(R*) delta^(3/2).
double hertzElasticForce(double effectiveModulus, double effectiveRadius, double overlap);

/// Total normal force of the contact law, N (>= 0): elastic part plus viscous damping
/// (Hertz: c sqrt(m* K) delta^(1/4) d(delta)/dt with K = 4/3 E* sqrt(R*); linear:
/// 2 zeta sqrt(m* kn) d(delta)/dt), cut off at zero.
double normalForce(const ContactModel& model, const PairProperties& pair, double overlap,
                   double approachSpeed);

/// Current normal contact stiffness dF/d(delta), N/m (Hertz: 2 E* sqrt(R* delta)).
double normalStiffness(const ContactModel& model, const PairProperties& pair, double overlap);
/// Current tangential stiffness, N/m (Mindlin: 8 G* sqrt(R* delta); linear: kt).
double tangentialStiffness(const ContactModel& model, const PairProperties& pair, double overlap);

/// Incremental tangential spring (Mindlin / Coulomb). `spring` (m) is the stored
/// tangential displacement: it is first rotated into the current contact plane (normal
/// `n`, unit), then incremented by the tangential relative displacement of the contact
/// point `slipIncrement` (m, already in the plane), and capped so that the force
/// magnitude does not exceed mu Fn (gross sliding). Returns the tangential force on
/// particle A, N: Ft = -kt * spring.
Vec3 tangentialForce(const ContactModel& model, const PairProperties& pair, double overlap,
                     double normalForceMagnitude, const Vec3& n, const Vec3& slipIncrement,
                     Vec3& spring);

/// Elastic-plastic rolling resistance (Ai, Chen, Rotter & Ooi 2011, model A): rolling
/// spring kr = 2.25 kn mu_r^2 R*^2 on the relative rolling rotation `rollIncrement`
/// (rad, perpendicular to n), torque capped at mu_r R* Fn. `spring` (N m) is the stored
/// rolling torque, rotated into the current plane first. Returns the torque on A, N m.
Vec3 rollingTorque(const ContactModel& model, const PairProperties& pair, double overlap,
                   double normalForceMagnitude, const Vec3& n, const Vec3& rollIncrement,
                   Vec3& spring);

/// Eigen's Vector3d as the vector type of the laws in dem/ContactLawLanes.h (the CPU
/// backend's scalar loop and the wall contacts run them on it).
template <> struct VecOps<Vec3> {
  using Scalar = double;
  static double dot(const Vec3& a, const Vec3& b) { return a.dot(b); }
  static double squaredNorm(const Vec3& a) { return a.squaredNorm(); }
  static Vec3 cross(const Vec3& a, const Vec3& b) { return a.cross(b); }
  static Vec3 scaled(double s, const Vec3& v) { return s * v; }
  static Vec3 divided(const Vec3& v, double s) { return v / s; }
  static Vec3 select(bool m, const Vec3& a, const Vec3& b) { return m ? a : b; }
  static Vec3 zero() { return Vec3::Zero(); }
};

/// Removes the component of `v` along the unit normal `n` (projection onto the plane).
inline Vec3 inPlane(const Vec3& v, const Vec3& n) { return v - v.dot(n) * n; }

// ---------------------------------------------------------------------------------------
// The laws with their per-contact constants precomputed (the time-stepping hot path).
//
// E*, G*, R* and m* depend only on the material and on the two partners' radii and masses,
// so the solver computes the factors below once per pair, when it builds its neighbour
// list, instead of once per pair and step. The functions give the same physics as
// normalForce / normalStiffness / tangentialStiffness / tangentialForce above (they differ
// from them only in the rounding of the last bits).

/// Constants of one contact (PHYSICS.md section 1).
struct ContactConstants {
  /// Hertz: K = 4/3 E* sqrt(R*), N/m^(3/2) (F = K delta^(3/2)); linear: kn, N/m.
  double normalStiffness = 0.0;
  /// Hertz: c sqrt(m* K), N s/m^(5/4) (F_d = that x delta^(1/4) d(delta)/dt);
  /// linear: 2 zeta sqrt(m* kn), N s/m. 0 when undamped (e = 1, or two kinematic bodies).
  double normalDamping = 0.0;
  /// Hertz (Mindlin): 8 G* sqrt(R*), N/m^(3/2) (kt = that x sqrt(delta)); linear: kt, N/m.
  double tangentialStiffness = 0.0;
};

/// The constants of a contact with these effective properties.
ContactConstants contactConstants(const ContactModel& model, const PairProperties& pair);

/// The state of the normal spring of one contact at overlap delta > 0 (m).
struct NormalResponse {
  double elasticForce;        ///< N, Hertz K delta^(3/2) or linear kn delta
  double force;               ///< N, elastic + viscous, cut off at zero (no tension)
  double stiffness;           ///< N/m, dF_elastic/d(delta): Hertz 3/2 K sqrt(delta), linear kn
  double tangentialStiffness; ///< N/m, Mindlin 8 G* sqrt(R* delta), linear kt
};

/// Hertz-Mindlin normal response with Tsuji-type damping: F = K delta^(3/2) +
/// c sqrt(m* K) delta^(1/4) d(delta)/dt, cut off at zero; one square root of delta serves
/// the force, the damping and both stiffnesses. `approachSpeed` (m/s) > 0 approaching.
inline NormalResponse hertzMindlinResponse(const ContactConstants& c, double overlap,
                                           double approachSpeed)
{
  // Written once, in dem/ContactLawLanes.h (the CPU backend's SIMD pair kernel runs it too).
  const NormalResponseLanes<double> r = hertzMindlinResponseLanes(
    c.normalStiffness, c.normalDamping, c.tangentialStiffness, overlap, approachSpeed);
  return { r.elasticForce, r.force, r.stiffness, r.tangentialStiffness };
}

/// Linear spring-dashpot normal response: F = kn delta + 2 zeta sqrt(m* kn) d(delta)/dt,
/// cut off at zero; constant stiffnesses.
inline NormalResponse linearResponse(const ContactConstants& c, double overlap, double approachSpeed)
{
  const NormalResponseLanes<double> r = linearResponseLanes(
    c.normalStiffness, c.normalDamping, c.tangentialStiffness, overlap, approachSpeed);
  return { r.elasticForce, r.force, r.stiffness, r.tangentialStiffness };
}

/// The normal response of the model's law (overlap > 0).
inline NormalResponse normalResponse(ContactLaw law, const ContactConstants& c, double overlap,
                                     double approachSpeed)
{
  return law == ContactLaw::HertzMindlin ? hertzMindlinResponse(c, overlap, approachSpeed)
                                         : linearResponse(c, overlap, approachSpeed);
}

/// Rotates a stored in-plane vector (spring, shear force, bending moment) into the plane
/// normal to `n`, keeping its length: history follows the rotating contact plane.
inline Vec3 rotateIntoPlane(const Vec3& v, const Vec3& n)
{
  return rotateIntoPlaneLanes(v, n); // written once, in dem/ContactLawLanes.h
}

/// Incremental tangential spring (Mindlin / Coulomb) with a known stiffness kt (N/m) and
/// friction coefficient mu: the stored spring (m) is rotated into the current plane,
/// incremented by `slipIncrement` (m, in the plane) and capped so that |Ft| <= mu Fn.
/// Returns the tangential force on particle A, N: Ft = -kt * spring.
inline Vec3 mindlinCoulombForce(double kt, double friction, double normalForceMagnitude,
                                const Vec3& n, const Vec3& slipIncrement, Vec3& spring)
{
  return mindlinCoulombForceLanes(kt, friction, normalForceMagnitude, n, slipIncrement, spring);
}

/// Cundall local damping of one degree of freedom (PHYSICS.md s.1): F - alpha |F| sign(v),
/// with sign(0) = 0 (N or N m). Branch-free: the damping term takes the sign of v by
/// copysign, and vanishes at v = 0.
inline double cundallDamping(double force, double velocity, double alpha)
{
  const double damping = std::copysign(alpha * std::abs(force), velocity); // N
  return force - (velocity != 0.0 ? damping : 0.0);
}

/// Work (J) that Cundall damping takes from one particle in a step of dt (s): the damping
/// force (force - damped, N) on the velocity it acted on (m/s), plus the damping torque
/// (torque - dampedTorque, N m) on the spin (rad/s); >= 0, the damping opposing the motion.
/// The energy check's dissipation (Simulation::checkStability; GLSL twin in
/// contact_laws.glsl).
inline double cundallDampingWork(const Vec3& force, const Vec3& damped, const Vec3& velocity,
                                 const Vec3& torque, const Vec3& dampedTorque, const Vec3& spin, double dt)
{
  return ((force - damped).dot(velocity) + (torque - dampedTorque).dot(spin)) * dt;
}

/// Restitution delivered by one head-on collision of the given law with damping
/// coefficient `c` and the no-tension cut-off (dimensionless, speed independent for both
/// laws). Integrates the collision in dimensionless form with a fine RK4 step.
double restitutionForDamping(ContactLaw law, double c);
/// Inverse of restitutionForDamping: the damping coefficient that delivers `e` (0..1].
/// e = 0 has no finite coefficient; it is reported as an error by validation.
double dampingForRestitution(ContactLaw law, double e);

} // namespace dem
