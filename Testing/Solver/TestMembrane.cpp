// The flexible membrane around a cylindrical specimen (dem/Membrane.h, Confinement =
// Membrane in Triaxial and Isotropic tests): a carved cylinder consolidated isotropically
// holds the confining stress on its lateral surface and on both platens and keeps its
// shape; bad input is refused by name; a triaxial membrane test resumes exactly (the
// resume check is in TestStateFile.cpp). SI units.
#include "Specimens.h"
#include "StateFixtures.h"

#include "dem/Errors.h"
#include "dem/Membrane.h"
#include "dem/Specimen.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

using namespace dem;

namespace {

/// Expects `f` to throw InputError whose message contains every one of `parts`.
template <class F>
void expectInputError(F f, std::initializer_list<const char*> parts)
{
  try {
    f();
    FAIL() << "accepted, expected an InputError mentioning " << *parts.begin();
  } catch (const InputError& e) {
    for (const char* part : parts) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << "'" << part << "' in: " << e.what();
    }
  }
}

} // namespace

// Cheung and O'Sullivan (2008, Granular Matter 10) and the stress-controlled membranes of
// PFC3D / YADE triaxial examples: the membrane applies the confining pressure to the
// specimen's lateral surface. Checked: after isotropic consolidation the membrane force
// summed over the surface / lateral area, both platens, and the Love-Weber stress of the
// specimen (membrane pushes included at the grains' outer surfaces) equal the confining
// stress within 2 %, and the cylinder keeps its shape: its radius changes by under a quarter
// of a mean grain diameter and the spread of the surface grains' outer radii does not grow
// (both reported).
TEST(Membrane, IsotropicCylinderHoldsTheConfiningStressAndItsShape)
{
  Model m = statetest::membraneCylinder();
  const double p = 1e5; // Pa
  LoadTestSettings settings;
  settings.mode = TestMode::Isotropic;
  settings.confinement = Confinement::Membrane;
  settings.confiningStress = p;
  settings.sampleInterval = 100;
  startLoadTest(m, settings);
  const MembraneSurface start = membraneSurface(m);
  const double startRadius = start.radius;
  Simulation sim(m);
  for (int k = 0; k < 400 && m.test.stage != TestStage::Done; ++k) {
    sim.advance(100);
  }
  ASSERT_EQ(m.test.stage, TestStage::Done) << "the isotropic stage settles";
  const TestMeasurements t = sim.measurements();
  const MembraneSurface s = membraneSurface(m);
  std::printf("Membrane: %zu grains, %d x %d bins (%zu hold a grain), step %lld; radius %.5g m (start %.5g m), "
              "spread %.4g m = %.2f %% (start %.4g m; min %.5g, max %.5g m); lateral %.5g Pa, platens %.5g / %.5g Pa, "
              "Love-Weber xx %.5g yy %.5g zz %.5g Pa; net membrane force %.3g N of %.3g N\n",
              m.particles.size(), s.sectors, s.slices, s.surfaceGrains, static_cast<long long>(m.clock.step),
              s.radius, startRadius, s.radiusSpread, 100.0 * s.radiusSpread / s.radius, start.radiusSpread, s.minRadius, s.maxRadius,
              t.lateralStress, t.faceStress[4], t.faceStress[5], t.stressTensor[0], t.stressTensor[1],
              t.stressTensor[2], s.netForce.norm(), s.force);
  EXPECT_GE(s.surfaceGrains, static_cast<std::size_t>(0.98 * s.sectors * s.slices)) << "the bins hold grains";
  EXPECT_NEAR(t.lateralStress, p, 0.02 * p) << "membrane force / lateral area";
  EXPECT_NEAR(t.faceStress[4], p, 0.02 * p) << "low platen";
  EXPECT_NEAR(t.faceStress[5], p, 0.02 * p) << "high platen";
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(t.stressTensor[k], p, 0.02 * p) << "Love-Weber stress, component " << k;
  }
  EXPECT_FALSE(m.walls[0].active || m.walls[1].active || m.walls[2].active || m.walls[3].active)
    << "no side faces: the membrane confines";
  EXPECT_LT(s.netForce.norm(), 0.02 * s.force) << "the pushes balance around the axis";
  // The outer radii of a carved grain surface spread by about a third of a grain diameter
  // (the surface is as rough as its grains); consolidation must not roughen it.
  EXPECT_LT(s.radiusSpread, 1.1 * start.radiusSpread) << "the surface does not roughen";
  // The radius shrinks as the grains that stood proud of the carved surface are pushed into
  // its hollows and the pack compacts: by a fraction of a grain, not more.
  double meanDiameter = 0.0;
  for (double r : m.particles.radius) {
    meanDiameter += 2.0 * r / static_cast<double>(m.particles.size());
  }
  std::printf("radius change %.4g m = %.3f mean diameters (%.2f %%)\n", s.radius - startRadius,
              (s.radius - startRadius) / meanDiameter, 100.0 * (s.radius - startRadius) / startRadius);
  EXPECT_LT(std::abs(s.radius - startRadius), 0.25 * meanDiameter) << "the radius changes by under a quarter grain";
}

TEST(Membrane, BadInputIsRefusedByName)
{
  // A box specimen: its corners lie beyond the half width.
  {
    Model box = dem::testing::placedPack(Vec3(0.01, 0.01, 0.016), false, 300, 0.0005, 0.0006, 3);
    LoadTestSettings s;
    s.mode = TestMode::Triaxial;
    s.confinement = Confinement::Membrane;
    expectInputError([&] { startLoadTest(box, s); },
                     { "Confinement = Membrane needs a cylindrical specimen along Axis = Z", "half width",
                       "Shape = Cylinder", "Rigid Walls" });
    EXPECT_EQ(box.test.settings.mode, TestMode::Off) << "the model is left as it was";
  }
  // A cylinder along Z tested along X: not round across X.
  {
    Model cylinder = statetest::membraneCylinder();
    LoadTestSettings s;
    s.mode = TestMode::Isotropic;
    s.confinement = Confinement::Membrane;
    s.axis = 0;
    expectInputError([&] { startLoadTest(cylinder, s); }, { "along Axis = X", "not round across X" });
  }
  // A membrane in a mode without a confining stress.
  {
    LoadTestSettings s;
    s.mode = TestMode::Compression;
    s.confinement = Confinement::Membrane;
    expectInputError([&] { validate(s); },
                     { "Confinement = Membrane is out of range for Mode = Compression", "valid values here: Rigid Walls" });
  }
  // A 2D section.
  {
    Model section = dem::testing::placedPack(Vec3(0.01, 0.01, 0.001), true, 100, 0.0004, 0.0005, 4);
    LoadTestSettings s;
    s.mode = TestMode::Isotropic;
    s.confinement = Confinement::Membrane;
    expectInputError([&] { startLoadTest(section, s); }, { "Confinement = Membrane is out of range for a 2D section" });
  }
  // The GPU solver: refused, naming the CPU.
  {
    Model cylinder = statetest::membraneCylinder();
    LoadTestSettings s;
    s.mode = TestMode::Isotropic;
    s.confinement = Confinement::Membrane;
    startLoadTest(cylinder, s);
    expectInputError([&] { Simulation sim(cylinder, SolverDevice::GPU); },
                     { "Confinement = Membrane runs on the CPU backend only", "turn GPU Solver off" });
  }
}

// The membrane is found serially in slot order: a membrane triaxial test gives the same bits
// on one thread and on two (the pair and bond loops threaded from the first particle).
TEST(Membrane, SameBitsOnAnyNumberOfThreads)
{
  Model start = statetest::membraneCylinder();
  LoadTestSettings s;
  s.mode = TestMode::Triaxial;
  s.confinement = Confinement::Membrane;
  s.confiningStress = 1e5;
  s.strainRate = 0.5;
  startLoadTest(start, s);
  Model one = start;
  one.solver.threads = 1;
  Model two = start;
  two.solver.threads = 2;
  two.solver.parallelThreshold = 0;
  {
    Simulation a(one);
    a.advance(600);
    Simulation b(two);
    EXPECT_NE(b.path().find("OpenMP"), std::string::npos) << b.path();
    b.advance(600);
  }
  two.solver = one.solver; // the settings differ on purpose; the state must not
  EXPECT_EQ(statetest::firstDifference(one, two), "");
  EXPECT_NE(one.test.stage, TestStage::Idle);
}
