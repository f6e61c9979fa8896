// The per-size-class cell grids: class boundaries, cell sizes, and overlap / nearest-surface
// queries checked against brute force over all stored particles (BruteForce.h).
#include "BruteForce.h"

#include "dem/Random.h"
#include "dem/SizeClassGrids.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <vector>

namespace {

struct Stored {
  std::vector<dem::Vec3> centre;
  std::vector<double> radius;
};

/// Random centres in the box (overlaps allowed) with radii log-uniform in [rMin, rMax].
Stored randomParticles(const dem::Domain& domain, std::size_t n, double rMin, double rMax,
                       dem::Random& random)
{
  Stored s;
  for (std::size_t i = 0; i < n; ++i) {
    dem::Vec3 x;
    for (int a = 0; a < 3; ++a) {
      x[a] = random.uniform(domain.origin[a], domain.upper()[a]);
    }
    if (domain.section2D) {
      x.z() = domain.midPlaneZ();
    }
    s.centre.push_back(x);
    s.radius.push_back(rMin * std::pow(rMax / rMin, random.uniform()));
  }
  return s;
}

struct BruteNearest {
  double gap;
  std::size_t key;
};

BruteNearest bruteNearest(const dem::Domain& domain, const Stored& s, const dem::Vec3& x, double r,
                          double reach, std::size_t ignore)
{
  BruteNearest best{ reach, dem::SizeClassGrids::npos };
  for (std::size_t j = 0; j < s.centre.size(); ++j) {
    if (j == ignore) {
      continue;
    }
    const double gap = bruteforce::separation(domain, x, s.centre[j]).norm() - r - s.radius[j];
    if (gap < best.gap) {
      best = { gap, j };
    }
  }
  return best;
}

bool bruteOverlaps(const dem::Domain& domain, const Stored& s, const dem::Vec3& x, double r)
{
  for (std::size_t j = 0; j < s.centre.size(); ++j) {
    if (bruteforce::separation(domain, x, s.centre[j]).norm() < r + s.radius[j]) {
      return true;
    }
  }
  return false;
}

/// Stores random particles and compares many random queries with brute force.
void checkAgainstBruteForce(const dem::Domain& domain, double rMin, double rMax,
                            std::size_t maxCells = dem::SizeClassGrids::kDefaultMaxCellsPerClass,
                            std::size_t n = 1500)
{
  dem::Random random(99);
  const Stored s = randomParticles(domain, n, rMin, rMax, random);
  dem::SizeClassGrids grids(domain, rMin, rMax, maxCells);
  for (std::size_t i = 0; i < s.centre.size(); ++i) {
    ASSERT_EQ(grids.insert(s.centre[i], s.radius[i]), i);
  }
  std::size_t overlapping = 0, found = 0;
  for (int q = 0; q < 1500; ++q) {
    dem::Vec3 x;
    for (int a = 0; a < 3; ++a) { // a little outside the box too, on every axis
      const double margin = 0.05 * domain.size[a];
      x[a] = random.uniform(domain.origin[a] - margin, domain.upper()[a] + margin);
    }
    if (domain.section2D) {
      x.z() = domain.midPlaneZ();
    }
    const double r = rMin * std::pow(rMax / rMin, random.uniform());
    const double reach = random.uniform(0.0, 3.0 * rMax);
    const std::size_t ignore = (q % 3 == 0) ? static_cast<std::size_t>(q) % n
                                            : dem::SizeClassGrids::npos;

    const BruteNearest expected = bruteNearest(domain, s, x, r, reach, ignore);
    const dem::SizeClassGrids::Nearest got = grids.nearest(x, r, reach, ignore);
    ASSERT_EQ(got.key, expected.key) << "query " << q;
    ASSERT_NEAR(got.gap, expected.gap, 1e-12) << "query " << q;
    if (got.key != dem::SizeClassGrids::npos) {
      ASSERT_EQ(got.radius, s.radius[got.key]);
      ++found;
    }
    // Every particle within the reach, each exactly once.
    std::vector<std::size_t> keys;
    grids.neighboursWithin(x, r, reach, ignore, keys);
    std::vector<std::size_t> expectedKeys;
    for (std::size_t j = 0; j < n; ++j) {
      if (j != ignore &&
          bruteforce::separation(domain, x, s.centre[j]).norm() - r - s.radius[j] < reach) {
        expectedKeys.push_back(j);
      }
    }
    std::sort(keys.begin(), keys.end());
    ASSERT_EQ(keys, expectedKeys) << "query " << q;

    const bool overlaps = bruteOverlaps(domain, s, x, r);
    ASSERT_EQ(grids.overlapsAny(x, r), overlaps) << "query " << q;
    overlapping += overlaps ? 1 : 0;
  }
  // The random data must exercise both answers.
  EXPECT_GT(overlapping, 0u);
  EXPECT_LT(overlapping, 1500u);
  EXPECT_GT(found, 0u);
}

dem::Domain box(double lx, double ly, double lz)
{
  dem::Domain d;
  d.origin = dem::Vec3(-0.3, 1.7, 10.0);
  d.size = dem::Vec3(lx, ly, lz);
  return d;
}

} // namespace

TEST(SizeClassGrids, ClassPerDoublingOfRadiusUpToFour)
{
  const dem::SizeClassGrids grids(box(0.1, 0.1, 0.1), 0.001, 0.05);
  EXPECT_EQ(grids.sizeClass(0.001), 0);
  EXPECT_EQ(grids.sizeClass(0.00199), 0);
  EXPECT_EQ(grids.sizeClass(0.002), 1);
  EXPECT_EQ(grids.sizeClass(0.00399), 1);
  EXPECT_EQ(grids.sizeClass(0.004), 2);
  EXPECT_EQ(grids.sizeClass(0.008), 3);
  EXPECT_EQ(grids.sizeClass(0.05), 3);
}

TEST(SizeClassGrids, CellEdgeIsAboutOneDiameterOfTheClassLargest)
{
  // Class k holds radii below rmin 2^(k+1), so its cells are about 2 rmin 2^(k+1) wide
  // (at least that, since whole cells tile the box).
  const double rMin = 0.0005;
  const dem::SizeClassGrids grids(box(0.2, 0.2, 0.2), rMin, 0.02);
  for (int k = 0; k < 3; ++k) {
    const double nominal = 2.0 * rMin * std::ldexp(1.0, k + 1);
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(grids.cellEdge(k, a), nominal);
      EXPECT_LT(grids.cellEdge(k, a), 1.1 * nominal);
    }
  }
  EXPECT_GE(grids.cellEdge(3, 0), 2.0 * 0.02); // the last class: the largest radius
}

TEST(SizeClassGrids, CellCountIsCapped)
{
  const std::size_t cap = 5000;
  const dem::SizeClassGrids grids(box(10.0, 10.0, 10.0), 0.001, 0.002, cap);
  for (int k = 0; k < dem::SizeClassGrids::kMaxClasses; ++k) {
    const auto n = grids.cellCounts(k);
    EXPECT_LE(static_cast<std::size_t>(n[0] * n[1] * n[2]), cap);
  }
}

TEST(SizeClassGrids, NearestAndOverlapMatchBruteForceInAWalledBox)
{
  checkAgainstBruteForce(box(0.1, 0.08, 0.06), 0.001, 0.004);
}

TEST(SizeClassGrids, NearestAndOverlapMatchBruteForceWithATenToOneRadiusRange)
{
  checkAgainstBruteForce(box(0.2, 0.15, 0.1), 0.0005, 0.005);
}

TEST(SizeClassGrids, NearestAndOverlapMatchBruteForceAcrossPeriodicSeams)
{
  dem::Domain d = box(0.1, 0.08, 0.06);
  d.periodic = { { true, true, true } };
  checkAgainstBruteForce(d, 0.0005, 0.005);
  d.periodic = { { true, false, true } };
  checkAgainstBruteForce(d, 0.001, 0.004);
}

TEST(SizeClassGrids, PeriodicAxisWithFewCellsVisitsEachCellOnce)
{
  // A period of 4 maximum radii holds only two cells of the largest class; a query reach
  // of several radii spans the whole period. Every particle must still be seen once, with
  // its minimum image.
  dem::Domain d = box(0.02, 0.02, 0.1);
  d.periodic = { { true, true, false } };
  checkAgainstBruteForce(d, 0.0025, 0.005, dem::SizeClassGrids::kDefaultMaxCellsPerClass, 200);
}

TEST(SizeClassGrids, TwoDimensionalSectionIgnoresZ)
{
  dem::Domain d = box(0.2, 0.1, 0.004);
  d.section2D = true;
  d.periodic = { { true, false, false } };
  checkAgainstBruteForce(d, 0.001, 0.008);
}

TEST(SizeClassGrids, CappedCellsAreStillCorrect)
{
  checkAgainstBruteForce(box(0.1, 0.08, 0.06), 0.0005, 0.004, 64);
}

TEST(SizeClassGrids, GrowingARadiusWidensTheSearch)
{
  const dem::Domain d = box(0.1, 0.1, 0.1);
  dem::Random random(3);
  Stored s = randomParticles(d, 800, 0.001, 0.002, random);
  dem::SizeClassGrids grids(d, 0.001, 0.002);
  for (std::size_t i = 0; i < s.centre.size(); ++i) {
    grids.insert(s.centre[i], s.radius[i]);
  }
  // Grow some particles well past their class bound (as Grow Elements does).
  for (std::size_t i = 0; i < s.centre.size(); i += 7) {
    s.radius[i] *= 3.5;
    grids.setRadius(i, s.radius[i]);
  }
  EXPECT_GE(grids.classMaxRadius(0), 0.0035);
  for (int q = 0; q < 500; ++q) {
    const dem::Vec3 x(random.uniform(-0.3, -0.2), random.uniform(1.7, 1.8), random.uniform(10, 10.1));
    const double r = random.uniform(0.001, 0.002);
    const BruteNearest expected = bruteNearest(d, s, x, r, 0.01, dem::SizeClassGrids::npos);
    const auto got = grids.nearest(x, r, 0.01);
    ASSERT_EQ(got.key, expected.key);
    ASSERT_NEAR(got.gap, expected.gap, 1e-12);
    ASSERT_EQ(grids.overlapsAny(x, r), bruteOverlaps(d, s, x, r));
  }
}

TEST(SizeClassGrids, InsertAllKeysParticlesBySlot)
{
  dem::Model model;
  model.particles.append(dem::Vec3(0.01, 0.01, 0.01), 0.002, 5);
  model.particles.append(dem::Vec3(0.02, 0.01, 0.01), 0.003, 6);
  model.particles.append(dem::Vec3(0.09, 0.09, 0.09), 0.001, 7);
  dem::SizeClassGrids grids(model.domain, 0.001, 0.003);
  grids.insertAll(model.particles);
  EXPECT_EQ(grids.size(), 3u);
  const auto near = grids.nearest(model.particles.position[0], 0.002, 1.0, 0);
  EXPECT_EQ(near.key, 1u);
  EXPECT_NEAR(near.gap, 0.01 - 0.005, 1e-15);
  EXPECT_TRUE(grids.overlapsAny(dem::Vec3(0.0115, 0.01, 0.01), 0.0001));
  EXPECT_FALSE(grids.overlapsAny(dem::Vec3(0.05, 0.05, 0.05), 0.01));
}

TEST(SizeClassGrids, SeparationUsesTheMinimumImage)
{
  dem::Domain d = box(1.0, 1.0, 1.0);
  d.periodic = { { true, false, false } };
  const dem::SizeClassGrids grids(d, 0.01, 0.02);
  const dem::Vec3 a(-0.25, 2.0, 10.5), b(0.65, 2.1, 10.5);
  const dem::Vec3 s = grids.separation(a, b);
  EXPECT_NEAR(s.x(), -0.1, 1e-12);
  EXPECT_NEAR(s.y(), 0.1, 1e-12);
}
