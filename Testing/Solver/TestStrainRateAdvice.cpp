// The Suggested Strain Rate known before a test runs (dem/StrainRateAdvice.h,
// Documentation/SpeedAccuracy.md): the peak stress estimated from the cement strengths and
// the Confining Stress, the strain rate giving the target inertial number there
// (I = strain rate x mean diameter x sqrt(density / mean stress); GDR MiDi 2004), its
// refinement from the measured peak, and its order on a cemented specimen whose UCS is
// measured (the unconfined test at the suggestion reaches an inertial number at its peak
// between 0.3 x and 1 x the target: the estimate errs on the slow side, by a bounded factor).
#include "Specimens.h"

#include "dem/Cement.h"
#include "dem/LoadTest.h"
#include "dem/Simulation.h"
#include "dem/StrainRateAdvice.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace dem;

namespace {

/// Two grains of radius r touching, bonded with bond radius r (area ratio 1), and a third
/// unbonded grain of the same size; density 2650 kg/m^3, grain friction 0.5.
Model bondedTrio(double r, double tensile, double cohesion)
{
  Model m;
  m.domain.size = Vec3(0.02, 0.02, 0.02);
  m.particles.append(Vec3(0.005, 0.01, 0.01), r, 1);
  m.particles.append(Vec3(0.005 + 2 * r, 0.01, 0.01), r, 2);
  m.particles.append(Vec3(0.015, 0.01, 0.01), r, 3);
  updateMassProperties(m);
  m.bonds.append(1, 2, r, 1e10, 4e9, tensile, cohesion, 0.5);
  m.material.friction = 0.5;
  return m;
}

/// The rate giving inertial number I (default: CementedTargetInertialNumber, 2.5e-5).
double expectedRate(double diameter, double meanStress, double inertial = 2.5e-5)
{
  return inertial / (diameter * std::sqrt(2650.0 / meanStress));
}

} // namespace

TEST(StrainRateAdvice, PeakStressFromTheCementStrengthsAndTheConfiningStress)
{
  const double r = 0.001;
  const Model m = bondedTrio(r, 1e6, 3e6);
  LoadTestSettings s;
  s.mode = TestMode::Compression;
  PeakStressEstimate e = estimatePeakStress(m, s);
  EXPECT_DOUBLE_EQ(e.axial, UcsPerBondStrength * 3e6); // max(Tensile, Cohesion) x area ratio 1
  EXPECT_DOUBLE_EQ(e.lateral, 0.0);
  EXPECT_DOUBLE_EQ(e.mean, e.axial / 3.0);
  EXPECT_NE(e.basis.find("Cohesion"), std::string::npos) << e.basis;
  const double mean = UcsPerBondStrength * 1e6;
  EXPECT_NEAR(suggestedStrainRate(m, s), expectedRate(2 * r, mean), 1e-12 * expectedRate(2 * r, mean));

  // Triaxial: sigma1 = UCS + Kp sigma3, Kp = (1 + sin phi) / (1 - sin phi), tan phi = 0.5.
  s.mode = TestMode::Triaxial;
  s.confiningStress = 2e6;
  const double sinPhi = std::sin(std::atan(0.5));
  const double kp = (1 + sinPhi) / (1 - sinPhi);
  e = estimatePeakStress(m, s);
  EXPECT_NEAR(kp, 2.618, 1e-3);
  const double ucs = UcsPerBondStrength * 3e6;
  EXPECT_NEAR(e.axial, ucs + kp * 2e6, 1e-6);
  EXPECT_NEAR(e.mean, (ucs + kp * 2e6 + 4e6) / 3.0, 1e-6);

  // Tension and Brazilian: the tensile strength; Isotropic: the Confining Stress.
  s.mode = TestMode::Tension;
  EXPECT_DOUBLE_EQ(estimatePeakStress(m, s).axial, 1e6);
  s.mode = TestMode::Isotropic;
  EXPECT_DOUBLE_EQ(estimatePeakStress(m, s).mean, 2e6);
  s.mode = TestMode::Off;
  EXPECT_EQ(suggestedStrainRate(m, s), 0.0);

  // Half the bond radius: a quarter of the bond area, a quarter of the strength scale
  // (mean Rb^2 / mean r^2 = (r/2)^2 / r^2).
  Model thin = bondedTrio(r, 1e6, 3e6);
  thin.bonds.radius[0] = 0.5 * r;
  s.mode = TestMode::Compression;
  EXPECT_DOUBLE_EQ(estimatePeakStress(thin, s).axial, UcsPerBondStrength * 0.75e6);
}

TEST(StrainRateAdvice, NoBondsUnconfinedHasNoEstimateAndFallsBackOnTheMeasuredStress)
{
  Model m = bondedTrio(0.001, 1e6, 3e6);
  m.bonds = Bonds{};
  LoadTestSettings s;
  s.mode = TestMode::Compression;
  m.test.settings = s;
  EXPECT_EQ(estimatePeakStress(m, s).axial, 0.0);
  EXPECT_EQ(suggestedStrainRate(m, s), 0.0);
  // Not cemented: the granular target, 1e-4.
  EXPECT_NEAR(suggestedStrainRate(m, 5e4), expectedRate(0.002, 5e4, 1e-4), 1e-9);
  // Triaxial without bonds: Kp x sigma3.
  s.mode = TestMode::Triaxial;
  s.confiningStress = 1e5;
  EXPECT_GT(suggestedStrainRate(m, s), expectedRate(0.002, 1e5, 1e-4));
  EXPECT_FALSE(estimatePeakStress(m, s).cemented);
}

TEST(StrainRateAdvice, RefinedFromTheMeasuredPeakOnceTheTestPassesTheEstimate)
{
  Model m = bondedTrio(0.001, 1e6, 3e6);
  LoadTestSettings s;
  s.mode = TestMode::Compression;
  m.test.settings = s;
  const double before = suggestedStrainRate(m, 0.0);
  EXPECT_NEAR(before, expectedRate(0.002, UcsPerBondStrength * 1e6), 1e-9);
  m.test.peakStress = 1e6; // below the estimate: no change
  EXPECT_EQ(suggestedStrainRate(m, 0.0), before);
  m.test.peakStress = 12e6; // the test went past the estimate: from the measured peak
  EXPECT_NEAR(suggestedStrainRate(m, 0.0), expectedRate(0.002, 4e6), 1e-9);
}

// The order on a real specimen: the unconfined test of a cemented 400-grain specimen at
// 4 x the suggestion made before it (4 x fewer steps than at the suggestion; the inertial
// number is proportional to the rate) reaches, at its measured peak, an inertial number
// within [0.3, 1.05] x 4 x the target (2.5e-5): the estimate is below the real peak (the
// rate errs slow) by less than a factor 11 in stress. Simulation::measurements() before the first step
// gives the same suggestion (what DEM Load Test publishes before Play), and afterwards the
// refined one (never lower).
TEST(StrainRateAdvice, RightOrderOnACementedSpecimen)
{
  Model m = dem::testing::specimen(400, 0.016, 0.0008, 0.0012, 3);
  m.solver.timestepSafety = 0.3;
  dem::testing::consolidate(m, 2e4);
  cement(m, dem::testing::testCement());
  LoadTestSettings s;
  s.mode = TestMode::Compression;
  s.maxStrain = 0.05;
  s.sampleInterval = 100;
  startLoadTest(m, s);
  const double suggested = suggestedStrainRate(m, s);
  ASSERT_GT(suggested, 0.0);
  const double multiple = 4.0;
  s.strainRate = multiple * suggested;
  startLoadTest(m, s);
  Simulation sim(m);
  EXPECT_DOUBLE_EQ(sim.measurements().suggestedStrainRate, suggested);
  double peakInertial = 0.0;
  double peak = 0.0;
  while (m.test.stage != TestStage::Done) {
    sim.advance(s.sampleInterval);
    const TestMeasurements me = sim.measurements();
    if (me.axialStress > peak) {
      peak = me.axialStress;
      peakInertial = me.inertialNumber;
    }
    if (peak > 0.0 && me.axialStress < 0.7 * peak) {
      break;
    }
  }
  std::printf("[order] suggested %.4g 1/s before the run (estimated UCS %.4g Pa); measured UCS %.4g Pa, "
              "inertial number at the peak %.3g; refined suggestion %.4g 1/s\n",
    suggested, estimatePeakStress(m, s).axial, peak, peakInertial, sim.measurements().suggestedStrainRate);
  EXPECT_GT(peak, 0.0);
  EXPECT_TRUE(estimatePeakStress(m, s).cemented);
  EXPECT_LE(peakInertial, 1.05 * multiple * CementedTargetInertialNumber);
  EXPECT_GE(peakInertial, 0.3 * multiple * CementedTargetInertialNumber);
  // Refined: never below the suggestion made before the run; from the measured peak once
  // it is above the estimate.
  const double refined = sim.measurements().suggestedStrainRate;
  EXPECT_GE(refined, suggested);
  if (m.test.peakStress > estimatePeakStress(m, s).axial) {
    EXPECT_NEAR(refined, strainRateForInertialNumber(m, m.test.peakStress / 3.0, CementedTargetInertialNumber),
                1e-9 * refined);
  }
}

// The advice in Output Messages (DEM Load Test): above FastRateFactor x the suggestion it
// names the rate, the multiple and what the atlas measured; none at or below it, and none
// when the suggestion is unknown.
TEST(StrainRateAdvice, AdviceAboveFourTimesTheSuggestionOnly)
{
  EXPECT_EQ(strainRateAdvice(4.0, 1.0), "");
  EXPECT_EQ(strainRateAdvice(0.01, 1.0), "");
  EXPECT_EQ(strainRateAdvice(10.0, 0.0), "");
  const std::string fast = strainRateAdvice(10.0, 1.0);
  EXPECT_NE(fast.find("Strain Rate 10 1/s is 10 x the Suggested Strain Rate 1 1/s"), std::string::npos) << fast;
  EXPECT_NE(fast.find("12.8 %"), std::string::npos) << fast;
  EXPECT_NE(fast.find("at most 4 1/s"), std::string::npos) << fast;
}

TEST(StrainRateAdvice, SlowAdviceBelowOneSixteenthOfTheSuggestionWithItsCostInSteps)
{
  // At 1/16 of the suggestion and above: nothing; unknown suggestion, timestep or strain: nothing.
  EXPECT_EQ(slowStrainRateAdvice(1.0 / 16.0, 1.0, 1e-8, 0.02), "");
  EXPECT_EQ(slowStrainRateAdvice(0.5, 1.0, 1e-8, 0.02), "");
  EXPECT_EQ(slowStrainRateAdvice(0.01, 0.0, 1e-8, 0.02), "");
  EXPECT_EQ(slowStrainRateAdvice(0.01, 1.0, 0.0, 0.02), "");
  EXPECT_EQ(slowStrainRateAdvice(0.01, 1.0, 1e-8, 0.0), "");
  // 1/100 of the suggestion: Max Strain 0.02 at 1e-8 s takes 0.02 / (0.01 x 1e-8) = 2e8 steps,
  // 100 x the 2e6 at the suggestion; the advised range is 1/16 to 4 x the suggestion.
  const std::string slow = slowStrainRateAdvice(0.01, 1.0, 1e-8, 0.02);
  EXPECT_NE(slow.find("Strain Rate 0.01 1/s is 1/100 of the Suggested Strain Rate 1 1/s"), std::string::npos) << slow;
  EXPECT_NE(slow.find("takes 2e+08 steps of 1e-08 s, 100 x the 2e+06 steps at the suggestion"), std::string::npos)
    << slow;
  EXPECT_NE(slow.find("Advised range of Strain Rate: 0.0625 to 4 1/s"), std::string::npos) << slow;
  // The fast advice stays silent there, and the slow one above the suggestion.
  EXPECT_EQ(strainRateAdvice(0.01, 1.0), "");
  EXPECT_EQ(slowStrainRateAdvice(10.0, 1.0, 1e-8, 0.02), "");
}

TEST(StrainRateAdvice, BondToContactStiffnessRatioIsBondModulusOverYoungsModulus)
{
  // DEM Cement: kn = Bond Modulus / (rA + rB); the trio's bond has kn 1e10 N/m^3 between two
  // grains of radius 1 mm: Bond Modulus 1e10 x 2e-3 = 2e7 Pa, over Young's Modulus 1e9 Pa.
  Model m = bondedTrio(0.001, 1e6, 1e6);
  m.material.youngsModulus = 1e9;
  EXPECT_NEAR(bondToContactStiffnessRatio(m), 0.02, 1e-12);
  m.bonds.failure[0] = static_cast<std::uint8_t>(BondFailure::Tension);
  EXPECT_EQ(bondToContactStiffnessRatio(m), 0.0); // no intact bond
}

TEST(StrainRateAdvice, TimestepSafetyAdviceWithinAFactorTwoOfTheMeasuredBoundary)
{
  // Cemented, ratio and damping inside what the stability map measured: unstable from 2, so
  // nothing up to the engine's cap of 1.
  EXPECT_EQ(timestepSafetyAdvice(1.0, 1.0, 0.7), "");
  EXPECT_EQ(timestepSafetyAdvice(1.0, 100.0, 0.9), "");
  // Without bonds, without damping, or outside the measured ratios: the sweep's boundary 1.0,
  // advice above 0.5.
  EXPECT_EQ(timestepSafetyAdvice(0.5, 0.0, 0.7), "");
  EXPECT_EQ(timestepSafetyAdvice(0.1, 1000.0, 0.0), "");
  const std::string grains = timestepSafetyAdvice(0.8, 0.0, 0.7);
  EXPECT_NE(grains.find("Timestep Safety 0.8 is within a factor 2 of the stability boundary"), std::string::npos)
    << grains;
  EXPECT_NE(grains.find("unstable from 1"), std::string::npos) << grains;
  EXPECT_NE(grains.find("Advised range of Timestep Safety: up to 0.5 (default 0.1)"), std::string::npos) << grains;
  const std::string undamped = timestepSafetyAdvice(0.7, 1.0, 0.0);
  EXPECT_NE(undamped.find("Bond Modulus / Young's Modulus 1, Settling Damping 0"), std::string::npos) << undamped;
  EXPECT_NE(undamped.find("up to 0.5"), std::string::npos) << undamped;
  EXPECT_NE(timestepSafetyAdvice(0.6, 1000.0, 0.7), "");
}
