// Bonds over an interaction range (Bond Range; Scholtes & Donze 2013, JMPS 61:352; YADE
// JCFpm's interactionDetectionFactor): which pairs are bonded, Bond Range 1 keeps the
// Gap Tolerance bond set exactly, a bond's rest length is its length at cementing (a fresh
// model is unstressed), a broken long bond's particles interact only when they touch, and
// the Bonded Coordination equals an independent count. SI units.
#include "DynamicsFixtures.h"

#include "BruteForce.h"

#include "dem/Bonds.h"
#include "dem/Cement.h"
#include "dem/Errors.h"
#include "dem/Pack.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

using namespace dem;
using namespace dem::testing;

namespace {

constexpr double Pi = 3.14159265358979323846;

/// A grown pack (every particle touches a neighbour, none overlaps): 3D, 300 spheres of
/// radius 1-2 mm in a 24 mm cube, periodic in x and y (unless `walled`); 2D, 90 discs in
/// a 36 mm square.
Model grownPack(bool planar, bool walled = false)
{
  Model m;
  if (planar) {
    m.domain.section2D = true;
    m.domain.size = Vec3(0.036, 0.036, 0.002);
  } else {
    m.domain.size = Vec3(0.024, 0.024, 0.024);
  }
  m.domain.periodic = { { !walled, !walled, false } };
  m.material.youngsModulus = 1e8;
  m.gravity.setZero();
  PackParameters params;
  params.initialElements = planar ? 90 : 300;
  params.minimumSize = 0.001;
  params.maximumSize = 0.002;
  params.randomSeed = 7;
  buildPack(m, params);
  growElements(m);
  return m;
}

using bruteforce::IdPair;
using bruteforce::separation; // minimum image, written independently of the engine
using bruteforce::bondPairs;

/// All pairs bonded by the rule, by brute force over every pair: gap <= tolerance x the
/// smaller radius, or (range > 1) centre distance <= range x (rA + rB). Pairs within a
/// relative 1e-9 of either threshold may go either way under rounding: returned apart.
void bruteForce(const Model& m, double tolerance, double range, std::vector<IdPair>& bonded,
                std::vector<IdPair>& ambiguous)
{
  const Particles& p = m.particles;
  bonded.clear();
  ambiguous.clear();
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double distance = separation(m.domain, p.position[i], p.position[j]).norm();
      const double sum = p.radius[i] + p.radius[j];
      const double gapLimit = sum + tolerance * std::min(p.radius[i], p.radius[j]);
      const double rangeLimit = range > 1.0 ? range * sum : -1.0;
      const IdPair ids{ std::min(p.id[i], p.id[j]), std::max(p.id[i], p.id[j]) };
      const double eps = 1e-9 * sum;
      if (std::abs(distance - gapLimit) <= eps || std::abs(distance - rangeLimit) <= eps) {
        ambiguous.push_back(ids);
      } else if (distance <= gapLimit || distance <= rangeLimit) {
        bonded.push_back(ids);
      }
    }
  }
  std::sort(bonded.begin(), bonded.end());
  std::sort(ambiguous.begin(), ambiguous.end());
}


std::vector<IdPair> withoutAmbiguous(const std::vector<IdPair>& got, const std::vector<IdPair>& ambiguous)
{
  std::vector<IdPair> out;
  std::set_difference(got.begin(), got.end(), ambiguous.begin(), ambiguous.end(), std::back_inserter(out));
  return out;
}

CementParameters rangeCement(double range)
{
  CementParameters cp;
  cp.bondRange = range;
  cp.bondModulus = 1e8;
  cp.tensileStrength = 1e6;
  cp.cohesion = 2e6;
  return cp;
}

// A pair of particles of radius R with a gap between them, for the bond-law tests.
constexpr double R = 0.01;     // m
constexpr double Gap = 0.3 * R; // m, surface gap at cementing
constexpr double Dt = 1.0e-7;  // s, prescribed step of the kinematic tests
constexpr double Range = 1.2;  // reaches a centre distance of 2.4 R > 2 R + Gap

/// Two spheres of radius R on the x axis, a surface gap Gap apart, cemented with Bond
/// Range 1.2 (Gap Tolerance 0.05 alone would not bond them). `kinematic`: both move only
/// as prescribed (FlagFixed), with step Dt.
Model longPair(bool kinematic, double tensileStrength = 1e9)
{
  Model m = emptyModel(1e9, 0.25, 2650.0, 1.0, 2.0);
  addSphere(m, Vec3(-R - 0.5 * Gap, 0, 0), R);
  addSphere(m, Vec3(R + 0.5 * Gap, 0, 0), R);
  if (kinematic) {
    m.particles.flags[0] |= FlagFixed;
    m.particles.flags[1] |= FlagFixed;
    m.solver.requestedTimestep = Dt;
    m.solver.allowUnsafeTimestep = true;
  }
  CementParameters cp = rangeCement(Range);
  cp.tensileStrength = tensileStrength;
  cp.cohesion = 1e9;
  const CementReport report = cement(m, cp);
  EXPECT_EQ(report.bonds, 1u);
  EXPECT_EQ(report.longBonds, 1u);
  return m;
}

double centreDistance(const Model& m)
{
  return (m.particles.position[1] - m.particles.position[0]).norm();
}

} // namespace

// ---------------------------------------------------------------------------------------
// Which pairs are bonded

TEST(BondRange, RangeOneKeepsTheGapToleranceBondSetExactly)
{
  for (bool planar : { false, true }) {
    const Model pack = grownPack(planar);
    for (double tolerance : { 0.0, 0.05, 0.3, 1.0 }) {
      CementParameters today;
      today.gapTolerance = tolerance;
      today.strengthScatter = 0.2;
      CementParameters explicitOne = today;
      explicitOne.bondRange = 1.0;
      Model a = pack;
      Model b = pack;
      cement(a, today);
      cement(b, explicitOne);
      // The Gap Tolerance rule by brute force: today's set, exactly.
      std::vector<IdPair> expected, ambiguous;
      bruteForce(pack, tolerance, 1.0, expected, ambiguous); // touching pairs may be ambiguous
      EXPECT_EQ(withoutAmbiguous(bondPairs(b.bonds), ambiguous), expected)
        << (planar ? "2D" : "3D") << " Gap Tolerance " << tolerance;
      // And bond for bond the same state (strengths drawn from the same keys).
      ASSERT_EQ(a.bonds.size(), b.bonds.size());
      EXPECT_EQ(a.bonds.idA, b.bonds.idA);
      EXPECT_EQ(a.bonds.idB, b.bonds.idB);
      EXPECT_EQ(a.bonds.tensileStrength, b.bonds.tensileStrength);
      EXPECT_EQ(a.bonds.normalStiffness, b.bonds.normalStiffness);
      EXPECT_EQ(a.bonds.radius, b.bonds.radius);
    }
  }
}

TEST(BondRange, BondsExactlyThePairsWithinTheRange)
{
  for (bool planar : { false, true }) {
    const Model pack = grownPack(planar);
    std::size_t previous = 0;
    for (double range : { 1.1, 1.3, 1.6, 2.0 }) {
      Model m = pack;
      const CementReport report = cement(m, rangeCement(range));
      std::vector<IdPair> expected, ambiguous;
      bruteForce(pack, 0.05, range, expected, ambiguous);
      const std::vector<IdPair> got = bondPairs(m.bonds);
      EXPECT_TRUE(std::is_sorted(got.begin(), got.end()));
      EXPECT_EQ(withoutAmbiguous(got, ambiguous), expected) << (planar ? "2D" : "3D") << " range " << range;
      EXPECT_GT(got.size(), previous) << "a longer range bonds more pairs";
      previous = got.size();
      // Long bonds: the pairs whose gap is positive, counted independently.
      std::size_t longBonds = 0;
      for (const IdPair& ids : got) {
        std::size_t i = 0, j = 0;
        for (std::size_t s = 0; s < pack.particles.size(); ++s) {
          i = pack.particles.id[s] == ids.first ? s : i;
          j = pack.particles.id[s] == ids.second ? s : j;
        }
        const double distance = separation(pack.domain, pack.particles.position[i], pack.particles.position[j]).norm();
        longBonds += distance > pack.particles.radius[i] + pack.particles.radius[j] ? 1 : 0;
      }
      EXPECT_EQ(report.longBonds, longBonds);
    }
  }
}

TEST(BondRange, BondedCoordinationEqualsAnIndependentCount)
{
  for (bool planar : { false, true }) {
    const Model pack = grownPack(planar);
    for (double range : { 1.0, 1.25, 1.5 }) {
      Model m = pack;
      const CementReport report = cement(m, rangeCement(range));
      // Bonds per particle, counted from the brute-force pair set: the mean number of
      // bonded partners.
      std::vector<IdPair> expected, ambiguous;
      bruteForce(pack, 0.05, range, expected, ambiguous);
      ASSERT_TRUE(ambiguous.empty());
      std::vector<int> partners(pack.particles.size(), 0);
      for (const IdPair& ids : expected) {
        ++partners[static_cast<std::size_t>(ids.first)]; // ids are 0..N-1 in a built pack
        ++partners[static_cast<std::size_t>(ids.second)];
      }
      double mean = 0.0;
      for (int k : partners) {
        mean += k;
      }
      mean /= static_cast<double>(partners.size());
      EXPECT_NEAR(report.bondedCoordination, mean, 1e-12 * mean) << "range " << range;
      EXPECT_DOUBLE_EQ(bondedCoordination(m.bonds.size(), m.particles.size()), report.bondedCoordination);
      EXPECT_EQ(report.particles, pack.particles.size());
      if (range == 1.0) {
        EXPECT_LT(report.bondedCoordination, planar ? 4.5 : 7.0);
      }
    }
    EXPECT_EQ(bondedCoordination(0, 0), 0.0);
  }
}

// ---------------------------------------------------------------------------------------
// The bond law over a range

TEST(BondRange, AFreshlyCementedModelIsUnstressed)
{
  // A long bond alone: nothing moves, the bond holds nothing, step after step.
  {
    Model m = longPair(false);
    const std::vector<Vec3> start = m.particles.position;
    Simulation sim(m);
    sim.advance(2000);
    EXPECT_EQ(m.particles.position, start);
    EXPECT_EQ(m.bonds.normalForce[0], 0.0);
    EXPECT_EQ(m.bonds.shearForce[0].norm(), 0.0);
    EXPECT_EQ(m.particles.velocity[0].norm() + m.particles.velocity[1].norm(), 0.0);
  }
  // A whole grown pack cemented over a range (no overlaps, no gravity): no bond holds a
  // force, no particle moves.
  for (bool planar : { false, true }) {
    Model m = grownPack(planar, true);
    const CementReport report = cement(m, rangeCement(1.4));
    ASSERT_GT(report.longBonds, report.bonds / 3);
    const std::vector<Vec3> start = m.particles.position;
    Simulation sim(m);
    sim.advance(300);
    double largestForce = 0.0;
    for (std::size_t k = 0; k < m.bonds.size(); ++k) {
      largestForce = std::max(largestForce, std::abs(m.bonds.normalForce[k]) + m.bonds.shearForce[k].norm());
    }
    EXPECT_EQ(largestForce, 0.0) << (planar ? "2D" : "3D");
    EXPECT_EQ(m.particles.position, start);
    EXPECT_EQ(countBonds(m.bonds).broken, 0u);
  }
}

TEST(BondRange, RestLengthIsTheLengthAtCementing)
{
  // B pulled along the axis, then pushed back past its cemented position (the particles
  // still apart): the bond force is kn A (d - d0) with d0 the distance at cementing, in
  // tension and in compression.
  Model m = longPair(true);
  const double d0 = centreDistance(m);
  ASSERT_NEAR(d0, 2.0 * R + Gap, 1e-15);
  const double kn = 1e8 / (2.0 * R); // Bond Modulus / (rA + rB): the touching pair's stiffness
  const double area = Pi * R * R;
  EXPECT_NEAR(m.bonds.normalStiffness[0], kn, 1e-12 * kn);
  EXPECT_NEAR(m.bonds.radius[0], R, 1e-15);
  const double v = 0.1 * Gap / (400 * Dt);
  m.particles.velocity[1] = Vec3(v, 0, 0);
  Simulation sim(m);
  for (int k = 0; k < 400; ++k) {
    sim.advance(1);
    const double expected = kn * area * (centreDistance(m) - d0);
    ASSERT_NEAR(m.bonds.normalForce[0], expected, 1e-9 * std::abs(expected) + 1e-12) << "step " << k;
    ASSERT_NEAR(m.particles.force[0].x(), expected, 1e-9 * std::abs(expected) + 1e-12);
  }
  m.particles.velocity[1] = Vec3(-v, 0, 0);
  for (int k = 0; k < 1200; ++k) {
    sim.advance(1);
    const double d = centreDistance(m);
    ASSERT_GT(d, 2.0 * R); // apart: the bond alone acts
    const double expected = kn * area * (d - d0);
    ASSERT_NEAR(m.bonds.normalForce[0], expected, 1e-9 * std::abs(expected) + 1e-12) << "step " << k;
  }
  EXPECT_LT(m.bonds.normalForce[0], 0.0) << "compressed below its rest length";
}

TEST(BondRange, ABrokenLongBondsParticlesInteractOnlyWhenTheyTouch)
{
  // Strength 1 MPa: B pulled until the bond breaks in tension, then pushed back towards A.
  Model m = longPair(true, 1e6);
  const double v = 1e-5 * R / Dt; // m/s: 1e-5 R per step
  m.particles.velocity[1] = Vec3(v, 0, 0);
  Simulation sim(m);
  int steps = 0;
  while (!m.bonds.broken(0) && steps < 200000) {
    sim.advance(1);
    ++steps;
  }
  ASSERT_TRUE(m.bonds.broken(0));
  EXPECT_EQ(m.bonds.failure[0], static_cast<std::uint8_t>(BondFailure::Tension));
  m.particles.velocity[1] = Vec3(-v, 0, 0);
  bool touched = false;
  for (int k = 0; k < 100000 && !touched; ++k) {
    sim.advance(1);
    const double d = centreDistance(m);
    if (d >= 2.0 * R) {
      // Apart: no force at all between them (the broken bond holds nothing).
      ASSERT_EQ(m.particles.force[0].norm(), 0.0) << "distance " << d;
      ASSERT_EQ(m.particles.force[1].norm(), 0.0);
    } else {
      touched = true;
      // Touching: the contact pushes them apart, and the bond stays broken.
      EXPECT_LT(m.particles.force[0].x(), 0.0);
      EXPECT_GT(m.particles.force[1].x(), 0.0);
    }
  }
  EXPECT_TRUE(touched);
  EXPECT_TRUE(m.bonds.broken(0));
  EXPECT_EQ(m.bonds.normalForce[0], 0.0);
}

// ---------------------------------------------------------------------------------------
// Bounds

TEST(BondRange, BondRangeAndGapToleranceAreBounded)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (double bad : { 0.0, 0.99, 2.01, 100.0, nan, inf }) {
    CementParameters p;
    p.bondRange = bad;
    try {
      validate(p);
      ADD_FAILURE() << "Bond Range = " << bad << " accepted";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("Bond Range = "), std::string::npos) << what;
      EXPECT_NE(what.find("[1, 2]"), std::string::npos) << what;
    }
  }
  for (double bad : { -0.01, 1.01, 100.0, nan, inf }) {
    CementParameters p;
    p.gapTolerance = bad;
    try {
      validate(p);
      ADD_FAILURE() << "Gap Tolerance = " << bad << " accepted";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("Gap Tolerance = "), std::string::npos) << what;
      EXPECT_NE(what.find("[0, 1]"), std::string::npos) << what;
    }
  }
  // Gap Tolerance 100 once bonded every pair of a 300-particle pack (issue 18, item 12).
  Model m = grownPack(false);
  CementParameters p;
  p.gapTolerance = 100.0;
  EXPECT_THROW(cement(m, p), InputError);
  EXPECT_EQ(m.bonds.size(), 0u);
  for (double bad : { -0.1, 1.1, nan }) {
    CementParameters p;
    p.momentContribution = bad;
    try {
      validate(p);
      ADD_FAILURE() << "Moment Contribution = " << bad << " accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("Moment Contribution"), std::string::npos) << e.what();
    }
  }
  for (double good : { 1.0, 1.5, 2.0 }) {
    CementParameters q;
    q.bondRange = good;
    EXPECT_NO_THROW(validate(q));
  }
}
