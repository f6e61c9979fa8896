// The time of a stepping stage and the estimate of its length (dem/StageTime.h): frames
// are whole steps, a frame shorter than a step is refused, the steps a compression test
// takes to reach Max Strain, what counts as settled, and the measured stepping speed.
// References: the definitions in StageTime.h (the platen advances at Strain Rate x the
// starting length per second, so Max Strain is reached after Max Strain / Strain Rate s of
// model time; the test notices it at its next history sample) and PHYSICS.md section 4
// (equilibrium: unbalanced force ratio below 0.01).
#include "Specimens.h"

#include "dem/Errors.h"
#include "dem/LoadTest.h"
#include "dem/Simulation.h"
#include "dem/StageTime.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

using namespace dem;

TEST(StageTime, AFrameIsTheWholeNumberOfStepsNearestTheInterval)
{
  const double dt = 3.8e-7;
  EXPECT_EQ(stepsPerFrame(10 * dt, dt), 10);
  EXPECT_EQ(stepsPerFrame(1 * dt, dt), 1);
  EXPECT_EQ(stepsPerFrame(2.7 * dt, dt), 3);
  EXPECT_EQ(stepsPerFrame(2.4 * dt, dt), 2);
  // Written as n x timestep, even with rounding in the product, it is n.
  EXPECT_EQ(stepsPerFrame(0.002, 0.002 / 5263.0), 5263);
  // No particles, no timestep: one step per frame, never taken.
  EXPECT_EQ(stepsPerFrame(0.01, 0.0), 1);
}

TEST(StageTime, AFrameShorterThanOneStepIsRefusedNamingBoth)
{
  // Issue: Frame Interval 2.7e-7 s with a 3.8e-7 s timestep published 187 us while the
  // model advanced 264 us.
  try {
    stepsPerFrame(2.7e-7, 3.8e-7);
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("Frame Interval = 2.7e-07 s"), std::string::npos) << what;
    EXPECT_NE(what.find("3.8e-07 s"), std::string::npos) << what;
  }
  EXPECT_THROW(stepsPerFrame(0.0, 1e-6), InputError);
  EXPECT_THROW(stepsPerFrame(-1.0, 1e-6), InputError);
  EXPECT_THROW(stepsPerFrame(std::numeric_limits<double>::quiet_NaN(), 1e-6), InputError);
  EXPECT_THROW(stepsPerFrame(std::numeric_limits<double>::infinity(), 1e-6), InputError);
}

TEST(StageTime, ACompressionEndsAtTheFirstSampleAfterMaxStrain)
{
  Model m = dem::testing::specimen(60, 0.01, 0.0008, 0.0011);
  LoadTestSettings press;
  press.mode = TestMode::Compression;
  press.strainRate = 2.0;
  press.maxStrain = 0.004;
  press.sampleInterval = 100;
  startLoadTest(m, press);
  const double dt = 1e-5;
  // 0.004 / 2 = 2e-3 s of model time = 200 steps; samples at 100, 200: the end is step 200.
  TestEstimate e = estimateRemainingTestSteps(m, dt);
  EXPECT_TRUE(e.complete);
  EXPECT_EQ(e.steps, 200);
  // 201 steps to go: noticed at the sample of step 300.
  e = estimateRemainingTestSteps(m, 0.002 / 201.0);
  EXPECT_EQ(e.steps, 300);
  EXPECT_NE(e.summary.find("Max Strain 0.004"), std::string::npos) << e.summary;
}

TEST(StageTime, AConsolidationCannotBeEstimatedAheadAndATestWithoutShearIsNoTest)
{
  Model m = dem::testing::specimen(60, 0.01, 0.0008, 0.0011);
  LoadTestSettings iso;
  iso.mode = TestMode::Isotropic;
  startLoadTest(m, iso);
  TestEstimate e = estimateRemainingTestSteps(m, 1e-5);
  EXPECT_FALSE(e.complete);
  EXPECT_EQ(e.steps, 0);

  LoadTestSettings tri = iso;
  tri.mode = TestMode::Triaxial;
  tri.strainRate = 1.0;
  tri.maxStrain = 0.01;
  startLoadTest(m, tri);
  e = estimateRemainingTestSteps(m, 1e-5);
  EXPECT_FALSE(e.complete); // the consolidation comes first
  EXPECT_EQ(e.steps, 1000);  // then the shear: 0.01 s of model time

  LoadTestSettings off;
  startLoadTest(m, off);
  e = estimateRemainingTestSteps(m, 1e-5);
  EXPECT_TRUE(e.complete);
  EXPECT_EQ(e.steps, 0);
}

TEST(StageTime, SettledMeansTouchingAndInEquilibrium)
{
  Diagnostics d;
  d.contacts = 0;
  d.unbalancedForceRatio = 0.0;
  EXPECT_FALSE(isSettled(d)); // nothing touches: falling, not settled
  d.contacts = 10;
  d.unbalancedForceRatio = 0.5;
  EXPECT_FALSE(isSettled(d));
  d.unbalancedForceRatio = 0.009;
  EXPECT_TRUE(isSettled(d));
}

TEST(StageTime, TheThroughputIsMeasuredOnACopy)
{
  Model m = dem::testing::specimen(80, 0.01, 0.0008, 0.0011);
  const Model before = m;
  const double rate = measureThroughput(m, 0.02);
  EXPECT_GT(rate, 0.0);
  ASSERT_EQ(m.particles.size(), before.particles.size());
  for (std::size_t i = 0; i < m.particles.size(); ++i) {
    EXPECT_EQ(m.particles.position[i], before.particles.position[i]);
  }
  EXPECT_EQ(m.clock.step, before.clock.step);
  EXPECT_EQ(measureThroughput(Model(), 0.02), 0.0); // no particles
}
