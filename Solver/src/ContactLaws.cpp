#include "dem/ContactLaws.h"

#include "dem/Errors.h"

#include <cmath>
#include <limits>
#include <mutex>
#include <vector>

namespace dem {
namespace {

constexpr double Pi = 3.14159265358979323846;

/// Shear modulus G = E / (2 (1 + nu)), Pa.
double shearModulus(double youngsModulus, double poissonsRatio)
{
  return youngsModulus / (2.0 * (1.0 + poissonsRatio));
}

/// Linear-law normal stiffness kn = A E / L (PHYSICS.md section 3, "same method").
double linearStiffness(double youngsModulus, double contactRadius, double springLength,
                       bool section2D, double slab)
{
  const double area = section2D ? 2.0 * contactRadius * slab : Pi * contactRadius * contactRadius;
  return area * youngsModulus / springLength;
}

/// Mindlin ratio of tangential to normal stiffness for identical materials, 2(1-nu)/(2-nu).
double shearToNormalRatio(double poissonsRatio)
{
  return 2.0 * (1.0 - poissonsRatio) / (2.0 - poissonsRatio);
}

/// Dimensionless normal force of one collision (see restitutionForDamping).
double dimensionlessForce(ContactLaw law, double c, double x, double xdot)
{
  if (x <= 0.0) {
    return 0.0;
  }
  const double force = law == ContactLaw::HertzMindlin
    ? x * std::sqrt(x) + c * std::sqrt(std::sqrt(x)) * xdot
    : x + 2.0 * c * xdot;
  return force > 0.0 ? force : 0.0;
}

} // namespace

double restitutionForDamping(ContactLaw law, double c)
{
  // Head-on collision in dimensionless form (x = delta / delta0, t = t / (delta0 / v)):
  //   Hertz:  x'' = -(x^(3/2) + c x^(1/4) x')   (speed independent, see PHYSICS.md s.1)
  //   linear: x'' = -(x + 2 zeta x')
  // with the force cut off at zero; x(0) = 0, x'(0) = 1. Restitution e = -x'(end).
  const double h = 2.0e-4 / std::max(1.0, c);
  double x = 0.0;
  double v = 1.0;
  const double tEnd = 1.0e4;
  for (double t = 0.0; t < tEnd; t += h) {
    auto acc = [&](double xx, double vv) { return -dimensionlessForce(law, c, xx, vv); };
    const double k1x = v;
    const double k1v = acc(x, v);
    const double k2x = v + 0.5 * h * k1v;
    const double k2v = acc(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
    const double k3x = v + 0.5 * h * k2v;
    const double k3v = acc(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
    const double k4x = v + h * k3v;
    const double k4v = acc(x + h * k3x, v + h * k3v);
    const double xNext = x + h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
    const double vNext = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
    if (xNext <= 0.0 && t > 0.0) {
      return -vNext; // separated: no force acts once x <= 0, so the speed is final
    }
    x = xNext;
    v = vNext;
    if (v <= 0.0 && dimensionlessForce(law, c, x, v) == 0.0) {
      return -v; // force cut off while receding: the speed no longer changes
    }
    if (v >= 0.0 && x > 0.0 && t > 10.0 && dimensionlessForce(law, c, x, v) == 0.0) {
      return 0.0; // stuck (cannot happen for finite c; guards the loop)
    }
  }
  return -v;
}

namespace {
/// The damping coefficient whose collision rebounds with restitution e (0 < e < 1).
double solveDampingForRestitution(ContactLaw law, double e)
{
  // e(c) decreases monotonically from 1 at c = 0: bisect in log(c).
  double lo = 1.0e-8;
  double hi = 1.0;
  while (restitutionForDamping(law, hi) > e) {
    lo = hi;
    hi *= 4.0;
    if (hi > 1.0e4) {
      throw InputError("Restitution = " + formatValue(e) +
                       " is below what the contact law can deliver: use a larger value.");
    }
  }
  for (int iteration = 0; iteration < 60; ++iteration) {
    const double mid = std::sqrt(lo * hi);
    if (restitutionForDamping(law, mid) > e) {
      lo = mid;
    } else {
      hi = mid;
    }
    if (hi / lo < 1.0 + 1.0e-12) {
      break;
    }
  }
  return std::sqrt(lo * hi);
}

/// The last few (law, restitution) -> damping coefficients solved in this process: each
/// solve integrates about 60 collisions (about 20 ms), and every Simulation asks for it.
struct DampingCache {
  std::mutex mutex;
  struct Entry {
    ContactLaw law;
    double restitution;
    double damping;
  };
  std::vector<Entry> entries; // most recent last, at most kEntries
  static constexpr std::size_t kEntries = 8;
};
DampingCache& dampingCache()
{
  static DampingCache cache;
  return cache;
}
} // namespace

double dampingForRestitution(ContactLaw law, double e)
{
  if (!(e > 0.0 && e <= 1.0)) {
    throw InputError("Restitution = " + formatValue(e) +
                     " is out of range: valid range is (0, 1] (0 would need infinite damping).");
  }
  if (e == 1.0) {
    return 0.0;
  }
  DampingCache& cache = dampingCache();
  {
    std::lock_guard<std::mutex> lock(cache.mutex);
    for (const DampingCache::Entry& entry : cache.entries) {
      if (entry.law == law && entry.restitution == e) {
        return entry.damping; // the value the solve below gave, bit for bit
      }
    }
  }
  const double damping = solveDampingForRestitution(law, e); // may throw: nothing cached
  std::lock_guard<std::mutex> lock(cache.mutex);
  if (cache.entries.size() == DampingCache::kEntries) {
    cache.entries.erase(cache.entries.begin());
  }
  cache.entries.push_back({ law, e, damping });
  return damping;
}


ContactModel makeContactModel(const Material& material, ContactLaw law)
{
  ContactModel model;
  model.law = law;
  model.restitution = material.restitution;
  model.dampingCoefficient = dampingForRestitution(law, material.restitution);
  model.friction = material.friction;
  model.rollingFriction = material.rollingFriction;
  model.youngsModulus = material.youngsModulus;
  model.poissonsRatio = material.poissonsRatio;
  return model;
}

PairProperties pairProperties(const ContactModel& model, double radiusA, double massA,
                              double radiusB, double massB, bool section2D, double slab)
{
  const double nu = model.poissonsRatio;
  const double E = model.youngsModulus;
  PairProperties p;
  p.effectiveModulus = E / (2.0 * (1.0 - nu * nu));                 // 1/E* = sum (1-nu^2)/E
  p.effectiveShearModulus = shearModulus(E, nu) / (2.0 * (2.0 - nu)); // 1/G* = sum (2-nu)/G
  p.effectiveRadius = radiusA * radiusB / (radiusA + radiusB);
  // A fixed particle has infinite mass: m* is then the other particle's mass.
  if (std::isinf(massA)) {
    p.effectiveMass = massB;
  } else if (std::isinf(massB)) {
    p.effectiveMass = massA;
  } else {
    p.effectiveMass = massA * massB / (massA + massB);
  }
  p.linearNormalStiffness =
    linearStiffness(E, std::min(radiusA, radiusB), radiusA + radiusB, section2D, slab);
  p.linearShearStiffness = p.linearNormalStiffness * shearToNormalRatio(nu);
  return p;
}

PairProperties wallProperties(const ContactModel& model, double radius, double mass,
                              bool section2D, double slab)
{
  const double nu = model.poissonsRatio;
  const double E = model.youngsModulus;
  PairProperties p;
  p.effectiveModulus = E / (1.0 - nu * nu);
  p.effectiveShearModulus = shearModulus(E, nu) / (2.0 - nu);
  p.effectiveRadius = radius;
  p.effectiveMass = mass;
  // The spring spans the particle only (the wall is rigid): L = r.
  p.linearNormalStiffness = linearStiffness(E, radius, radius, section2D, slab);
  p.linearShearStiffness = p.linearNormalStiffness * shearToNormalRatio(nu);
  return p;
}

ContactConstants contactConstants(const ContactModel& model, const PairProperties& pair)
{
  ContactConstants c;
  // Two kinematic bodies (both of infinite mass) have no relative inertia to damp: their
  // contact is elastic only.
  const bool damped = std::isfinite(pair.effectiveMass) && model.dampingCoefficient > 0.0;
  if (model.law == ContactLaw::HertzMindlin) {
    const double rootRadius = std::sqrt(pair.effectiveRadius);
    c.normalStiffness = 4.0 / 3.0 * pair.effectiveModulus * rootRadius;
    c.normalDamping = damped ? model.dampingCoefficient * std::sqrt(pair.effectiveMass * c.normalStiffness) : 0.0;
    c.tangentialStiffness = 8.0 * pair.effectiveShearModulus * rootRadius;
  } else {
    c.normalStiffness = pair.linearNormalStiffness;
    c.normalDamping = damped
      ? 2.0 * model.dampingCoefficient * std::sqrt(pair.effectiveMass * pair.linearNormalStiffness)
      : 0.0;
    c.tangentialStiffness = pair.linearShearStiffness;
  }
  return c;
}

double hertzElasticForce(double effectiveModulus, double effectiveRadius, double overlap)
{
  return 4.0 / 3.0 * effectiveModulus * std::sqrt(effectiveRadius) * overlap * std::sqrt(overlap);
}

double normalForce(const ContactModel& model, const PairProperties& pair, double overlap,
                   double approachSpeed)
{
  if (overlap <= 0.0) {
    return 0.0;
  }
  // Two kinematic bodies (both of infinite mass) have no relative inertia to damp:
  // their contact is elastic only.
  const bool damped = std::isfinite(pair.effectiveMass) && model.dampingCoefficient > 0.0;
  double force = 0.0;
  if (model.law == ContactLaw::HertzMindlin) {
    const double K = 4.0 / 3.0 * pair.effectiveModulus * std::sqrt(pair.effectiveRadius);
    force = K * overlap * std::sqrt(overlap);
    if (damped) {
      force += model.dampingCoefficient * std::sqrt(pair.effectiveMass * K) *
        std::sqrt(std::sqrt(overlap)) * approachSpeed;
    }
  } else {
    const double kn = pair.linearNormalStiffness;
    force = kn * overlap;
    if (damped) {
      force += 2.0 * model.dampingCoefficient * std::sqrt(pair.effectiveMass * kn) * approachSpeed;
    }
  }
  return force > 0.0 ? force : 0.0; // no-tension cut-off
}

double normalStiffness(const ContactModel& model, const PairProperties& pair, double overlap)
{
  if (model.law == ContactLaw::HertzMindlin) {
    return 2.0 * pair.effectiveModulus * std::sqrt(pair.effectiveRadius * std::max(overlap, 0.0));
  }
  return pair.linearNormalStiffness;
}

double tangentialStiffness(const ContactModel& model, const PairProperties& pair, double overlap)
{
  if (model.law == ContactLaw::HertzMindlin) {
    return 8.0 * pair.effectiveShearModulus *
      std::sqrt(pair.effectiveRadius * std::max(overlap, 0.0));
  }
  return pair.linearShearStiffness;
}

Vec3 tangentialForce(const ContactModel& model, const PairProperties& pair, double overlap,
                     double normalForceMagnitude, const Vec3& n, const Vec3& slipIncrement,
                     Vec3& spring)
{
  spring = rotateIntoPlane(spring, n) + slipIncrement;
  const double kt = tangentialStiffness(model, pair, overlap);
  const double limit = model.friction * normalForceMagnitude; // Coulomb: |Ft| <= mu Fn
  const double trial = kt * spring.norm();
  if (trial > limit) {
    // Gross sliding: keep the spring at the length that carries exactly mu Fn.
    spring *= (kt > 0.0 && trial > 0.0) ? limit / trial : 0.0;
  }
  return -kt * spring;
}

Vec3 rollingTorque(const ContactModel& model, const PairProperties& pair, double overlap,
                   double normalForceMagnitude, const Vec3& n, const Vec3& rollIncrement,
                   Vec3& spring)
{
  if (model.rollingFriction <= 0.0) {
    spring.setZero();
    return Vec3::Zero();
  }
  const double R = pair.effectiveRadius;
  const double kr = 2.25 * normalStiffness(model, pair, overlap) * model.rollingFriction *
    model.rollingFriction * R * R;
  spring = rotateIntoPlane(spring, n) - kr * rollIncrement;
  const double limit = model.rollingFriction * R * normalForceMagnitude;
  const double magnitude = spring.norm();
  if (magnitude > limit) {
    spring *= magnitude > 0.0 ? limit / magnitude : 0.0;
  }
  return spring;
}

} // namespace dem
