// Cementing a pack (dem::cement, PHYSICS.md section 3): which pairs get a bond, what each
// bond holds, the strength draw, validation, and cemented packs under the solver
// (stability under gravity, the timestep accounting for bond stiffness).
#include "BruteForce.h"

#include "dem/Bonds.h"
#include "dem/Cement.h"
#include "dem/Errors.h"
#include "dem/Pack.h"
#include "dem/Simulation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

using namespace dem;

namespace {

constexpr double Pi = 3.14159265358979323846;

/// A grown pack: every particle touches a neighbour. 3D: 250 spheres of radius 1-1.5 mm
/// in a 20 mm cube (or `count` in a cube of side `side`); 2D: 70 discs in a 30 mm square,
/// slab 2 mm.
Model grownPack(bool planar, bool periodic, std::uint64_t seed, std::int64_t count = 0, double side = 0.02)
{
  Model m;
  if (planar) {
    m.domain.section2D = true;
    m.domain.size = Vec3(0.03, 0.03, 0.002);
  } else {
    m.domain.size = Vec3(side, side, side);
  }
  m.domain.periodic = { { periodic, periodic, false } };
  m.material.youngsModulus = 1e8;
  PackParameters params;
  params.initialElements = count > 0 ? count : (planar ? 70 : 250);
  params.minimumSize = 0.001;
  params.maximumSize = 0.0015;
  params.randomSeed = seed;
  buildPack(m, params);
  growElements(m);
  return m;
}

/// Minimum-image separation b - a (z = 0 in a 2D section).
Vec3 separation(const Domain& d, const Vec3& a, const Vec3& b)
{
  Vec3 s = b - a;
  for (int k = 0; k < 3; ++k) {
    if (d.periodic[k]) {
      s[k] -= d.size[k] * std::nearbyint(s[k] / d.size[k]);
    }
  }
  if (d.section2D) {
    s.z() = 0.0;
  }
  return s;
}

using bruteforce::IdPair;
using bruteforce::bondPairs;

/// Brute force over all pairs: gap <= tolerance x smaller radius. Pairs within a relative
/// 1e-9 of the threshold are ambiguous under rounding and returned separately.
void bruteForcePairs(const Model& m, double tolerance, std::vector<IdPair>& bonded,
                     std::vector<IdPair>& ambiguous)
{
  const Particles& p = m.particles;
  bonded.clear();
  ambiguous.clear();
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double gap = separation(m.domain, p.position[i], p.position[j]).norm() - p.radius[i] - p.radius[j];
      const double limit = tolerance * std::min(p.radius[i], p.radius[j]);
      const IdPair ids{ std::min(p.id[i], p.id[j]), std::max(p.id[i], p.id[j]) };
      if (std::abs(gap - limit) <= 1e-9 * std::min(p.radius[i], p.radius[j])) {
        ambiguous.push_back(ids);
      } else if (gap <= limit) {
        bonded.push_back(ids);
      }
    }
  }
  std::sort(bonded.begin(), bonded.end());
  std::sort(ambiguous.begin(), ambiguous.end());
}


std::size_t slotOfId(const Particles& p, std::int64_t id)
{
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.id[i] == id) {
      return i;
    }
  }
  return p.size();
}

/// The same model with its particle slots in another order (ids unchanged).
Model permuted(const Model& m, std::uint64_t seed)
{
  Model out = m;
  const std::size_t n = m.particles.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t(0));
  Random rng(seed);
  for (std::size_t i = n; i > 1; --i) {
    std::swap(order[i - 1], order[static_cast<std::size_t>(rng.uniform() * i)]);
  }
  const Particles& a = m.particles;
  Particles& b = out.particles;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t s = order[k];
    b.position[k] = a.position[s];
    b.velocity[k] = a.velocity[s];
    b.angularVelocity[k] = a.angularVelocity[s];
    b.displacement[k] = a.displacement[s];
    b.force[k] = a.force[s];
    b.torque[k] = a.torque[s];
    b.radius[k] = a.radius[s];
    b.mass[k] = a.mass[s];
    b.inertia[k] = a.inertia[s];
    b.id[k] = a.id[s];
    b.flags[k] = a.flags[s];
  }
  return out;
}

struct Sample {
  double mean, sd;
};
Sample statistics(const std::vector<double>& x)
{
  double sum = 0.0;
  for (double v : x) {
    sum += v;
  }
  const double mean = sum / x.size();
  double ss = 0.0;
  for (double v : x) {
    ss += (v - mean) * (v - mean);
  }
  return { mean, std::sqrt(ss / (x.size() - 1)) };
}

} // namespace

// ---------------------------------------------------------------------------------------
// 9. Which pairs are bonded, and what each bond holds.

TEST(CementSelection, BondsExactlyThePairsWithinTheGapTolerance)
{
  for (bool planar : { false, true }) {
    Model m = grownPack(planar, true, 11);
    const Domain& d = m.domain;
    for (double tolerance : { 0.05, 0.3 }) {
      CementParameters cp;
      cp.gapTolerance = tolerance;
      cp.bondRadiusMultiplier = 0.8;
      cp.bondModulus = 2e9;
      cp.bondStiffnessRatio = 0.3;
      cp.tensileStrength = 7e6;
      cp.cohesion = 9e6;
      cp.frictionAngle = 35.0;
      const CementReport report = cement(m, cp);
      std::vector<IdPair> expected, ambiguous;
      bruteForcePairs(m, tolerance, expected, ambiguous);
      std::vector<IdPair> got = bondPairs(m.bonds);
      // Sorted by (idA, idB), idA < idB.
      EXPECT_TRUE(std::is_sorted(got.begin(), got.end()));
      for (const IdPair& b : got) {
        ASSERT_LT(b.first, b.second);
      }
      // Ambiguous pairs (none expected) may go either way.
      std::vector<IdPair> unambiguous;
      std::set_difference(got.begin(), got.end(), ambiguous.begin(), ambiguous.end(),
                          std::back_inserter(unambiguous));
      EXPECT_EQ(unambiguous, expected) << (planar ? "2D" : "3D") << " tolerance " << tolerance;
      EXPECT_EQ(report.bonds, got.size());
      EXPECT_GT(got.size(), m.particles.size() / 2);
      // Pairs across a periodic seam are included.
      std::size_t seam = 0;
      for (const IdPair& ids : got) {
        const Vec3 raw = m.particles.position[slotOfId(m.particles, ids.second)] -
          m.particles.position[slotOfId(m.particles, ids.first)];
        seam += (std::abs(raw.x()) > 0.5 * d.size.x() || std::abs(raw.y()) > 0.5 * d.size.y()) ? 1 : 0;
      }
      EXPECT_GT(seam, 0u) << (planar ? "2D" : "3D") << " tolerance " << tolerance;
      // Each bond: Rb = multiplier x min radius, kn = Ebar / (rA + rB), ks = ratio x kn,
      // strengths as asked (no scatter), phi in radians, intact with no load.
      double rmax = 0.0;
      for (double r : m.particles.radius) {
        rmax = std::max(rmax, r);
      }
      const Bonds& b = m.bonds;
      for (std::size_t k = 0; k < b.size(); ++k) {
        const double ra = m.particles.radius[slotOfId(m.particles, b.idA[k])];
        const double rb = m.particles.radius[slotOfId(m.particles, b.idB[k])];
        ASSERT_NEAR(b.radius[k], 0.8 * std::min(ra, rb), 1e-15);
        ASSERT_NEAR(b.normalStiffness[k], 2e9 / (ra + rb), 1e-12 * b.normalStiffness[k]);
        ASSERT_NEAR(b.shearStiffness[k], 0.3 * b.normalStiffness[k], 1e-12 * b.normalStiffness[k]);
        ASSERT_EQ(b.tensileStrength[k], 7e6);
        ASSERT_EQ(b.cohesion[k], 9e6);
        ASSERT_NEAR(b.frictionAngle[k], 35.0 * Pi / 180.0, 1e-15);
        ASSERT_EQ(b.normalForce[k], 0.0);
        ASSERT_EQ(b.shearForce[k].norm() + b.bendingMoment[k].norm() + std::abs(b.twistingMoment[k]), 0.0);
        ASSERT_FALSE(b.broken(k));
      }
      EXPECT_NEAR(report.bondStiffness, 2e9 / (2.0 * rmax), 1e-12 * report.bondStiffness);
      EXPECT_FALSE(report.summary().empty());
    }
  }
}

TEST(CementSelection, ExplicitNormalStiffnessOverridesModulus)
{
  Model m = grownPack(false, false, 12);
  CementParameters cp;
  cp.bondNormalStiffness = 3e12;
  cp.bondStiffnessRatio = 0.5;
  const CementReport report = cement(m, cp);
  ASSERT_GT(m.bonds.size(), 0u);
  for (std::size_t k = 0; k < m.bonds.size(); ++k) {
    ASSERT_EQ(m.bonds.normalStiffness[k], 3e12);
    ASSERT_EQ(m.bonds.shearStiffness[k], 1.5e12);
  }
  EXPECT_EQ(report.bondStiffness, 3e12);
}

// Re-cementing replaces the bond set (and so heals broken bonds).
TEST(CementSelection, RecementingReplacesTheSetAndHeals)
{
  Model m = grownPack(false, true, 13);
  CementParameters wide;
  wide.gapTolerance = 0.3;
  const CementReport first = cement(m, wide);
  EXPECT_EQ(first.replaced, 0u);
  const std::size_t wideCount = m.bonds.size();
  for (std::size_t k = 0; k < m.bonds.size(); k += 3) {
    m.bonds.failure[k] = static_cast<std::uint8_t>(BondFailure::Tension);
    m.bonds.failureTime[k] = 1.0;
  }
  ASSERT_GT(countBonds(m.bonds).broken, 0u);

  CementParameters narrow;
  narrow.gapTolerance = 0.05;
  const CementReport second = cement(m, narrow);
  Model fresh = grownPack(false, true, 13);
  const CementReport freshReport = cement(fresh, narrow);
  EXPECT_EQ(second.replaced, wideCount);
  EXPECT_EQ(second.bonds, freshReport.bonds);
  EXPECT_EQ(bondPairs(m.bonds), bondPairs(fresh.bonds));
  EXPECT_LT(m.bonds.size(), wideCount);
  EXPECT_EQ(countBonds(m.bonds).broken, 0u);

  // Same parameters again: same set, all intact, the previous set counted as replaced.
  for (std::size_t k = 0; k < m.bonds.size(); k += 2) {
    m.bonds.failure[k] = static_cast<std::uint8_t>(BondFailure::Shear);
    m.bonds.normalForce[k] = 5.0;
  }
  const std::size_t before = m.bonds.size();
  const CementReport third = cement(m, narrow);
  EXPECT_EQ(third.replaced, before);
  EXPECT_EQ(third.bonds, before);
  EXPECT_EQ(countBonds(m.bonds).broken, 0u);
  for (std::size_t k = 0; k < m.bonds.size(); ++k) {
    ASSERT_EQ(m.bonds.normalForce[k], 0.0);
  }
}

// ---------------------------------------------------------------------------------------
// 10. Strength scatter: lognormal, mean 1, requested CoV; keyed by (seed, idA, idB).

TEST(CementStrength, FactorHasRequestedMeanAndScatter)
{
  const double cov = 0.2;
  const std::size_t n = 100000;
  std::vector<double> tension(n), cohesion(n), logs(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::int64_t a = static_cast<std::int64_t>(k);
    const std::int64_t b = a + 1 + static_cast<std::int64_t>(k % 13);
    tension[k] = strengthFactor(42, a, b, 0, cov);
    cohesion[k] = strengthFactor(42, a, b, 1, cov);
    ASSERT_GT(tension[k], 0.0);
    logs[k] = std::log(tension[k]);
  }
  for (const std::vector<double>* x : { &tension, &cohesion }) {
    const Sample s = statistics(*x);
    const double standardError = s.sd / std::sqrt(static_cast<double>(n));
    EXPECT_NEAR(s.mean, 1.0, 3.0 * standardError); // mean within 3 standard errors
    EXPECT_NEAR(s.sd / s.mean, cov, 0.05 * cov);   // CoV within 5%
  }
  // Lognormal: ln X ~ N(-s^2/2, s^2) with s^2 = ln(1 + cov^2).
  const double s2 = std::log(1.0 + cov * cov);
  const Sample l = statistics(logs);
  EXPECT_NEAR(l.mean, -0.5 * s2, 3.0 * l.sd / std::sqrt(static_cast<double>(n)));
  EXPECT_NEAR(l.sd, std::sqrt(s2), 0.02 * std::sqrt(s2));
  // Tension and cohesion draws are independent: correlation within 4 / sqrt(n).
  const Sample st = statistics(tension);
  const Sample sc = statistics(cohesion);
  double covariance = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    covariance += (tension[k] - st.mean) * (cohesion[k] - sc.mean);
  }
  covariance /= (n - 1);
  EXPECT_LT(std::abs(covariance / (st.sd * sc.sd)), 4.0 / std::sqrt(static_cast<double>(n)));
}

TEST(CementStrength, FactorIsADeterministicFunctionOfSeedAndIds)
{
  std::size_t differentSeed = 0;
  std::size_t differentPair = 0;
  for (std::int64_t a = 0; a < 1000; ++a) {
    const std::int64_t b = a + 7;
    EXPECT_EQ(strengthFactor(5, a, b, 0, 0.0), 1.0);
    EXPECT_EQ(strengthFactor(5, a, b, 1, 0.0), 1.0);
    const double x = strengthFactor(5, a, b, 0, 0.3);
    EXPECT_EQ(x, strengthFactor(5, a, b, 0, 0.3)); // same inputs, same draw
    differentSeed += x != strengthFactor(6, a, b, 0, 0.3) ? 1 : 0;
    differentPair += x != strengthFactor(5, a, b + 1, 0, 0.3) ? 1 : 0;
  }
  EXPECT_EQ(differentSeed, 1000u);
  EXPECT_EQ(differentPair, 1000u);
}

TEST(CementStrength, PackBondsDrawFromTheirIdsNotTheirOrder)
{
  Model m = grownPack(false, true, 21, 900, 0.03);
  CementParameters cp;
  cp.gapTolerance = 0.3;
  cp.tensileStrength = 8e6;
  cp.cohesion = 12e6;
  cp.strengthScatter = 0.2;
  cp.randomSeed = 77;
  cement(m, cp);
  const Bonds& b = m.bonds;
  ASSERT_GT(b.size(), 1000u);
  for (std::size_t k = 0; k < b.size(); ++k) {
    ASSERT_NEAR(b.tensileStrength[k], 8e6 * strengthFactor(77, b.idA[k], b.idB[k], 0, 0.2), 1e-9 * 8e6);
    ASSERT_NEAR(b.cohesion[k], 12e6 * strengthFactor(77, b.idA[k], b.idB[k], 1, 0.2), 1e-9 * 12e6);
  }
  // Over the pack: mean within 3 standard errors; CoV within 3 standard errors of the
  // sample standard deviation, sd sqrt((2 + kurtosis excess) / 4n), excess 0.66 for a
  // lognormal of CoV 0.2 (at least 5%).
  const Sample s = statistics(b.tensileStrength);
  const double count = static_cast<double>(b.size());
  EXPECT_NEAR(s.mean, 8e6, 3.0 * s.sd / std::sqrt(count));
  EXPECT_NEAR(s.sd / s.mean, 0.2, 0.2 * std::max(0.05, 3.0 * std::sqrt(2.66 / (4.0 * count))));

  // Same pack, particle slots shuffled: the same bonds with the same strengths.
  Model shuffled = permuted(m, 3);
  cement(shuffled, cp);
  EXPECT_EQ(bondPairs(shuffled.bonds), bondPairs(b));
  EXPECT_EQ(shuffled.bonds.tensileStrength, b.tensileStrength);
  EXPECT_EQ(shuffled.bonds.cohesion, b.cohesion);

  // Another seed: other strengths. No scatter: all equal to the mean.
  Model other = m;
  cp.randomSeed = 78;
  cement(other, cp);
  std::size_t differ = 0;
  for (std::size_t k = 0; k < b.size(); ++k) {
    differ += other.bonds.tensileStrength[k] != b.tensileStrength[k] ? 1 : 0;
  }
  EXPECT_EQ(differ, b.size());
  cp.strengthScatter = 0.0;
  cement(other, cp);
  for (std::size_t k = 0; k < other.bonds.size(); ++k) {
    ASSERT_EQ(other.bonds.tensileStrength[k], 8e6);
    ASSERT_EQ(other.bonds.cohesion[k], 12e6);
  }
}

// ---------------------------------------------------------------------------------------
// 11. Validation: every field out of range is an InputError naming it.

TEST(CementValidation, EachParameterOutOfRangeIsNamed)
{
  EXPECT_NO_THROW(validate(CementParameters{}));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  struct Case {
    const char* name;
    void (*set)(CementParameters&, double);
    std::vector<double> bad;
    std::vector<double> good;
  };
  const std::vector<Case> cases = {
    { "Gap Tolerance", [](CementParameters& p, double v) { p.gapTolerance = v; }, { -0.01, nan, inf }, { 0.0, 0.5 } },
    { "Bond Radius Multiplier", [](CementParameters& p, double v) { p.bondRadiusMultiplier = v; },
      { 0.0, -0.5, 1.01, nan }, { 1.0, 0.1 } },
    { "Bond Modulus", [](CementParameters& p, double v) { p.bondModulus = v; }, { 0.0, -1e9, nan, inf }, { 1e6 } },
    { "Bond Stiffness Ratio", [](CementParameters& p, double v) { p.bondStiffnessRatio = v; }, { 0.0, -0.4, nan },
      { 1.0, 2.0 } },
    { "Tensile Strength", [](CementParameters& p, double v) { p.tensileStrength = v; }, { 0.0, -1.0, nan }, { 1.0 } },
    { "Cohesion", [](CementParameters& p, double v) { p.cohesion = v; }, { 0.0, -1.0, nan }, { 1.0 } },
    { "Friction Angle", [](CementParameters& p, double v) { p.frictionAngle = v; }, { -1.0, 90.0, 95.0, nan },
      { 0.0, 89.0 } },
    { "Strength Scatter", [](CementParameters& p, double v) { p.strengthScatter = v; }, { -0.1, 1.1, nan },
      { 0.0, 1.0 } },
  };
  for (const Case& c : cases) {
    for (double v : c.bad) {
      CementParameters p;
      c.set(p, v);
      try {
        validate(p);
        ADD_FAILURE() << c.name << " = " << v << " accepted";
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(c.name), std::string::npos) << e.what();
      }
    }
    for (double v : c.good) {
      CementParameters p;
      c.set(p, v);
      EXPECT_NO_THROW(validate(p)) << c.name << " = " << v;
    }
  }
  CementParameters negativeStiffness;
  negativeStiffness.bondNormalStiffness = -1.0;
  EXPECT_THROW(validate(negativeStiffness), InputError);

  // cement() validates first and leaves the model's bonds alone.
  Model m = grownPack(false, false, 14);
  cement(m, CementParameters{});
  const std::size_t before = m.bonds.size();
  ASSERT_GT(before, 0u);
  CementParameters bad;
  bad.cohesion = -5.0;
  EXPECT_THROW(cement(m, bad), InputError);
  EXPECT_EQ(m.bonds.size(), before);
}

// ---------------------------------------------------------------------------------------
// 12. A cemented, settled pack under gravity alone: no bond breaks, it comes to rest.

namespace {
/// A pack settled under gravity: built and grown (about 380 spheres of radius 1-1.5 mm in
/// a 20 x 20 x 25 mm box, porosity about 0.62), collapsed under 30 g with local damping
/// 0.7 (a loose random pack takes tens of thousands of steps to fall into place at 1 g;
/// 30 g does it in a few thousand), then relaxed at 1 g.
Model settledPack(std::uint64_t seed, int collapseSteps, int relaxSteps)
{
  Model m;
  m.domain.size = Vec3(0.02, 0.02, 0.025);
  m.material.youngsModulus = 1e8;
  m.material.friction = 0.5;
  PackParameters params;
  params.initialElements = 400;
  params.minimumSize = 0.001;
  params.maximumSize = 0.0015;
  params.randomSeed = seed;
  buildPack(m, params);
  growElements(m);
  m.solver.settlingDamping = 0.7;
  m.gravity = Vec3(0, 0, -30.0 * 9.81);
  {
    Simulation collapse(m);
    collapse.advance(collapseSteps);
  }
  m.gravity = Vec3(0, 0, -9.81);
  Simulation relax(m);
  relax.advance(relaxSteps);
  return m;
}
} // namespace

// Cemented after settling, with strengths (1 MPa) far above the gravitational stresses
// (rho g h ~ 1e3 Pa), the pack must keep every bond and come to rest: the kinetic energy
// of the bonded particles falls below 1e-3 of its value at cementing and the unbalanced
// force ratio below 0.01 (PHYSICS.md s.4). (A few particles touch nothing within the gap
// tolerance and stay unbonded; rattlers spinning freely keep their energy, since local
// damping acts on unbalanced forces only, so they are left out of the energy check.)
TEST(CementStability, CementedPackStaysIntactUnderGravity)
{
  Model m = settledPack(31, 6000, 3000);
  CementParameters cp;
  cp.bondModulus = 1e8;
  cp.tensileStrength = 1e6;
  cp.cohesion = 1e6;
  const CementReport report = cement(m, cp);
  ASSERT_GT(report.bonds, m.particles.size());
  std::vector<char> bonded(m.particles.size(), 0);
  for (std::size_t k = 0; k < m.bonds.size(); ++k) {
    bonded[slotOfId(m.particles, m.bonds.idA[k])] = 1;
    bonded[slotOfId(m.particles, m.bonds.idB[k])] = 1;
  }
  auto bondedKinetic = [&]() {
    double e = 0.0;
    for (std::size_t i = 0; i < m.particles.size(); ++i) {
      if (bonded[i]) {
        e += 0.5 * m.particles.mass[i] * m.particles.velocity[i].squaredNorm() +
          0.5 * m.particles.inertia[i] * m.particles.angularVelocity[i].squaredNorm();
      }
    }
    return e;
  };
  const double atCement = bondedKinetic();
  ASSERT_GT(atCement, 0.0);
  Simulation sim(m);
  sim.advance(4000);
  const Diagnostics d = sim.diagnostics();
  const double after = bondedKinetic();
  std::printf("cemented pack: %zu particles, %zu bonds; kinetic energy of bonded particles "
              "%.3e J at cementing, %.3e J after 4000 steps; unbalanced force ratio %.3e\n",
              m.particles.size(), report.bonds, atCement, after, d.unbalancedForceRatio);
  EXPECT_EQ(countBonds(m.bonds).broken, 0u);
  EXPECT_LT(after, 1e-3 * atCement);
  EXPECT_LT(d.unbalancedForceRatio, 0.01);
  EXPECT_EQ(d.escaped, 0u);
}

// ---------------------------------------------------------------------------------------
// 13. The timestep accounts for bond stiffness (PHYSICS.md s.2: bonds in parallel with
// contacts shorten it) and the stiff cemented pack runs stably.

TEST(CementStability, TimestepAccountsForBondStiffness)
{
  Model m = settledPack(32, 1000, 0);
  for (ContactLaw law : { ContactLaw::HertzMindlin, ContactLaw::Linear }) {
    Model probe = m;
    probe.bonds.clear();
    const double before = criticalTimestep(probe, law);
    CementParameters cp;
    cp.bondModulus = 1e11; // 1000 x the particles' modulus
    cement(probe, cp);
    const double after = criticalTimestep(probe, law);
    // Upper bound from the bonds alone: sqrt(m / sum kn A) for each particle (contacts
    // in parallel only shorten it further).
    std::vector<double> stiffness(probe.particles.size(), 0.0);
    for (std::size_t k = 0; k < probe.bonds.size(); ++k) {
      const double area = Pi * probe.bonds.radius[k] * probe.bonds.radius[k];
      stiffness[slotOfId(probe.particles, probe.bonds.idA[k])] += probe.bonds.normalStiffness[k] * area;
      stiffness[slotOfId(probe.particles, probe.bonds.idB[k])] += probe.bonds.normalStiffness[k] * area;
    }
    double bound = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < probe.particles.size(); ++i) {
      if (stiffness[i] > 0.0) {
        bound = std::min(bound, std::sqrt(probe.particles.mass[i] / stiffness[i]));
      }
    }
    std::printf("critical timestep %s: %.3e s uncemented, %.3e s cemented (bond bound %.3e s)\n",
                law == ContactLaw::HertzMindlin ? "Hertz" : "linear", before, after, bound);
    EXPECT_LT(after, before);
    EXPECT_LE(after, bound * (1.0 + 1e-12));
  }
  // The stiff cemented pack, undamped, at the solver's step: stable.
  const double uncementedSafe = m.solver.timestepSafety * criticalTimestep(m, m.solver.contactLaw);
  CementParameters cp;
  cp.bondModulus = 1e11;
  cement(m, cp);
  m.solver.settlingDamping = 0.0;
  Simulation sim(m);
  EXPECT_LT(sim.timestep(), uncementedSafe);
  EXPECT_NO_THROW(sim.advance(3000));
  EXPECT_EQ(sim.diagnostics().escaped, 0u);
  EXPECT_EQ(countBonds(m.bonds).broken, 0u);
}
