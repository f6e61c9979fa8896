// How fast to load (reference guide "How fast to load"; PHYSICS.md section 4;
// Documentation/Press.md): the stiffness does not depend on the strain rate below the
// Suggested Strain Rate, the specimen stays in equilibrium (unbalanced force ratio below
// 0.01) at that rate, and a cemented specimen is much weaker in tension than in
// compression.
//
// One cemented specimen (400 particles, bonds 2e7 Pa, tensile 0.2 MPa, cohesion 0.4 MPa,
// scatter 0.2, as in Press.UnconfinedCompressionOfCementedSpecimenFails) is built once
// and copied for every run; the compression run at the suggested rate is shared by the
// three tests. Timestep Safety 0.3 (instead of 0.1) keeps the file near a minute.
#include "dem/Cement.h"
#include "dem/LoadTest.h"
#include "dem/Pack.h"
#include "dem/Simulation.h"
#include "Specimens.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>

using namespace dem;
using namespace dem::testing;

namespace {

std::size_t column(const char* name)
{
  const auto& c = historyColumns();
  const auto it = std::find(c.begin(), c.end(), name);
  EXPECT_NE(it, c.end()) << name;
  return static_cast<std::size_t>(it - c.begin());
}

struct Specimen {
  Model model;
  double suggestedRate = 0.0; ///< 1/s, Simulation::measurements() at the consolidation stress
};

/// Grown pack, closed by an isotropic consolidation to 20 kPa, cemented, then unloaded
/// (Mode Off puts the walls back at the box) and left to relax, so that no stress is
/// locked in when the press starts.
const Specimen& cementedSpecimen()
{
  static const Specimen s = [] {
    Specimen out;
    Model& m = out.model;
    m = specimen(400, 0.016, 0.0008, 0.0012, 3);
    m.solver.timestepSafety = 0.3;
    out.suggestedRate = consolidate(m, 2e4);
    EXPECT_EQ(m.test.stage, TestStage::Done) << "consolidation settles";
    const std::size_t bonds = cement(m, testCement()).bonds;
    EXPECT_GT(bonds, 500u);
    LoadTestSettings off;
    off.mode = TestMode::Off;
    startLoadTest(m, off);
    {
      Simulation sim(m);
      sim.advance(5000);
      std::printf("[specimen] %zu bonds, suggested strain rate %.4g /s, unbalanced force ratio "
                  "after relaxing %.2g\n",
        bonds, out.suggestedRate, sim.diagnostics().unbalancedForceRatio);
    }
    return out;
  }();
  return s;
}

/// Runs a Compression or Tension test on a copy of the specimen until Max Strain, or
/// (stopAfterPeak) once the axial stress has fallen below 70 % of the peak.
Model runTest(TestMode mode, double rate, double maxStrain, bool stopAfterPeak)
{
  Model m = cementedSpecimen().model;
  LoadTestSettings s;
  s.mode = mode;
  s.strainRate = rate;
  s.maxStrain = maxStrain;
  s.sampleInterval = 250;
  startLoadTest(m, s);
  Simulation sim(m);
  const std::size_t axial = column("Axial Stress (Pa)");
  const double sign = mode == TestMode::Tension ? -1.0 : 1.0;
  while (m.test.stage != TestStage::Done) {
    sim.advance(2000);
    if (stopAfterPeak && !m.test.history.empty() &&
        sign * m.test.history.back()[axial] < 0.7 * m.test.peakStress) {
      break;
    }
  }
  return m;
}

/// The compression run at the suggested rate, to past the peak (shared by the tests).
const Model& compressionAtSuggestedRate()
{
  static const Model m = runTest(TestMode::Compression, cementedSpecimen().suggestedRate, 0.03, true);
  return m;
}

std::size_t peakRow(const Model& m, double sign = 1.0)
{
  const auto& h = m.test.history;
  const std::size_t a = column("Axial Stress (Pa)");
  std::size_t best = 0;
  for (std::size_t r = 0; r < h.size(); ++r) {
    if (sign * h[r][a] > sign * h[best][a]) {
      best = r;
    }
  }
  return best;
}

/// Axial strain (interpolated) where the axial stress first reaches `level`; < 0 if never.
double strainAtStress(const Model& m, double level)
{
  const auto& h = m.test.history;
  const std::size_t a = column("Axial Stress (Pa)");
  const std::size_t e = column("Strain Z");
  double prevStress = 0.0;
  double prevStrain = 0.0;
  for (const auto& row : h) {
    if (row[a] >= level) {
      const double t = (level - prevStress) / (row[a] - prevStress);
      return prevStrain + t * (row[e] - prevStrain);
    }
    prevStress = row[a];
    prevStrain = row[e];
  }
  return -1.0;
}

/// Young's modulus: secant slope of axial stress vs axial strain between 10 % and 40 %
/// of the reference peak.
double secantModulus(const Model& m, double peak)
{
  const double e10 = strainAtStress(m, 0.1 * peak);
  const double e40 = strainAtStress(m, 0.4 * peak);
  EXPECT_GE(e10, 0.0);
  EXPECT_GT(e40, e10);
  return 0.3 * peak / (e40 - e10);
}

} // namespace

// Reference: PHYSICS.md s.4 / guide "How fast to load" (below the Suggested Strain Rate the
// response is quasi-static). Bar: Young's modulus changes by less than 5 % when the rate
// is halved. The half-rate run stops at the strain where the suggested-rate run reached
// 60 % of its peak (not to failure, to save time).
TEST(PressRates, YoungsModulusIndependentOfStrainRateBelowSuggested)
{
  const double rate = cementedSpecimen().suggestedRate;
  const Model& fast = compressionAtSuggestedRate();
  const double peak = fast.test.peakStress;
  ASSERT_GT(peak, 0.0);
  const double stopStrain = strainAtStress(fast, 0.6 * peak);
  ASSERT_GT(stopStrain, 0.0);
  const Model slow = runTest(TestMode::Compression, 0.5 * rate, stopStrain, false);
  const double reached = slow.test.history[peakRow(slow)][column("Axial Stress (Pa)")];
  EXPECT_GT(reached, 0.45 * peak) << "the half-rate run reaches past 40 % of the peak";
  const double eFast = secantModulus(fast, peak);
  const double eSlow = secantModulus(slow, peak);
  const double change = std::abs(eSlow - eFast) / eFast;
  std::printf("[E] suggested rate %.4g /s: E = %.6g Pa; half rate: E = %.6g Pa; change %.3f %%; "
              "peak %.4g Pa at strain %.4g; half-rate run to strain %.4g reached %.0f %% of it\n",
    rate, eFast, eSlow, 100.0 * change, peak, fast.test.history[peakRow(fast)][column("Strain Z")],
    stopStrain, 100.0 * reached / peak);
  EXPECT_LT(change, 0.05);
}

// Reference: PHYSICS.md s.4 (equilibrium below an unbalanced force ratio of about 0.01).
// Bar: below 0.01 in every history row from the start of loading to the peak, at the
// Suggested Strain Rate.
TEST(PressRates, UnbalancedForceRatioBelowOnePercentAtSuggestedRate)
{
  const Model& m = compressionAtSuggestedRate();
  const auto& h = m.test.history;
  const std::size_t peak = peakRow(m);
  ASSERT_GT(peak, 10u) << "enough rows before the peak";
  const std::size_t ubf = column("Unbalanced Force Ratio");
  const std::size_t strain = column("Strain Z");
  double worst = 0.0;
  std::size_t worstRow = 0;
  for (std::size_t r = 0; r < peak; ++r) {
    EXPECT_LT(h[r][ubf], 0.01) << "row " << r << " at strain " << h[r][strain];
    if (h[r][ubf] > worst) {
      worst = h[r][ubf];
      worstRow = r;
    }
  }
  std::printf("[UBF] %zu rows before the peak (strain %.4g): max unbalanced force ratio %.3g in row "
              "%zu (strain %.4g)\n",
    peak, h[peak][strain], worst, worstRow, h[worstRow][strain]);
}

// Reference: PHYSICS.md s.3-4 (parallel-bond models: compressive over tensile strength
// about 7; Potyondy & Cundall 2004). Bar: ratio > 2.
TEST(PressRates, TensionPeakWellBelowCompressionPeak)
{
  const double rate = cementedSpecimen().suggestedRate;
  const double compression = compressionAtSuggestedRate().test.peakStress;
  const Model t = runTest(TestMode::Tension, rate, 0.012, true);
  const double tension = t.test.peakStress;
  ASSERT_GT(tension, 0.0) << "the specimen carries a pull";
  const auto& h = t.test.history;
  const std::size_t p = peakRow(t, -1.0);
  EXPECT_NEAR(-h[p][column("Axial Stress (Pa)")], tension, 1e-9 * tension) << "peak is the largest pull";
  std::printf("[tension] compression peak %.4g Pa, tension peak %.4g Pa (at strain %.4g), ratio %.3g; "
              "tension starts at axial stress %.4g Pa\n",
    compression, tension, -h[p][column("Strain Z")], compression / tension,
    h.front()[column("Axial Stress (Pa)")]);
  EXPECT_GT(compression / tension, 2.0);
}
