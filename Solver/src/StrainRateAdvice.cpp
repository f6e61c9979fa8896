// RockDEM engine: the Suggested Strain Rate from the estimated peak stress
// (dem/StrainRateAdvice.h, Documentation/SpeedAccuracy.md).
#include "dem/StrainRateAdvice.h"

#include "dem/Fractures.h"
#include "dem/LoadTest.h"
#include "dem/Model.h"

#include "SlotLookup.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace dem {

namespace {

/// Means over the intact bonds, and the bond-to-grain area ratio.
struct BondStrengths {
  std::size_t intact = 0;
  double tensile = 0.0;   ///< Pa
  double cohesion = 0.0;  ///< Pa
  double areaRatio = 0.0; ///< mean Rb^2 / mean r^2, at most 1
};

BondStrengths bondStrengths(const Model& model)
{
  BondStrengths s;
  const Bonds& b = model.bonds;
  double rb2 = 0.0;
  for (std::size_t k = 0; k < b.size(); ++k) {
    if (b.broken(k)) {
      continue;
    }
    ++s.intact;
    s.tensile += b.tensileStrength[k];
    s.cohesion += b.cohesion[k];
    rb2 += b.radius[k] * b.radius[k];
  }
  if (s.intact == 0) {
    return s;
  }
  const double n = static_cast<double>(s.intact);
  s.tensile /= n;
  s.cohesion /= n;
  rb2 /= n;
  double r2 = 0.0;
  for (double r : model.particles.radius) {
    r2 += r * r;
  }
  r2 = model.particles.empty() ? 0.0 : r2 / static_cast<double>(model.particles.size());
  s.areaRatio = r2 > 0.0 ? std::min(1.0, rb2 / r2) : 0.0;
  return s;
}

/// What the atlas measured (Documentation/SpeedAccuracy.md, "Strain rate"), quoted in the advice.
constexpr const char* FastRateAdviceMeasured =
  "on a cemented 200-grain rock the atlas measured the UCS 5.0 % above the UCS at the suggestion at 4 x it, "
  "12.8 % above at 16 x and 19.5 % above at 64 x";

std::string fmt(double v)
{
  std::ostringstream o;
  o.precision(3);
  o << v;
  return o.str();
}

} // namespace

PeakStressEstimate estimatePeakStress(const Model& model, const LoadTestSettings& settings)
{
  PeakStressEstimate e;
  const bool planar = model.domain.section2D;
  const BondStrengths b = bondStrengths(model);
  const double scale = std::max(b.tensile, b.cohesion) * b.areaRatio; // Pa
  const double ucs = UcsPerBondStrength * scale;
  const double phi = std::atan(std::max(0.0, model.material.friction));
  const double kp = (1.0 + std::sin(phi)) / (1.0 - std::sin(phi));
  std::string cement;
  if (b.intact > 0) {
    cement = "UCS ~ " + fmt(UcsPerBondStrength) + " x max(Tensile Strength " + fmt(b.tensile) +
      " Pa, Cohesion " + fmt(b.cohesion) + " Pa) x bond/grain area " + fmt(b.areaRatio) + " = " + fmt(ucs) + " Pa";
  }
  switch (settings.mode) {
    case TestMode::Compression:
      if (b.intact > 0) {
        e.axial = ucs;
        e.basis = cement;
      }
      break;
    case TestMode::Triaxial:
      e.lateral = settings.confiningStress;
      e.axial = ucs + kp * settings.confiningStress;
      e.basis = (b.intact > 0 ? cement + " plus " : std::string("no bonds: ")) + "Kp " + fmt(kp) +
        " (grain friction " + fmt(model.material.friction) + ") x Confining Stress " + fmt(settings.confiningStress) + " Pa";
      break;
    case TestMode::Isotropic:
      e.axial = settings.confiningStress;
      e.lateral = settings.confiningStress;
      e.basis = "the Confining Stress";
      break;
    case TestMode::Tension:
    case TestMode::Brazilian:
      if (b.intact > 0) {
        e.axial = b.tensile * b.areaRatio;
        e.basis = "the mean Tensile Strength " + fmt(b.tensile) + " Pa x bond/grain area " + fmt(b.areaRatio);
      }
      break;
    case TestMode::Off:
      break;
  }
  e.mean = planar ? 0.5 * (e.axial + e.lateral) : (e.axial + 2.0 * e.lateral) / 3.0;
  e.cemented = b.intact > 0 && settings.mode != TestMode::Isotropic && settings.mode != TestMode::Off;
  if (settings.mode == TestMode::Isotropic) {
    e.mean = settings.confiningStress;
  }
  return e;
}

double strainRateForInertialNumber(const Model& model, double meanStress, double inertialNumber)
{
  const double diameter = meanParticleDiameter(model);
  const double rho = model.material.density;
  if (!(meanStress > 0.0) || !(diameter > 0.0) || !(rho > 0.0)) {
    return 0.0;
  }
  return inertialNumber / (diameter * std::sqrt(rho / meanStress));
}

double suggestedStrainRate(const Model& model, double measuredMeanStress)
{
  const LoadTestState& t = model.test;
  const LoadTestSettings& s = t.settings;
  if (s.mode == TestMode::Off) {
    return 0.0;
  }
  const PeakStressEstimate e = estimatePeakStress(model, s);
  // Without an estimate (an unconfined test on a model without bonds) the measured mean
  // stress is all there is.
  double reference = e.mean > 0.0 ? e.mean : std::abs(measuredMeanStress);
  // The largest axial stress reached so far, as a mean stress (with the lateral stress of
  // the estimate: the Confining Stress, or 0 when unconfined).
  const double peak = std::abs(t.peakStress);
  if (peak > 0.0 && s.mode != TestMode::Isotropic) {
    const double mean = model.domain.section2D ? 0.5 * (peak + e.lateral) : (peak + 2.0 * e.lateral) / 3.0;
    reference = std::max(reference, mean);
  }
  return strainRateForInertialNumber(model, reference, e.cemented ? CementedTargetInertialNumber : TargetInertialNumber);
}

double suggestedStrainRate(const Model& model, const LoadTestSettings& settings)
{
  const PeakStressEstimate e = estimatePeakStress(model, settings);
  return strainRateForInertialNumber(model, e.mean, e.cemented ? CementedTargetInertialNumber : TargetInertialNumber);
}

std::string strainRateAdvice(double strainRate, double suggested)
{
  if (!(suggested > 0.0) || !(strainRate > 0.0)) {
    return "";
  }
  const double ratio = strainRate / suggested;
  if (ratio > FastRateFactor) {
    return "Strain Rate " + fmt(strainRate) + " 1/s is " + fmt(ratio) + " x the Suggested Strain Rate " +
      fmt(suggested) + " 1/s: the test is not quasi-static, and its peak stress comes out too high (" +
      std::string(FastRateAdviceMeasured) + "; Documentation/SpeedAccuracy.md). Use at most " +
      fmt(FastRateFactor * suggested) + " 1/s for a strength.";
  }
  return "";
}

double bondToContactStiffnessRatio(const Model& model)
{
  const Bonds& b = model.bonds;
  const Particles& p = model.particles;
  if (!(model.material.youngsModulus > 0.0)) {
    return 0.0;
  }
  const SlotLookup slots(p);
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t k = 0; k < b.size(); ++k) {
    const long i = slots.find(b.idA[k]);
    const long j = slots.find(b.idB[k]);
    if (b.broken(k) || i < 0 || j < 0) {
      continue;
    }
    sum += b.normalStiffness[k] * (p.radius[static_cast<std::size_t>(i)] + p.radius[static_cast<std::size_t>(j)]);
    ++n;
  }
  return n ? sum / static_cast<double>(n) / model.material.youngsModulus : 0.0;
}

std::string timestepSafetyAdvice(double safety, double bondToContact, double settlingDamping)
{
  const bool measured = bondToContact >= MeasuredBondToContactMin && bondToContact <= MeasuredBondToContactMax &&
    settlingDamping >= MeasuredSettlingDamping;
  const double boundary = measured ? CementedUnstableTimestepSafety : SweepUnstableTimestepSafety;
  if (!(safety > 0.5 * boundary)) {
    return "";
  }
  std::string basis;
  if (measured) {
    basis = "the atlas's stability map measured cemented specimens (Bond Modulus / Young's Modulus " +
      fmt(MeasuredBondToContactMin) + " to " + fmt(MeasuredBondToContactMax) + ", Settling Damping " +
      fmt(MeasuredSettlingDamping) + ") stable to 1.5 x the critical timestep and unstable from " + fmt(boundary) +
      " x";
  } else {
    basis = std::string(bondToContact > 0.0 ? "this model (Bond Modulus / Young's Modulus " + fmt(bondToContact) +
                                                ", Settling Damping " + fmt(settlingDamping) + ") is outside what the "
                                                "stability map measured, so the boundary of"
                                            : "for grains without bonds") +
      " the Timestep Safety sweep applies: impacts and a settling pack unstable from " + fmt(boundary) +
      " x the critical timestep, impact errors of 5-18 % at 0.7 x";
  }
  return "Timestep Safety " + fmt(safety) + " is within a factor 2 of the stability boundary (" + basis +
    "; Documentation/SpeedAccuracy.md, \"Stability map\", and Benchmarks-Solver.md section 3). Advised range of Timestep "
    "Safety: up to " + fmt(0.5 * boundary) + " (default 0.1).";
}

std::string slowStrainRateAdvice(double strainRate, double suggested, double timestep, double strain)
{
  if (!(suggested > 0.0) || !(strainRate > 0.0) || !(timestep > 0.0) || !(strain > 0.0)) {
    return "";
  }
  const double ratio = strainRate / suggested;
  if (ratio >= SlowRateFactor) {
    return "";
  }
  const double steps = strain / (strainRate * timestep);
  const double stepsAtSuggestion = strain / (suggested * timestep);
  return "Strain Rate " + fmt(strainRate) + " 1/s is 1/" + fmt(1.0 / ratio) + " of the Suggested Strain Rate " +
    fmt(suggested) + " 1/s: reaching Max Strain " + fmt(strain) + " takes " + fmt(steps) + " steps of " +
    fmt(timestep) + " s, " + fmt(1.0 / ratio) + " x the " + fmt(stepsAtSuggestion) +
    " steps at the suggestion, for a test already quasi-static there (the atlas measured the UCS 6.7 % lower at "
    "1/4 of the suggestion, nothing slower than 1/16; Documentation/SpeedAccuracy.md). Advised range of Strain Rate: " +
    fmt(SlowRateFactor * suggested) + " to " + fmt(FastRateFactor * suggested) + " 1/s.";
}

} // namespace dem
