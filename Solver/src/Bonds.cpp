#include "dem/Bonds.h"
#include "dem/ContactLaws.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace dem {

void Bonds::clear()
{
  idA.clear();
  idB.clear();
  radius.clear();
  normalStiffness.clear();
  shearStiffness.clear();
  tensileStrength.clear();
  cohesion.clear();
  frictionAngle.clear();
  momentContribution.clear();
  softening.clear();
  normalForce.clear();
  shearForce.clear();
  twistingMoment.clear();
  bendingMoment.clear();
  damage.clear();
  failure.clear();
  failureTime.clear();
  failurePosition.clear();
  failureNormal.clear();
}

void Bonds::append(std::int64_t a, std::int64_t b, double bondRadius, double kn, double ks,
                   double sigmaC, double c, double phi, double beta, double softeningRatio)
{
  idA.push_back(a);
  idB.push_back(b);
  radius.push_back(bondRadius);
  normalStiffness.push_back(kn);
  shearStiffness.push_back(ks);
  tensileStrength.push_back(sigmaC);
  cohesion.push_back(c);
  frictionAngle.push_back(phi);
  momentContribution.push_back(beta);
  softening.push_back(softeningRatio);
  normalForce.push_back(0.0);
  shearForce.push_back(Vec3::Zero());
  twistingMoment.push_back(0.0);
  bendingMoment.push_back(Vec3::Zero());
  damage.push_back(0.0);
  failure.push_back(static_cast<std::uint8_t>(BondFailure::Intact));
  failureTime.push_back(0.0);
  failurePosition.push_back(Vec3::Zero());
  failureNormal.push_back(Vec3::Zero());
}

void Bonds::markBroken(std::size_t k, BondFailure how, double time, const Vec3& position,
                       const Vec3& normal)
{
  failure[k] = static_cast<std::uint8_t>(how);
  failureTime[k] = time;
  failurePosition[k] = position;
  failureNormal[k] = normal;
  normalForce[k] = 0.0;
  shearForce[k].setZero();
  twistingMoment[k] = 0.0;
  bendingMoment[k].setZero();
}

namespace {
/// The arrays stepping changes, listed once: each of `from`'s copied into `to`'s (from a
/// Bonds into a BondStepState, or back).
template <class From, class To> void copyStepState(const From& from, To& to)
{
  to.normalForce = from.normalForce;
  to.shearForce = from.shearForce;
  to.twistingMoment = from.twistingMoment;
  to.bendingMoment = from.bendingMoment;
  to.damage = from.damage;
  to.failure = from.failure;
  to.failureTime = from.failureTime;
  to.failurePosition = from.failurePosition;
  to.failureNormal = from.failureNormal;
}
} // namespace

void BondStepState::save(const Bonds& b)
{
  copyStepState(b, *this);
}

void BondStepState::restore(Bonds& b) const
{
  if (b.size() != failure.size()) {
    throw std::logic_error("BondStepState::restore: " + std::to_string(failure.size()) +
                           " bonds saved, " + std::to_string(b.size()) + " in the model");
  }
  copyStepState(*this, b);
}

BondCounts countBonds(const Bonds& bonds)
{
  BondCounts counts;
  counts.installed = bonds.size();
  for (std::uint8_t f : bonds.failure) {
    switch (static_cast<BondFailure>(f)) {
      case BondFailure::Intact:
        break;
      case BondFailure::Tension:
        ++counts.broken;
        ++counts.tension;
        break;
      case BondFailure::Shear:
        ++counts.broken;
        ++counts.shear;
        break;
      case BondFailure::Inherited:
        ++counts.broken;
        ++counts.inherited;
        break;
    }
  }
  return counts;
}

BondSection bondSection(double bondRadius, bool section2D, double slab)
{
  return bondSectionLanes(bondRadius, section2D, slab); // dem/BondLawLanes.h
}

BondStresses bondStresses(const BondSection& s, double bondRadius, double normalForce,
                          const Vec3& shearForce, double twistingMoment, const Vec3& bendingMoment,
                          double momentContribution)
{
  return bondStressesLanes<Vec3>(s, bondRadius, normalForce, shearForce, twistingMoment, bendingMoment,
                                 momentContribution);
}

namespace {
// Mohr-Coulomb: the shear strength grows with the compressive normal stress.
bool failsInShear(const BondStresses& stresses, double cohesion, double tanFriction)
{
  return failsInShearLanes(stresses, cohesion, tanFriction);
}

// The brittle law: tension first, then Mohr-Coulomb shear.
BondFailure brittleFailure(const BondStresses& stresses, double tensileStrength, double cohesion,
                           double tanFriction)
{
  if (failsInTensionLanes(stresses, tensileStrength)) {
    return BondFailure::Tension;
  }
  return failsInShear(stresses, cohesion, tanFriction) ? BondFailure::Shear : BondFailure::Intact;
}
} // namespace

BondFailure bondFailure(const BondStresses& stresses, double tensileStrength, double cohesion,
                        double frictionAngle)
{
  return brittleFailure(stresses, tensileStrength, cohesion, std::tan(frictionAngle));
}

double softeningDamage(double stressRatio, double softeningRatio)
{
  if (!(stressRatio > 1.0)) {
    return 0.0;
  }
  const double r = softeningRatio;
  if (stressRatio >= 1.0 + r) {
    return 1.0;
  }
  // (1 - D) x = (1 + r - x) / r: the applied stress on the line from (1, 1) to (1 + r, 0).
  return 1.0 - (1.0 + r - stressRatio) / (r * stressRatio);
}

BondFailure softenedBondFailure(const BondStresses& elastic, double tensileStrength, double cohesion,
                                double frictionAngle, double softeningRatio, double& damage)
{
  return softenedBondFailureWithTan(elastic, tensileStrength, cohesion, std::tan(frictionAngle),
                                    softeningRatio, damage);
}

BondFailure softenedBondFailureWithTan(const BondStresses& elastic, double tensileStrength, double cohesion,
                                       double tanFriction, double softeningRatio, double& damage)
{
  if (!(softeningRatio > 0.0)) {
    return brittleFailure(elastic, tensileStrength, cohesion, tanFriction);
  }
  const double ratio = elastic.sigmaMax / tensileStrength;
  if (ratio >= 1.0 + softeningRatio) {
    return BondFailure::Tension;
  }
  damage = std::max(damage, softeningDamage(ratio, softeningRatio));
  if (failsInShear(elastic, cohesion, tanFriction)) {
    return BondFailure::Shear;
  }
  return BondFailure::Intact;
}

} // namespace dem
