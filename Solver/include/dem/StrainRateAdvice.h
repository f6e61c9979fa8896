// RockDEM engine: how fast a load test may load, known before the test runs.
//
// A test is quasi-static when the grains rearrange much faster than the platen moves:
// its inertial number I = strain rate x mean grain diameter x sqrt(density / mean stress)
// stays small (GDR MiDi 2004; reference guide "How fast to load"). The stress that
// matters is the one the test reaches at its peak, not the near-zero stress it starts
// from, so the Suggested Strain Rate is computed from an estimate of the peak stress made
// from the cement strengths, the confining stress and the grain friction before the test
// runs, and raised to the measured stress once the test has gone past the estimate.
// Documentation/SpeedAccuracy.md ("Suggested Strain Rate") gives the rule, the factors
// and the chart that checks it. The advice DEM Load Test prints in Output Messages where
// the settings are risky (a strain rate far above the suggestion, a Timestep Safety near
// the stability boundary of the atlas's stability map) or wasteful (a strain rate far
// below the suggestion) is computed here too. SI units: Pa, m, kg/m^3, 1/s.
#pragma once

#include <string>

namespace dem {

struct LoadTestSettings;
struct LoadTestState;
struct Model;

/// The inertial number the Suggested Strain Rate gives at the test's (estimated) peak on a
/// model without intact bonds, and in an isotropic consolidation: well inside the
/// quasi-static regime of granular flow (I < 1e-3, GDR MiDi 2004).
constexpr double TargetInertialNumber = 1e-4;
/// The same on a cemented model (intact bonds; not Isotropic): 4 x smaller. At 1e-4 the
/// atlas measured the UCS of a cemented rock 5.0 % above that of a 4 x slower test, at
/// 2.5e-5 within 1 % of the converged value (Documentation/SpeedAccuracy.md, "Strain rate").
constexpr double CementedTargetInertialNumber = 2.5e-5;

/// The unconfined compressive strength of a cemented model estimated from its bonds, as a
/// multiple of the bond strength scale S = max(mean Tensile Strength, mean Cohesion) x
/// (mean bond radius^2 / mean grain radius^2). Measured: 2.2-3.2 S on the stiff-bond rocks
/// of Documentation/Rock.md (E 1e10 Pa), 0.41 S on the soft test specimen of
/// StrainRateAdvice.RightOrderOnACementedSpecimen (bonds 2e7 Pa). 0.35 keeps the estimate
/// below every measured peak, so the suggested rate errs on the slow side (the rate goes
/// with the square root of the stress: by up to sqrt(3.2 / 0.35) = 3 on stiff rock).
constexpr double UcsPerBondStrength = 0.35;

/// The stress a test is expected to reach at its peak (Pa, compression positive).
struct PeakStressEstimate {
  double axial = 0.0;   ///< Pa, the axial stress at the peak (tension: the pull)
  double lateral = 0.0; ///< Pa, the lateral stress then (the Confining Stress, or 0)
  double mean = 0.0;    ///< Pa, the mean stress then: (axial + 2 lateral) / 3, a 2D section (axial + lateral) / 2
  /// Whether the estimate rests on intact bonds (then the suggestion uses
  /// CementedTargetInertialNumber; Isotropic never does).
  bool cemented = false;
  std::string basis;    ///< one line: what the estimate rests on ("" when there is none)
};

/// Estimates the peak of the test `settings` would run on `model` from its intact bonds
/// (UcsPerBondStrength x the bond strength scale; tension and Brazilian: the mean Tensile
/// Strength x the area ratio), the Confining Stress (Triaxial: sigma1 = UCS + Kp sigma3,
/// Kp = (1 + sin phi) / (1 - sin phi), tan phi the grain friction; Isotropic: the
/// Confining Stress itself). All zero for Mode Off, and for an unconfined test on a model
/// without bonds (its strength cannot be known ahead).
PeakStressEstimate estimatePeakStress(const Model& model, const LoadTestSettings& settings);

/// The strain rate (1/s) giving TargetInertialNumber at the mean stress `meanStress`
/// (Pa) on this model's grains: I / (mean diameter x sqrt(density / meanStress)). 0 when
/// meanStress or the model's grain size is not positive.
double strainRateForInertialNumber(const Model& model, double meanStress, double inertialNumber = TargetInertialNumber);

/// The Suggested Strain Rate (1/s) of the model's test, at CementedTargetInertialNumber
/// when the estimate is cemented, else TargetInertialNumber: from the estimated peak mean
/// stress (estimatePeakStress of model.test.settings), raised to the mean stress at the
/// largest axial stress the test has reached (model.test.peakStress; not for Isotropic,
/// whose reference is the Confining Stress). Without an estimate (an unconfined test on a
/// model without bonds) from the measured mean stress `measuredMeanStress` (Pa, its
/// magnitude is used). 0 for Mode Off and when no stress is known.
double suggestedStrainRate(const Model& model, double measuredMeanStress = 0.0);

/// The same for a test that has not started yet: the estimate for `settings` on `model`.
double suggestedStrainRate(const Model& model, const LoadTestSettings& settings);

/// Above this multiple of the Suggested Strain Rate a test is risky: the atlas measured the
/// UCS too high there (Documentation/SpeedAccuracy.md, "Strain rate").
constexpr double FastRateFactor = 4.0;
/// Below this multiple of the Suggested Strain Rate a test is wasteful: it takes more than
/// 16 x the steps of the suggestion, at an inertial number 16 x below the target. The atlas
/// measured the UCS still falling at 0.25 x the suggestion (6.7 % below it), so a test
/// between 1/16 and 1 x is not wasted; below 1/16 nothing was measured, and the cost grows
/// as 1 / rate (Documentation/SpeedAccuracy.md, "Advice in Output Messages").
constexpr double SlowRateFactor = 1.0 / 16.0;

/// One line of advice for a test run at `strainRate` (1/s) when the suggestion is
/// `suggested` (1/s): "" when suggested is 0 (unknown) or the rate is at most
/// FastRateFactor x suggested; else what the atlas measured at such a rate and what to
/// change.
std::string strainRateAdvice(double strainRate, double suggested);

/// One line of advice for a test run at `strainRate` (1/s) below SlowRateFactor x the
/// Suggested Strain Rate `suggested` (1/s), "" otherwise (or when either is not positive):
/// the steps it takes to reach `strain` (the Max Strain) at `timestep` (s), against those at
/// the suggestion, and the advised range of Strain Rate (SlowRateFactor to FastRateFactor x
/// the suggestion). "" when timestep or strain is not positive.
std::string slowStrainRateAdvice(double strainRate, double suggested, double timestep, double strain);

/// Bond Modulus / Young's Modulus of the model: the mean over its intact bonds of the
/// bond's normal stiffness x (rA + rB) (DEM Cement: kn = Bond Modulus / (rA + rB)) over the
/// grains' Young's Modulus. 0 without intact bonds.
double bondToContactStiffnessRatio(const Model& model);

/// The stability boundaries the atlas measured (Documentation/SpeedAccuracy.md, "Stability
/// map"): the smallest Timestep Safety (x the engine's critical timestep) at which a run went
/// unstable. Cemented specimens with Bond Modulus / Young's Modulus 0.1 to 100 under Settling
/// Damping 0.7 stayed stable to 1.5 and broke their bonds to the instability from 2.
constexpr double CementedUnstableTimestepSafety = 2.0;
/// Bond Modulus / Young's Modulus range the map measured.
constexpr double MeasuredBondToContactMin = 0.1;
constexpr double MeasuredBondToContactMax = 100.0;
/// Grains without bonds, and any model without Settling Damping (the Timestep Safety sweep
/// of Documentation/Benchmarks-Solver.md section 3, undamped impacts and an undamped elastic
/// system: unstable at 1.0), and a cemented model outside the measured ratio range.
constexpr double SweepUnstableTimestepSafety = 1.0;
/// The Settling Damping of the cemented map; below it the undamped boundary applies.
constexpr double MeasuredSettlingDamping = 0.7;

/// One line of advice when Timestep Safety `safety` is within a factor 2 of the measured
/// stability boundary for a model with Bond Modulus / Young's Modulus `bondToContact` (0: no
/// intact bonds) under Settling Damping `settlingDamping`: the boundary, what it rests on, and
/// the advised range (at most half the boundary). "" otherwise.
std::string timestepSafetyAdvice(double safety, double bondToContact, double settlingDamping);

} // namespace dem
