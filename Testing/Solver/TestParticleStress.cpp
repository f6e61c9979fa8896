// Per-particle stress (Love-Weber average over each particle's volume; PHYSICS.md
// section 4, dem/ParticleStress.h): a sphere squeezed between two platens carries the
// analytic stress (Hertz force, PHYSICS.md section 1); the volume-weighted sum of the
// particle stresses is the specimen's Love-Weber tensor the press reports
// (Simulation::measurements), mid-test with contacts, bonds (some broken) and walls; the
// stresses of a model are a function of its state: a saved-and-reloaded model gives the
// same values bit for bit, and a running solver gives them without building a second one
// (Simulation::freshInteractionForces) and steps on as if it had not been asked.
#include "dem/Cement.h"
#include "dem/LoadTest.h"
#include "dem/Overlaps.h"
#include "dem/Pack.h"
#include "dem/Random.h"
#include "dem/ParticleStress.h"
#include "dem/Simulation.h"
#include "dem/StateFile.h"
#include "Specimens.h"
#include "StateFixtures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

using namespace dem;
using namespace dem::testing;

namespace {

constexpr double Pi = 3.14159265358979323846;

/// sum_p V_p sigma_p (Pa m^3).
StressTensor volumeWeightedSum(const Model& m, const std::vector<StressTensor>& s)
{
  StressTensor sum{ { 0, 0, 0, 0, 0, 0 } };
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double v = particleVolume(m.domain, m.particles.radius[i]);
    for (int q = 0; q < 6; ++q) {
      sum[q] += v * s[i][q];
    }
  }
  return sum;
}

/// Specimen volume between the six active walls (m^3), as the press measures it.
double volumeBetweenWalls(const Model& m)
{
  double v = 1.0;
  for (int k = 0; k < 3; ++k) {
    EXPECT_TRUE(m.walls[2 * k].active && m.walls[2 * k + 1].active);
    v *= m.walls[2 * k + 1].position - m.walls[2 * k].position;
  }
  return v;
}

/// A cemented specimen in a triaxial test, sheared until some bonds have broken.
Model shearedSpecimen()
{
  Model m = specimen(400, 0.012, 0.0006, 0.0009, 5);
  consolidate(m, 2e4);
  CementParameters c = testCement();
  c.tensileStrength = 5e4; // weak: bonds break early in the shear
  c.cohesion = 1e5;
  cement(m, c);
  LoadTestSettings s;
  s.mode = TestMode::Triaxial;
  s.confiningStress = 2e4;
  s.strainRate = 2.0;
  s.maxStrain = 0.05;
  s.sampleInterval = 100;
  startLoadTest(m, s);
  Simulation sim(m);
  for (int k = 0; k < 200 && (m.test.stage != TestStage::Shear || countBonds(m.bonds).broken < 5); ++k) {
    sim.advance(200);
  }
  sim.advance(300);
  return m;
}

} // namespace

// A sphere of radius R pressed between two platens (overlap d at each) carries the
// force F = 4/3 E* sqrt(R) d^1.5 (Hertz against a rigid wall, E* = E / (1 - nu^2)) at
// two contacts whose arms are R - d: sigma_zz = 2 (R - d) F / (4/3 pi R^3), every other
// component 0; mean stress sigma_zz / 3, von Mises sigma_zz.
TEST(ParticleStress, SphereBetweenTwoPlatensCarriesTheAnalyticStress)
{
  Model m;
  const double R = 0.002;
  const double d = 2e-5;
  m.domain.size = Vec3(0.01, 0.01, 2.0 * (R - d));
  m.gravity.setZero();
  m.material.youngsModulus = 1e8;
  m.material.poissonsRatio = 0.25;
  m.particles.append(Vec3(0.005, 0.005, R - d), R, 0);
  m.nextId = 1;
  updateMassProperties(m);
  const std::vector<StressTensor> s = particleStresses(m);
  ASSERT_EQ(s.size(), 1u);
  const double Estar = m.material.youngsModulus / (1.0 - 0.25 * 0.25);
  const double F = 4.0 / 3.0 * Estar * std::sqrt(R) * std::pow(d, 1.5);
  const double szz = 2.0 * (R - d) * F / (4.0 / 3.0 * Pi * R * R * R);
  EXPECT_NEAR(s[0][2], szz, 1e-12 * szz) << "sigma_zz, Pa";
  for (int q : { 0, 1, 3, 4, 5 }) {
    EXPECT_NEAR(s[0][q], 0.0, 1e-12 * szz) << "component " << q;
  }
  EXPECT_NEAR(meanStress(s[0], false), szz / 3.0, 1e-12 * szz);
  EXPECT_NEAR(vonMisesStress(s[0], false), szz, 1e-12 * szz);
}

// Triaxial mid-shear, bonds intact and broken, six walls: sum_p V_p sigma_p = V sigma
// (V the volume between the walls, sigma Simulation::measurements' Love-Weber tensor), for
// the live run and for the model state alone.
TEST(ParticleStress, VolumeWeightedSumIsTheSpecimenTensor)
{
  Model m = shearedSpecimen();
  const BondCounts bonds = countBonds(m.bonds);
  ASSERT_GT(bonds.broken, 0u) << "some bonds broke";
  ASSERT_GT(bonds.broken, 0u);
  ASSERT_LT(bonds.broken, bonds.installed);
  ASSERT_EQ(m.test.stage, TestStage::Shear);

  Simulation live(m);
  live.advance(7);
  const double V = volumeBetweenWalls(m);
  const StressTensor specimen = live.measurements().stressTensor;
  const StressTensor sum = volumeWeightedSum(m, particleStresses(m, live.interactionForces()));
  const double scale = std::abs(specimen[2]);
  ASSERT_GT(scale, 1e3) << "the specimen is loaded";
  for (int q = 0; q < 6; ++q) {
    EXPECT_NEAR(sum[q] / V, specimen[q], 1e-10 * scale) << "component " << q << " (live run)";
  }

  // The model state alone (the path of a model in a filter): the same identity against a
  // Simulation built on it.
  const std::vector<StressTensor> fromModel = particleStresses(m);
  Model copy = m;
  const Simulation rebuilt(copy);
  const StressTensor specimen2 = rebuilt.measurements().stressTensor;
  const StressTensor sum2 = volumeWeightedSum(m, fromModel);
  for (int q = 0; q < 6; ++q) {
    EXPECT_NEAR(sum2[q] / V, specimen2[q], 1e-10 * scale) << "component " << q << " (model state)";
  }
  // The two evaluations differ only in the viscous part of the contact forces (the live
  // one used the half-step velocities): in a quasi-static test by about 1e-8 of the stress.
  for (int q = 0; q < 6; ++q) {
    EXPECT_NEAR(specimen2[q], specimen[q], 1e-6 * scale) << "component " << q;
  }
}

// The stresses of a model are a function of its stored state: a state file written and
// read back gives the same stresses bit for bit, on any number of threads.
TEST(ParticleStress, ReloadedModelHasTheSameStressesBitForBit)
{
  Model m = shearedSpecimen();
  const std::vector<StressTensor> before = particleStresses(m);
  const std::vector<unsigned char> image = writeStateToMemory(m);
  Model reloaded = readStateFromMemory(image.data(), image.size());
  reloaded.solver.threads = 2;
  reloaded.solver.parallelThreshold = 1; // the OpenMP path, two threads
  const std::vector<StressTensor> after = particleStresses(reloaded);
  ASSERT_EQ(before.size(), after.size());
  EXPECT_EQ(std::memcmp(before.data(), after.data(), before.size() * sizeof(StressTensor)), 0);
}

using statetest::sameForces;

// The per-particle stresses of a running stage come from its own solver's lists
// (freshInteractionForces: every contact evaluated once with no time increment, then the
// solver's state put back): bit for bit those of a Simulation made from the same state
// (what a saved and reloaded frame shows), with contacts, rolling springs, bonds (some
// broken, some softening), rigid walls and a membrane; the solver, asked twice on the way,
// then steps exactly as an identical one that was never asked (particles, springs, bonds,
// walls, test history), and reports the same last-step forces and diagnostics meanwhile.
// Its overlaps (Current Porosity), measured on its neighbour list, are the search's.
TEST(ParticleStress, RunningSolverGivesTheFreshStressesAndStepsOnUnchanged)
{
  for (const char* name : { "settling", "cemented", "triaxial", "membrane" }) {
    SCOPED_TRACE(name);
    Model asked = statetest::byName(name);
    asked.solver.threads = 2;
    asked.solver.parallelThreshold = 1; // the threaded path for the one asked
    Model never = statetest::byName(name);
    Simulation a(asked);
    Simulation b(never);
    a.advance(5);
    b.advance(5);

    const InteractionForces fresh = a.freshInteractionForces();
    Model copy = asked;
    const Simulation rebuilt(copy);
    const InteractionForces reference = rebuilt.interactionForces();
    ASSERT_GT(reference.size(), 0u);
    EXPECT_TRUE(sameForces(fresh, reference)) << fresh.size() << " against " << reference.size() << " forces";
    const std::vector<StressTensor> running = particleStresses(asked, fresh);
    const std::vector<StressTensor> fromState = particleStresses(asked);
    EXPECT_TRUE(statetest::sameBits(running, fromState));

    // The overlaps (Current Porosity) from the solver's neighbour list: the search's, bit
    // for bit.
    const OverlapReport listed = a.overlaps();
    const OverlapReport searched = measureOverlaps(asked);
    EXPECT_GT(searched.pairs, 0u);
    EXPECT_EQ(listed.pairs, searched.pairs);
    EXPECT_EQ(std::memcmp(&listed.volume, &searched.volume, sizeof(double)), 0);
    EXPECT_EQ(std::memcmp(&listed.largest, &searched.largest, sizeof(double)), 0);
    EXPECT_EQ(listed.idA, searched.idA);
    EXPECT_EQ(listed.idB, searched.idB);
    // A list out of (i, j) order is refused (the solver then searches).
    if (reference.size() > 1) {
      OverlapReport refused;
      refused.pairs = 7;
      EXPECT_FALSE(measureOverlaps(asked, { 1, 0 }, { 2, 3 }, refused));
      EXPECT_FALSE(measureOverlaps(asked, { 2 }, { 1 }, refused));
      EXPECT_EQ(refused.pairs, 7u);
    }
    const double porosity = currentPorosity(asked, listed.volume);
    const double searchedPorosity = currentPorosity(asked);
    EXPECT_EQ(std::memcmp(&porosity, &searchedPorosity, sizeof(double)), 0);

    // Meanwhile the solver reports the last step's forces and diagnostics, as before.
    EXPECT_TRUE(sameForces(a.interactionForces(), b.interactionForces()));
    const Diagnostics da = a.diagnostics();
    const Diagnostics db = b.diagnostics();
    EXPECT_EQ(std::memcmp(&da.unbalancedForceRatio, &db.unbalancedForceRatio, sizeof(double)), 0);
    EXPECT_EQ(std::memcmp(&da.kineticEnergy, &db.kineticEnergy, sizeof(double)), 0);
    EXPECT_EQ(da.contacts, db.contacts);

    a.advance(150);
    (void)a.freshInteractionForces();
    a.advance(150);
    b.advance(300);
    EXPECT_EQ(statetest::firstDifference(asked, never), "") << "after 300 more steps";
  }
}

// After an instability the model holds the last good state and the solver's lists the
// state it stopped in: the stresses and overlaps a frame shows then are those of the last
// good state (a solver made from it; a search), every value finite.
TEST(ParticleStress, AfterAnInstabilityTheFrameShowsTheLastGoodState)
{
  Model m = dem::testing::specimen(300, 0.012, 0.0006, 0.0009, 4);
  dem::testing::consolidate(m, 2e4); // contacts with forces in the last good state
  m.solver.allowUnsafeTimestep = true;
  m.solver.settlingDamping = 0.0;
  m.solver.requestedTimestep = 5.0 * criticalTimestep(m, m.solver.contactLaw);
  Random shake(7);
  for (Vec3& v : m.particles.velocity) {
    v += 0.2 * Vec3(shake.uniform() - 0.5, shake.uniform() - 0.5, shake.uniform() - 0.5);
  }
  Simulation unstable(m);
  EXPECT_THROW(
    {
      for (int k = 0; k < 100; ++k) {
        unstable.advance(100);
      }
    },
    InstabilityError);
  const InteractionForces shown = unstable.freshInteractionForces();
  Model copy = m;
  const Simulation rebuilt(copy);
  const InteractionForces reference = rebuilt.interactionForces();
  ASSERT_GT(reference.size(), 0u);
  EXPECT_TRUE(sameForces(shown, reference));
  for (const StressTensor& t : particleStresses(m, shown)) {
    for (double c : t) {
      ASSERT_TRUE(std::isfinite(c));
    }
  }
  const OverlapReport listed = unstable.overlaps();
  const OverlapReport searched = measureOverlaps(m);
  EXPECT_EQ(listed.pairs, searched.pairs);
  EXPECT_EQ(std::memcmp(&listed.volume, &searched.volume, sizeof(double)), 0);
}
