// Building the pack: random sequential placement, Add Elements, Grow Elements, Current
// Porosity and input validation. Geometry is checked by brute force over all pairs
// (BruteForce.h), never with the engine's own grids.
#include "BruteForce.h"

#include "dem/Errors.h"
#include "dem/Pack.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <set>
#include <string>

namespace {

constexpr double kPi = 3.14159265358979323846;

dem::Model boxModel(double lx, double ly, double lz)
{
  dem::Model model;
  model.domain.origin = dem::Vec3(0.5, -0.25, 2.0);
  model.domain.size = dem::Vec3(lx, ly, lz);
  return model;
}

dem::PackParameters packOf(std::int64_t n, double rMin, double rMax, std::uint64_t seed = 7)
{
  dem::PackParameters params;
  params.initialElements = n;
  params.minimumSize = rMin;
  params.maximumSize = rMax;
  params.randomSeed = seed;
  return params;
}

/// Porosity written out independently of the engine (the definition in Porosity.h):
/// 1 - sum(particle volumes) / occupied volume; along the up axis (largest |g| among the
/// moving axes, when not periodic) the occupied volume stops at the highest particle top.
double independentPorosity(const dem::Model& model)
{
  const dem::Domain& d = model.domain;
  const dem::Particles& p = model.particles;
  if (p.empty()) {
    return 1.0;
  }
  double solid = 0.0;
  for (double r : p.radius) {
    solid += d.section2D ? kPi * r * r * d.size.z() : 4.0 / 3.0 * kPi * r * r * r;
  }
  int up = -1;
  for (int a = 0; a < d.dimension(); ++a) {
    if (model.gravity[a] != 0.0 && (up < 0 || std::abs(model.gravity[a]) > std::abs(model.gravity[up]))) {
      up = a;
    }
  }
  double occupied = d.size.x() * d.size.y() * d.size.z();
  if (up >= 0 && !d.periodic[up]) {
    double height;
    if (model.gravity[up] < 0.0) { // up is +axis: from the lower face to the highest top
      double top = -std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < p.size(); ++i) {
        top = std::max(top, p.position[i][up] + p.radius[i]);
      }
      height = std::min(top, d.upper()[up]) - d.origin[up];
    } else { // up is -axis: from the upper face down to the lowest bottom
      double bottom = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < p.size(); ++i) {
        bottom = std::min(bottom, p.position[i][up] - p.radius[i]);
      }
      height = d.upper()[up] - std::max(bottom, d.origin[up]);
    }
    occupied *= height / d.size[up];
  }
  return 1.0 - solid / occupied;
}

template <class F>
std::string messageOf(F&& f)
{
  try {
    f();
  } catch (const dem::InputError& e) {
    return e.what();
  }
  return "(no InputError thrown)";
}

void expectError(const dem::PackParameters& params, const dem::Domain& domain,
                 std::initializer_list<const char*> fragments)
{
  const std::string m = messageOf([&] { dem::validate(params, domain); });
  for (const char* fragment : fragments) {
    EXPECT_NE(m.find(fragment), std::string::npos) << "'" << fragment << "' not in: " << m;
  }
  // buildPack validates before touching the model.
  dem::Model model;
  model.domain = domain;
  model.particles.append(dem::Vec3(0, 0, 0), 1.0, 99);
  EXPECT_THROW(dem::buildPack(model, params), dem::InputError);
  EXPECT_EQ(model.particles.size(), 1u);
}

void expectRadiiIn(const dem::Model& model, double lo, double hi)
{
  for (double r : model.particles.radius) {
    ASSERT_GE(r, lo);
    ASSERT_LE(r, hi);
  }
}

void expectBitwiseEqual(const dem::Particles& a, const dem::Particles& b)
{
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(0, std::memcmp(a.position.data(), b.position.data(), a.size() * sizeof(dem::Vec3)));
  EXPECT_EQ(0, std::memcmp(a.radius.data(), b.radius.data(), a.size() * sizeof(double)));
  EXPECT_EQ(a.id, b.id);
  EXPECT_EQ(a.flags, b.flags);
}

} // namespace

// ---------------------------------------------------------------------------------------
// Placement

TEST(BuildPack, PlacesTheRequestedCountWithoutOverlapInsideTheWalls)
{
  dem::Model model = boxModel(0.1, 0.08, 0.06);
  const dem::PackReport report = dem::buildPack(model, packOf(2500, 0.001, 0.002));
  EXPECT_EQ(report.placed, 2500u);
  EXPECT_FALSE(report.saturated);
  ASSERT_EQ(model.particles.size(), 2500u);
  EXPECT_EQ(bruteforce::countOverlaps(model), 0u);
  EXPECT_EQ(bruteforce::countWallViolations(model), 0u);
  expectRadiiIn(model, 0.001, 0.002);

  std::set<std::int64_t> ids(model.particles.id.begin(), model.particles.id.end());
  EXPECT_EQ(ids.size(), 2500u);
  EXPECT_EQ(*ids.begin(), 0);
  EXPECT_EQ(*ids.rbegin(), 2499);
  EXPECT_EQ(model.nextId, 2500);
  for (std::size_t i = 0; i < model.particles.size(); ++i) {
    ASSERT_EQ(model.particles.velocity[i], dem::Vec3::Zero());
    ASSERT_GT(model.particles.mass[i], 0.0);
  }
}

TEST(BuildPack, RadiiAreTheUniformDrawsAskedFor)
{
  // Radii uniform in [a, b]: mean (a + b) / 2, standard deviation (b - a) / sqrt(12). A
  // placement that retried the radius on rejection would favour small particles.
  dem::Model model = boxModel(0.1, 0.1, 0.1);
  dem::buildPack(model, packOf(3000, 0.001, 0.002));
  double sum = 0.0;
  for (double r : model.particles.radius) {
    sum += r;
  }
  const double mean = sum / 3000.0;
  const double standardError = 0.001 / std::sqrt(12.0) / std::sqrt(3000.0); // 5.3e-6 m
  EXPECT_NEAR(mean, 0.0015, 5.0 * standardError);
}

TEST(BuildPack, NoOverlapAcrossPeriodicSeams)
{
  dem::Model model = boxModel(0.06, 0.05, 0.08);
  model.domain.periodic = { { true, true, false } };
  dem::buildPack(model, packOf(2500, 0.001, 0.002));
  ASSERT_EQ(model.particles.size(), 2500u);
  EXPECT_EQ(bruteforce::countOverlaps(model), 0u); // minimum image across the seams
  EXPECT_EQ(bruteforce::countWallViolations(model), 0u);
  std::size_t straddling = 0;
  const dem::Domain& d = model.domain;
  for (std::size_t i = 0; i < model.particles.size(); ++i) {
    const dem::Vec3& x = model.particles.position[i];
    const double r = model.particles.radius[i];
    for (int a = 0; a < 2; ++a) { // centres stay in [origin, upper) on periodic axes
      ASSERT_GE(x[a], d.origin[a]);
      ASSERT_LT(x[a], d.upper()[a]);
      straddling += (x[a] - r < d.origin[a] || x[a] + r > d.upper()[a]) ? 1 : 0;
    }
  }
  EXPECT_GT(straddling, 50u); // the seams really are crossed
}

TEST(BuildPack, TwoDimensionalSectionPlacesDiscsOnTheMidPlane)
{
  dem::Model model = boxModel(0.3, 0.15, 0.002);
  model.domain.section2D = true;
  model.domain.periodic = { { true, false, false } };
  model.gravity = dem::Vec3(0.0, -9.81, 0.0);
  model.material.density = 2500.0;
  const dem::PackReport report = dem::buildPack(model, packOf(1500, 0.001, 0.002));
  EXPECT_EQ(report.placed, 1500u);
  EXPECT_EQ(bruteforce::countOverlaps(model), 0u);
  EXPECT_EQ(bruteforce::countWallViolations(model), 0u);
  const double t = model.domain.size.z();
  for (std::size_t i = 0; i < model.particles.size(); ++i) {
    ASSERT_EQ(model.particles.position[i].z(), model.domain.midPlaneZ());
    // Disc through the slab: m = rho pi r^2 t, I = 1/2 m r^2 (solid cylinder about its axis).
    const double r = model.particles.radius[i];
    const double m = 2500.0 * kPi * r * r * t;
    ASSERT_NEAR(model.particles.mass[i], m, 1e-14 * m);
    ASSERT_NEAR(model.particles.inertia[i], 0.5 * m * r * r, 1e-14 * m * r * r);
  }
  EXPECT_NEAR(report.porosity, independentPorosity(model), 1e-12);
}

TEST(BuildPack, SameSeedSamePackDifferentSeedDifferentPack)
{
  dem::Model a = boxModel(0.05, 0.05, 0.05);
  dem::Model b = boxModel(0.05, 0.05, 0.05);
  dem::Model c = boxModel(0.05, 0.05, 0.05);
  const dem::PackParameters params = packOf(1000, 0.001, 0.0025, 123);
  dem::PackParameters other = params;
  other.randomSeed = 124;
  b.random.reseed(555); // the stream is reseeded from the parameters, whatever it was
  dem::buildPack(a, params);
  dem::buildPack(b, params);
  dem::buildPack(c, other);
  expectBitwiseEqual(a.particles, b.particles);
  EXPECT_TRUE(a.random == b.random);
  EXPECT_NE(a.particles.position[0], c.particles.position[0]);
  EXPECT_NE(a.particles.radius, c.particles.radius);

  // ... and the same commands afterwards give the same pack.
  for (dem::Model* m : { &a, &b }) {
    dem::PackParameters add = params;
    add.targetPorosity = 0.55;
    dem::addElements(*m, add);
    dem::growElements(*m);
    dem::addElements(*m, add);
  }
  expectBitwiseEqual(a.particles, b.particles);
}

TEST(BuildPack, SaturatesInsteadOfLoopingWhenTheBoxIsFull)
{
  dem::Model model = boxModel(0.02, 0.02, 0.02);
  const dem::PackReport report = dem::buildPack(model, packOf(100000, 0.002, 0.003));
  EXPECT_TRUE(report.saturated);
  EXPECT_LT(report.placed, 200u);
  EXPECT_EQ(model.particles.size(), report.placed);
  EXPECT_EQ(bruteforce::countOverlaps(model), 0u);
  EXPECT_NE(report.summary().find("saturated"), std::string::npos) << report.summary();
  EXPECT_NE(report.summary().find("of 100000"), std::string::npos) << report.summary();
}

TEST(BuildPack, ZeroElementsGivesAnEmptyPack)
{
  dem::Model model = boxModel(0.05, 0.05, 0.05);
  const dem::PackReport report = dem::buildPack(model, packOf(0, 0.001, 0.002));
  EXPECT_EQ(model.particles.size(), 0u);
  EXPECT_EQ(report.porosity, 1.0);
  EXPECT_FALSE(report.saturated);
}

// ---------------------------------------------------------------------------------------
// Fine zone

TEST(FineZone, FineRadiiInsideCoarseOutsideAndDenselyFilled)
{
  dem::Model model = boxModel(0.1, 0.1, 0.1);
  dem::PackParameters params = packOf(7000, 0.003, 0.004);
  dem::FineZone& zone = params.fineZone;
  zone.enabled = true;
  zone.origin = model.domain.origin + dem::Vec3(0.04, 0.0, 0.0); // a vertical slab, a "fault"
  zone.size = dem::Vec3(0.02, 0.1, 0.1);
  zone.minimumSize = 0.001;
  zone.maximumSize = 0.0015;
  const dem::PackReport report = dem::buildPack(model, params);
  EXPECT_EQ(report.placed, 7000u);
  EXPECT_EQ(bruteforce::countOverlaps(model), 0u);
  EXPECT_EQ(bruteforce::countWallViolations(model), 0u);

  const dem::Particles& p = model.particles;
  double fineSolid = 0.0, mainSolid = 0.0; // m^3, by where the centre lies
  std::size_t fineCount = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double x = p.position[i].x();
    const bool inside = x >= zone.origin.x() && x < zone.origin.x() + zone.size.x();
    const double volume = 4.0 / 3.0 * kPi * std::pow(p.radius[i], 3);
    if (inside) {
      ASSERT_GE(p.radius[i], 0.001);
      ASSERT_LE(p.radius[i], 0.0015);
      ASSERT_TRUE(p.flags[i] & dem::FlagFineZone);
      fineSolid += volume;
      ++fineCount;
    } else {
      ASSERT_GE(p.radius[i], 0.003);
      ASSERT_LE(p.radius[i], 0.004);
      ASSERT_FALSE(p.flags[i] & dem::FlagFineZone);
      mainSolid += volume;
    }
  }
  // Zones are drawn in proportion to the particles each holds at equal porosity, so the
  // solid fraction of the fault zone matches the rest of the box.
  const double fineFraction = fineSolid / (0.02 * 0.1 * 0.1);
  const double mainFraction = mainSolid / (0.08 * 0.1 * 0.1);
  EXPECT_GT(fineCount, 4000u);
  EXPECT_NEAR(fineFraction / mainFraction, 1.0, 0.25);
}

// ---------------------------------------------------------------------------------------
// Add Elements

TEST(AddElements, StopsAtTheFirstParticleThatReachesTheTarget)
{
  dem::Model model = boxModel(0.06, 0.06, 0.06);
  dem::PackParameters params = packOf(300, 0.001, 0.002);
  params.targetPorosity = 0.72;
  dem::buildPack(model, params);
  const std::size_t before = model.particles.size();
  const dem::PackReport report = dem::addElements(model, params);
  EXPECT_TRUE(report.targetReached);
  EXPECT_FALSE(report.saturated);
  EXPECT_EQ(model.particles.size(), before + report.placed);
  EXPECT_LE(report.porosity, 0.72);
  EXPECT_EQ(report.porosity, dem::currentPorosity(model));
  EXPECT_NEAR(report.porosity, independentPorosity(model), 1e-12);
  EXPECT_EQ(bruteforce::countOverlaps(model), 0u);
  EXPECT_EQ(bruteforce::countWallViolations(model), 0u);
  expectRadiiIn(model, 0.001, 0.002);

  // Without its last particle the pack was still above the target.
  dem::Model previous = model;
  previous.particles.position.pop_back();
  previous.particles.radius.pop_back();
  EXPECT_GT(independentPorosity(previous), 0.72);
  EXPECT_NE(report.summary().find("target porosity 0.720 reached"), std::string::npos)
    << report.summary();
}

TEST(AddElements, ReportsSaturationForAnUnreachableTarget)
{
  dem::Model model = boxModel(0.04, 0.04, 0.04);
  dem::PackParameters params = packOf(200, 0.001, 0.002);
  params.targetPorosity = 0.1; // far denser than random placement can reach
  dem::buildPack(model, params);
  const dem::PackReport report = dem::addElements(model, params);
  EXPECT_TRUE(report.saturated);
  EXPECT_FALSE(report.targetReached);
  EXPECT_GT(report.placed, 500u);
  EXPECT_EQ(bruteforce::countOverlaps(model), 0u);
  EXPECT_NE(report.summary().find("saturated"), std::string::npos) << report.summary();
}

TEST(AddElements, WorksOnParticlesThatCameFromElsewhere)
{
  dem::Model model = boxModel(0.05, 0.05, 0.05);
  model.domain.periodic = { { false, true, false } };
  std::int64_t id = 100;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      for (int k = 0; k < 3; ++k) {
        const dem::Vec3 x = model.domain.origin + dem::Vec3(0.01 + 0.015 * i, 0.015 * j, 0.01 + 0.015 * k);
        model.particles.append(x, 0.004, id++);
      }
    }
  }
  model.nextId = 0; // not kept up to date by whoever made these
  dem::PackParameters params = packOf(0, 0.001, 0.002);
  params.targetPorosity = 0.75;
  const dem::PackReport report = dem::addElements(model, params);
  EXPECT_TRUE(report.targetReached);
  EXPECT_GT(report.placed, 0u);
  EXPECT_EQ(bruteforce::countOverlaps(model), 0u);
  std::set<std::int64_t> ids(model.particles.id.begin(), model.particles.id.end());
  EXPECT_EQ(ids.size(), model.particles.size());
  EXPECT_GE(model.particles.id[27], 127);
}

// ---------------------------------------------------------------------------------------
// Grow Elements

TEST(GrowElements, DensifiesWithoutOverlapAndLeavesParticlesTouching)
{
  dem::Model model = boxModel(0.05, 0.05, 0.05);
  dem::buildPack(model, packOf(2400, 0.001, 0.002));
  for (std::size_t i = 0; i < model.particles.size(); i += 10) {
    model.particles.flags[i] |= dem::FlagFixed;
  }
  const std::vector<double> before = model.particles.radius;
  const dem::GrowReport report = dem::growElements(model);

  EXPECT_LT(report.porosityAfter, report.porosityBefore - 0.03);
  EXPECT_NEAR(report.porosityAfter, independentPorosity(model), 1e-12);
  EXPECT_EQ(bruteforce::countOverlaps(model), 0u);
  EXPECT_EQ(bruteforce::countWallViolations(model), 0u);
  EXPECT_GT(report.grown, 1500u);
  EXPECT_GT(report.meanRadiusGain, 0.0);

  std::size_t touching = 0;
  for (std::size_t i = 0; i < model.particles.size(); ++i) {
    const double r = model.particles.radius[i];
    if (model.particles.flags[i] & dem::FlagFixed) {
      ASSERT_EQ(r, before[i]); // fixed particles keep their size
      continue;
    }
    ASSERT_GE(r, before[i]);
    ASSERT_LE(r, 2.0 * before[i]); // at most its own radius per call
    // Each grown particle ends touching a neighbour or a wall, unless it doubled. "Touching"
    // allows for the margin the engine keeps against rounding (1e-12 of the coordinates).
    const double gap = bruteforce::nearestGap(model, i);
    ASSERT_GE(gap, 0.0);
    const double x = model.particles.position[i].cwiseAbs().maxCoeff();
    if (gap < 1e-10 * (x + r)) {
      ++touching;
    } else {
      ASSERT_EQ(r, 2.0 * before[i]) << "particle " << i << " has room left: gap " << gap;
    }
  }
  EXPECT_GT(touching, 1700u);

  // A second call has (almost) nothing left to fill.
  const dem::GrowReport again = dem::growElements(model);
  EXPECT_NEAR(again.porosityAfter, again.porosityBefore, 1e-3);
  EXPECT_EQ(bruteforce::countOverlaps(model), 0u);
}

TEST(GrowElements, PeriodicAnd2DPacksStayFreeOfOverlap)
{
  dem::Model periodic = boxModel(0.04, 0.04, 0.04);
  periodic.domain.periodic = { { true, true, true } };
  dem::buildPack(periodic, packOf(1000, 0.001, 0.002));
  dem::growElements(periodic);
  dem::growElements(periodic);
  EXPECT_EQ(bruteforce::countOverlaps(periodic), 0u);
  for (double r : periodic.particles.radius) {
    ASSERT_LE(r, 0.25 * 0.04); // radii stay within a quarter period
  }

  dem::Model section = boxModel(0.2, 0.1, 0.003);
  section.domain.section2D = true;
  section.gravity = dem::Vec3(0.0, -9.81, 0.0);
  dem::buildPack(section, packOf(800, 0.001, 0.002));
  const dem::GrowReport report = dem::growElements(section);
  EXPECT_LT(report.porosityAfter, report.porosityBefore);
  EXPECT_EQ(bruteforce::countOverlaps(section), 0u);
  EXPECT_EQ(bruteforce::countWallViolations(section), 0u);
  for (std::size_t i = 0; i < section.particles.size(); ++i) {
    ASSERT_EQ(section.particles.position[i].z(), section.domain.midPlaneZ());
    const double r = section.particles.radius[i];
    const double m = section.material.density * kPi * r * r * 0.003;
    ASSERT_NEAR(section.particles.mass[i], m, 1e-14 * m);
  }
}

TEST(GrowElements, AddThenGrowRoundsKeepThePackValid)
{
  dem::Model model = boxModel(0.05, 0.05, 0.05);
  model.domain.periodic = { { true, false, false } };
  dem::PackParameters params = packOf(1000, 0.001, 0.002);
  params.targetPorosity = 0.4;
  dem::buildPack(model, params);
  double porosity = dem::currentPorosity(model);
  for (int round = 0; round < 2; ++round) {
    const dem::PackReport add = dem::addElements(model, params);
    EXPECT_LE(add.porosity, porosity);
    EXPECT_EQ(bruteforce::countOverlaps(model), 0u);
    const dem::GrowReport grow = dem::growElements(model);
    EXPECT_LE(grow.porosityAfter, add.porosity);
    EXPECT_EQ(bruteforce::countOverlaps(model), 0u);
    EXPECT_EQ(bruteforce::countWallViolations(model), 0u);
    porosity = grow.porosityAfter;
  }
  EXPECT_LT(porosity, 0.65);
  const std::string line = dem::growElements(model).summary();
  EXPECT_NE(line.find("Grow Elements: grew"), std::string::npos) << line;
}

// ---------------------------------------------------------------------------------------
// Current Porosity

TEST(CurrentPorosity, MeasuredToTheTopOfTheHighestParticle)
{
  // Unit box, gravity -z, two spheres of radius 0.1 with tops at 0.3 and 0.6: the occupied
  // volume is 1 x 1 x 0.6, the solid 2 x 4/3 pi 0.1^3.
  dem::Model model;
  model.domain.size = dem::Vec3(1.0, 1.0, 1.0);
  model.particles.append(dem::Vec3(0.5, 0.5, 0.2), 0.1, 0);
  model.particles.append(dem::Vec3(0.2, 0.7, 0.5), 0.1, 1);
  const double solid = 2.0 * 4.0 / 3.0 * kPi * 0.001;
  EXPECT_NEAR(dem::currentPorosity(model), 1.0 - solid / 0.6, 1e-15);

  model.gravity = dem::Vec3(9.81, 0.0, 1.0); // up is -x: from x = 1 down to x = 0.1
  EXPECT_NEAR(dem::currentPorosity(model), 1.0 - solid / 0.9, 1e-15);

  model.gravity = dem::Vec3::Zero(); // no up: the whole box
  EXPECT_NEAR(dem::currentPorosity(model), 1.0 - solid, 1e-15);

  model.gravity = dem::Vec3(0.0, 0.0, -9.81);
  model.domain.periodic[2] = true; // a periodic pack has no top
  EXPECT_NEAR(dem::currentPorosity(model), 1.0 - solid, 1e-15);

  model.particles.clear();
  EXPECT_EQ(dem::currentPorosity(model), 1.0);
}

TEST(CurrentPorosity, TwoDimensionalIsAreaOverSectionArea)
{
  // 2D: disc areas over the section area (the slab thickness cancels); gravity -y.
  dem::Model model;
  model.domain.section2D = true;
  model.domain.size = dem::Vec3(2.0, 1.0, 0.01);
  model.gravity = dem::Vec3(0.0, -9.81, -5.0); // z is not a moving axis in 2D
  model.particles.append(dem::Vec3(0.5, 0.3, 0.005), 0.2, 0);
  EXPECT_NEAR(dem::currentPorosity(model), 1.0 - kPi * 0.04 / (2.0 * 0.5), 1e-15);
  EXPECT_NEAR(dem::currentPorosity(model), independentPorosity(model), 1e-15);
}

TEST(CurrentPorosity, MatchesTheIndependentFormulaOnPacks)
{
  for (bool periodicZ : { false, true }) {
    dem::Model model = boxModel(0.05, 0.04, 0.06);
    model.domain.periodic[2] = periodicZ;
    const dem::PackReport report = dem::buildPack(model, packOf(1200, 0.001, 0.002));
    EXPECT_NEAR(report.porosity, independentPorosity(model), 1e-12);
    EXPECT_NEAR(dem::currentPorosity(model), independentPorosity(model), 1e-12);
  }
}

// ---------------------------------------------------------------------------------------
// Validation: every bad input names the parameter and its value

TEST(PackValidation, SizeRange)
{
  const dem::Domain d;
  expectError(packOf(10, 0.005, 0.002), d,
              { "Minimum Size = 0.005 m must not exceed Maximum Size = 0.002 m" });
  expectError(packOf(10, 0.0, 0.002), d, { "Minimum Size = 0 m", "(0, inf)" });
  expectError(packOf(10, 0.001, -0.002), d, { "Maximum Size = -0.002 m" });
  expectError(packOf(10, std::nan(""), 0.002), d, { "Minimum Size = nan" });
}

TEST(PackValidation, BoxDimensionsAndOrigin)
{
  const dem::PackParameters params = packOf(10, 0.001, 0.002);
  dem::Domain d;
  d.size.x() = 0.0;
  expectError(params, d, { "X Dimension = 0 m" });
  d = dem::Domain{};
  d.size.y() = -0.1;
  expectError(params, d, { "Y Dimension = -0.1 m" });
  d = dem::Domain{};
  d.origin.z() = std::nan("");
  expectError(params, d, { "Origin Z = nan" });
}

TEST(PackValidation, TargetPorosityInTheOpenUnitInterval)
{
  for (double bad : { 0.0, 1.0, 1.2, -0.1 }) {
    dem::PackParameters params = packOf(10, 0.001, 0.002);
    params.targetPorosity = bad;
    expectError(params, dem::Domain{}, { "Target Porosity", dem::formatValue(bad).c_str(), "(0, 1)" });
  }
}

TEST(PackValidation, BoxThatCannotHoldOneParticle)
{
  dem::Domain d;
  d.size.x() = 0.001;
  expectError(packOf(10, 0.002, 0.003), d,
              { "X Dimension = 0.001 m cannot hold a particle of Maximum Size 0.003 m",
                "at least 2 x Maximum Size = 0.006 m" });
  // Issue 18 item 9: a box between 2 x Minimum Size and 2 x Maximum Size used to pass the
  // check and then place no particle at all (the large radii drawn never fit).
  d.size.x() = 0.005;
  expectError(packOf(10, 0.002, 0.003), d,
              { "X Dimension = 0.005 m cannot hold a particle of Maximum Size 0.003 m", "0.006 m" });
  // The slab of a 2D section is not a placement axis: a thin slab is fine.
  d = dem::Domain{};
  d.section2D = true;
  d.size.z() = 0.0001;
  EXPECT_NO_THROW(dem::validate(packOf(10, 0.002, 0.003), d));
}

TEST(PackValidation, PeriodicLengthOfAtLeastFourMaximumSizes)
{
  dem::Domain d;
  d.periodic[1] = true;
  d.size.y() = 0.01;
  expectError(packOf(10, 0.001, 0.003), d, { "Y Dimension = 0.01 m", "Periodic Y", "0.012 m" });
}

TEST(PackValidation, PeriodicZWith2DSection)
{
  dem::Domain d;
  d.section2D = true;
  d.periodic[2] = true;
  expectError(packOf(10, 0.001, 0.002), d, { "Periodic Z", "2D Section (XY)" });
}

TEST(PackValidation, MoreParticlesThanMemory)
{
  expectError(packOf(1000000000000000LL, 0.001, 0.002), dem::Domain{},
              { "Initial Elements = 1000000000000000", "GiB", "available" });
  expectError(packOf(-5, 0.001, 0.002), dem::Domain{}, { "Initial Elements = -5" });
}

TEST(PackValidation, FineZone)
{
  dem::PackParameters params = packOf(10, 0.002, 0.003);
  dem::FineZone& zone = params.fineZone;
  zone.enabled = true;
  zone.origin = dem::Vec3(0.04, 0.0, 0.0);
  zone.size = dem::Vec3(0.02, 0.1, 0.1);
  zone.minimumSize = 0.0005;
  zone.maximumSize = 0.001;
  const dem::Domain d;
  EXPECT_NO_THROW(dem::validate(params, d));

  dem::PackParameters bad = params;
  bad.fineZone.minimumSize = 0.002;
  expectError(bad, d, { "Fine Zone Minimum Size = 0.002 m must not exceed Fine Zone Maximum Size = 0.001 m" });
  bad = params;
  bad.fineZone.maximumSize = 0.0;
  expectError(bad, d, { "Fine Zone Maximum Size = 0 m" });
  bad = params;
  bad.fineZone.origin.x() = -0.01;
  expectError(bad, d, { "Fine Zone Origin X = -0.01 m", "[0, 0.1] m" });
  bad = params;
  bad.fineZone.size.y() = 0.0;
  expectError(bad, d, { "Fine Zone Y Dimension = 0 m" });
  bad = params;
  bad.fineZone.size.x() = 0.07;
  expectError(bad, d, { "Fine Zone X Dimension = 0.07 m", "reaches past the model box" });
  bad = params;
  bad.fineZone.origin.z() = 0.0998; // a sliver against the top wall
  bad.fineZone.size.z() = 0.0002;
  expectError(bad, d, { "Fine Zone Origin Z = 0.0998 m", "Fine Zone Z Dimension = 0.0002 m",
                        "no room for a fine particle" });
  // A disabled zone is not checked.
  bad.fineZone.enabled = false;
  EXPECT_NO_THROW(dem::validate(bad, d));
}

TEST(PackReports, SummariesAreOneInformativeLine)
{
  dem::PackReport add;
  add.command = "Add Elements";
  add.placed = 1234;
  add.attempts = 56789;
  add.targetPorosity = 0.4;
  add.porosity = 0.398;
  add.targetReached = true;
  EXPECT_EQ(add.summary(), "Add Elements: placed 1234 particles in 56789 attempts; target "
                           "porosity 0.400 reached (porosity 0.398).");
  add.targetReached = false;
  add.saturated = true;
  add.porosity = 0.612;
  EXPECT_EQ(add.summary(), "Add Elements: placed 1234 particles in 56789 attempts; placement "
                           "saturated at porosity 0.612 before reaching target 0.400.");
  dem::GrowReport grow;
  grow.particles = 10;
  grow.grown = 9;
  grow.meanRadiusGain = 1e-4;
  grow.porosityBefore = 0.7;
  grow.porosityAfter = 0.6;
  EXPECT_EQ(grow.summary(), "Grow Elements: grew 9 of 10 particles, mean radius gain 0.0001 m; "
                            "porosity 0.700 -> 0.600.");
  for (const std::string& line : { add.summary(), grow.summary() }) {
    EXPECT_EQ(line.find('\n'), std::string::npos);
  }
}
