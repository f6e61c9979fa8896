// Seeing inside a model (Documentation/Sections.md): exact sphere-box volumes
// (dem/SphereBoxVolume.h) against closed forms (cap, octant) and an independent quadrature; plane
// sections (dem/Section.h): circles of radius sqrt(R^2 - d^2) at the projected centres,
// uncut spheres absent, crossing bonds exactly those whose segment crosses, broken-bond
// traces; voxel models (dem/Voxelize.h): solid volume sums to the particles' volume, a
// sphere split across 8 voxels matches the analytic split, damage per voxel equals an
// independent count, the stress average is the particles', fractures rasterise to their
// area; bad input is named.
#include "dem/BondGeometry.h"
#include "dem/Cement.h"
#include "dem/Errors.h"
#include "dem/Fractures.h"
#include "dem/SphereBoxVolume.h"
#include "dem/ParticleStress.h"
#include "dem/Random.h"
#include "dem/Section.h"
#include "dem/Voxelize.h"
#include "Specimens.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace dem;
using namespace dem::testing;

namespace {

constexpr double Pi = 3.14159265358979323846;

/// Volume of the unit ball with x > a, y > b, z > c by the midpoint rule on an n x n grid
/// of columns over the disc (independent of dem/SphereBoxVolume.h).
double cornerByQuadrature(double a, double b, double c, int n)
{
  const double x0 = std::max(a, -1.0);
  const double y0 = std::max(b, -1.0);
  const double hx = (1.0 - x0) / n;
  const double hy = (1.0 - y0) / n;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = x0 + (i + 0.5) * hx;
    for (int j = 0; j < n; ++j) {
      const double y = y0 + (j + 0.5) * hy;
      const double r2 = 1.0 - x * x - y * y;
      if (r2 > 0.0) {
        const double top = std::sqrt(r2);
        sum += std::max(0.0, top - std::max(c, -top));
      }
    }
  }
  return sum * hx * hy;
}

double cap(double R, double h) { return Pi * h * h * (3.0 * R - h) / 3.0; }

/// A cemented pack (no gravity) with a third of its bonds broken by hand, in every mode.
Model cementedPack(bool periodicX = false)
{
  Model m = specimen(300, 0.01, 0.0006, 0.0009, 9);
  m.domain.periodic[0] = periodicX;
  CementParameters c = testCement();
  c.gapTolerance = 0.5; // geometry tests: many bonds
  cement(m, c);
  for (std::size_t k = 0; k < m.bonds.size(); k += 3) {
    m.bonds.markBroken(k, static_cast<BondFailure>(1 + (k / 3) % 3), 0.0, Vec3::Zero(), Vec3::UnitZ());
  }
  return m;
}

/// Particles given by hand (no bonds).
Model spheres(const std::vector<Vec3>& x, const std::vector<double>& r)
{
  Model m;
  m.domain.origin = Vec3(-1, -1, -1);
  m.domain.size = Vec3(2, 2, 2);
  m.gravity.setZero();
  for (std::size_t i = 0; i < x.size(); ++i) {
    m.particles.append(x[i], r[i], static_cast<std::int64_t>(i));
  }
  m.nextId = static_cast<std::int64_t>(x.size());
  updateMassProperties(m);
  return m;
}

} // namespace

// ---------------------------------------------------------------------------------------
// Exact overlap volumes

TEST(SphereBoxVolume, BallCornerMatchesClosedFormsAndQuadrature)
{
  EXPECT_NEAR(unitBallCornerVolume(0, 0, 0), Pi / 6.0, 1e-15) << "an octant";
  EXPECT_NEAR(unitBallCornerVolume(-1, -1, -1), 4.0 * Pi / 3.0, 1e-14) << "the ball";
  EXPECT_EQ(unitBallCornerVolume(0.6, 0.6, 0.6), 0.0) << "corner outside";
  for (double h : { -0.7, -0.2, 0.0, 0.3, 0.9 }) {
    EXPECT_NEAR(unitBallCornerVolume(-1, -1, h), cap(1.0, 1.0 - h), 1e-14) << "cap above z = " << h;
    EXPECT_NEAR(unitBallCornerVolume(0, 0, h), cap(1.0, 1.0 - h) / 4.0, 1e-14) << "quarter cap";
  }
  Random rng(4);
  for (int k = 0; k < 12; ++k) {
    const double a = 1.6 * rng.uniform() - 0.8;
    const double b = 1.6 * rng.uniform() - 0.8;
    const double c = 1.6 * rng.uniform() - 0.8;
    EXPECT_NEAR(unitBallCornerVolume(a, b, c), cornerByQuadrature(a, b, c, 1500), 2e-5)
      << "corner (" << a << ", " << b << ", " << c << ")";
  }
  // The disc corner: quarter disc and half-plane segments.
  EXPECT_NEAR(unitDiscCornerArea(0, 0), Pi / 4.0, 1e-15);
  EXPECT_NEAR(unitDiscCornerArea(-1, 0.5), std::acos(0.5) - 0.5 * std::sqrt(0.75), 1e-15);
  // A rectangle inside the disc (corners at distance 0.5): its own area, 0.6 x 0.8.
  EXPECT_NEAR(unitDiscCornerArea(-0.3, -0.4) - unitDiscCornerArea(0.3, -0.4) - unitDiscCornerArea(-0.3, 0.4) +
                unitDiscCornerArea(0.3, 0.4),
              0.48, 1e-15);
}

// A sphere centred on a grid node is split into eight equal parts; offset along Z by e,
// the four upper parts are each a quarter of the cap of height R - e; offset on all axes,
// each part matches the quadrature and the eight add up to the sphere.
TEST(SphereBoxVolume, SphereSplitAcrossEightBoxesMatchesTheAnalyticSplit)
{
  const double R = 0.003;
  const Vec3 c(0.01, -0.02, 0.005);
  const double V = 4.0 / 3.0 * Pi * R * R * R;
  auto part = [&](const Vec3& node, int octant) {
    Vec3 lo;
    Vec3 hi;
    for (int k = 0; k < 3; ++k) {
      const bool up = (octant >> k) & 1;
      lo[k] = up ? node[k] : node[k] - 2 * R;
      hi[k] = up ? node[k] + 2 * R : node[k];
    }
    return sphereBoxVolume(c, R, lo, hi);
  };
  for (int o = 0; o < 8; ++o) {
    EXPECT_NEAR(part(c, o), V / 8.0, 1e-12 * V) << "octant " << o;
  }
  const double e = 0.4 * R;
  for (int o = 0; o < 8; ++o) {
    const double expected = (o & 4) ? cap(R, R - e) / 4.0 : (V - cap(R, R - e)) / 4.0;
    EXPECT_NEAR(part(c + Vec3(0, 0, e), o), expected, 1e-12 * V) << "octant " << o << " offset along Z";
  }
  const Vec3 offset(0.3 * R, -0.55 * R, 0.1 * R);
  double sum = 0.0;
  for (int o = 0; o < 8; ++o) {
    const double got = part(c + offset, o);
    Vec3 a;
    for (int k = 0; k < 3; ++k) { // the part as a corner of the unit ball (mirrored to x > a)
      a[k] = ((o >> k) & 1) ? offset[k] / R : -offset[k] / R;
    }
    EXPECT_NEAR(got, cornerByQuadrature(a.x(), a.y(), a.z(), 1500) * R * R * R, 2e-5 * R * R * R) << "octant " << o;
    sum += got;
  }
  EXPECT_NEAR(sum, V, 1e-13 * V) << "the parts add up to the sphere";
  // A disc split across four rectangles.
  const double A = Pi * R * R;
  EXPECT_NEAR(discRectangleArea(0, 0, R, 0, 0, R, R), A / 4.0, 1e-15);
  EXPECT_NEAR(discRectangleArea(0, 0, R, -R, -R, R, R), A, 1e-15 * 1e6);
  EXPECT_EQ(sphereBoxVolume(c, R, c + Vec3(R, 0, 0), c + Vec3(2 * R, R, R)), 0.0) << "box beyond the sphere";
}

// ---------------------------------------------------------------------------------------
// Sections

// Every sphere the plane cuts gives one circle of radius sqrt(R^2 - d^2) at its centre
// minus d n; every other sphere is absent. All particles checked, for the three guide
// sections and an oblique plane.
TEST(Section, CirclesHaveTheAnalyticRadiusAndCentre)
{
  Random rng(12);
  std::vector<Vec3> x;
  std::vector<double> r;
  for (int i = 0; i < 400; ++i) {
    x.emplace_back(1.8 * rng.uniform() - 0.9, 1.8 * rng.uniform() - 0.9, 1.8 * rng.uniform() - 0.9);
    r.push_back(0.02 + 0.08 * rng.uniform());
  }
  const Model m = spheres(x, r);
  std::vector<SectionParameters> planes(4);
  planes[0].orientation = SectionOrientation::XY;
  planes[0].origin = Vec3(0.1, 0.2, 0.05);
  planes[1].orientation = SectionOrientation::XZ;
  planes[1].origin = Vec3(0.0, -0.3, 0.0);
  planes[2].orientation = SectionOrientation::YZ;
  planes[2].origin = Vec3(0.41, 0.0, 0.0);
  planes[3].orientation = SectionOrientation::Custom;
  planes[3].origin = Vec3(0.1, -0.1, 0.2);
  planes[3].normal = Vec3(1.0, -2.0, 0.5); // not unit: normalised
  const Vec3 axes[3] = { Vec3::UnitZ(), Vec3::UnitY(), Vec3::UnitX() };
  for (std::size_t p = 0; p < planes.size(); ++p) {
    const ModelSection s = sectionModel(m, planes[p]);
    const Vec3 n = p < 3 ? axes[p] : Vec3(1.0, -2.0, 0.5).normalized();
    EXPECT_NEAR((s.normal - n).norm(), 0.0, 1e-15);
    EXPECT_NEAR(s.u.dot(n), 0.0, 1e-15);
    EXPECT_NEAR(s.v.dot(n), 0.0, 1e-15);
    std::vector<int> found(x.size(), 0);
    for (const SectionCircle& c : s.circles) {
      ++found[c.particle];
    }
    std::size_t cut = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double d = (x[i] - planes[p].origin).dot(n);
      if (std::abs(d) >= r[i]) {
        EXPECT_EQ(found[i], 0) << "sphere " << i << " is not cut by plane " << p;
        continue;
      }
      ++cut;
      ASSERT_EQ(found[i], 1) << "sphere " << i << " is cut once by plane " << p;
    }
    EXPECT_EQ(s.circles.size(), cut);
    EXPECT_GT(cut, 10u);
    for (const SectionCircle& c : s.circles) {
      const std::size_t i = c.particle;
      const double d = (x[i] - planes[p].origin).dot(n);
      EXPECT_NEAR(c.radius, std::sqrt(r[i] * r[i] - d * d), 1e-15) << "sphere " << i;
      EXPECT_NEAR((c.centre - (x[i] - d * n)).norm(), 0.0, 1e-15) << "sphere " << i;
      EXPECT_NEAR((c.centre - planes[p].origin).dot(n), 0.0, 1e-15) << "centre on the plane";
      EXPECT_NEAR(c.distance, d, 1e-15);
    }
  }
}

// The intact bonds in the output are exactly those whose segment (A to A + branch)
// crosses the plane, each at a point of the plane on its segment; the broken bonds
// traced are exactly those whose contact point lies within half a mean diameter, with
// semi-axes Rb and Rb |m.n|.
TEST(Section, CrossingBondsAndBrokenBondTraces)
{
  for (bool periodic : { false, true }) {
    const Model m = cementedPack(periodic);
    ASSERT_GT(m.bonds.size(), 200u);
    SectionParameters params;
    params.orientation = SectionOrientation::Custom;
    params.origin = Vec3(0.005, 0.0051, 0.0049);
    params.normal = Vec3(0.3, 0.2, 1.0);
    const ModelSection s = sectionModel(m, params);
    const Vec3 n = params.normal.normalized();
    const BondGeometry g = bondGeometry(m);
    std::vector<int> crossing(m.bonds.size(), 0);
    for (const BondCrossing& c : s.crossings) {
      ++crossing[c.bond];
      EXPECT_NEAR((c.point - params.origin).dot(n), 0.0, 1e-15) << "on the plane";
      const Vec3 a = g.start[c.bond];
      const Vec3 b = g.end(c.bond);
      EXPECT_NEAR(((c.point - a).cross(b - a)).norm(), 0.0, 1e-15) << "on the segment";
      EXPECT_LE((c.point - a).dot(b - a), (b - a).squaredNorm() * (1 + 1e-12));
      EXPECT_GE((c.point - a).dot(b - a), -1e-18);
    }
    std::size_t expected = 0;
    for (std::size_t k = 0; k < m.bonds.size(); ++k) {
      // Independent: the segment x(t) = a + t (b - a), t in [0, 1], meets the plane when
      // the line's parameter at the plane lies in [0, 1].
      const Vec3 a = g.start[k];
      const Vec3 b = g.end(k);
      const double denominator = (b - a).dot(n);
      const double t = denominator != 0.0 ? (params.origin - a).dot(n) / denominator : -1.0;
      const bool crosses = !m.bonds.broken(k) && t >= 0.0 && t <= 1.0;
      expected += crosses ? 1 : 0;
      EXPECT_EQ(crossing[k], crosses ? 1 : 0) << "bond " << k << " (t = " << t << ")";
    }
    EXPECT_EQ(s.crossings.size(), expected);
    EXPECT_GT(expected, 5u);

    const double half = 0.5 * meanParticleDiameter(m);
    EXPECT_NEAR(s.traceDistance, half, 1e-18);
    std::vector<int> traced(m.bonds.size(), 0);
    for (const CrackTrace& t : s.traces) {
      ++traced[t.bond];
      const Vec3 mAxis = g.branch[t.bond].normalized();
      EXPECT_NEAR(t.major.norm(), m.bonds.radius[t.bond], 1e-15);
      EXPECT_NEAR(t.minor.norm(), m.bonds.radius[t.bond] * std::abs(mAxis.dot(n)), 1e-15);
      EXPECT_NEAR(t.major.dot(n), 0.0, 1e-15);
      EXPECT_NEAR(t.minor.dot(n), 0.0, 1e-15);
      EXPECT_NEAR(t.major.dot(mAxis), 0.0, 1e-15) << "the major axis lies in the crack";
    }
    std::size_t near = 0;
    for (std::size_t k = 0; k < m.bonds.size(); ++k) {
      const bool expectTrace = m.bonds.broken(k) && std::abs((g.contact[k] - params.origin).dot(n)) <= half;
      near += expectTrace ? 1 : 0;
      EXPECT_EQ(traced[k], expectTrace ? 1 : 0) << "bond " << k;
    }
    EXPECT_GT(near, 3u);
  }
}

TEST(Section, PlaneMissingTheModelIsEmptyWithAMessage)
{
  const Model m = cementedPack();
  SectionParameters params;
  params.origin = Vec3(0.0, 0.0, 1.0); // far above the box
  const ModelSection s = sectionModel(m, params);
  EXPECT_TRUE(s.circles.empty() && s.crossings.empty() && s.traces.empty());
  EXPECT_NE(s.message.find("misses the model"), std::string::npos) << s.message;
}

TEST(Section, BadPlaneIsNamed)
{
  const Model m = cementedPack();
  SectionParameters params;
  params.orientation = SectionOrientation::Custom;
  params.normal = Vec3::Zero();
  try {
    sectionModel(m, params);
    FAIL() << "a zero normal is rejected";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("Normal = (0, 0, 0)"), std::string::npos) << e.what();
  }
  params.normal = Vec3::UnitX();
  params.traceDistance = -1.0;
  EXPECT_THROW(sectionModel(m, params), InputError);
  params.traceDistance = 0.0;
  params.origin.x() = std::nan("");
  EXPECT_THROW(sectionModel(m, params), InputError);
}

// A 2D section model: every disc, at its centre with its radius, in the model plane; the
// plane settings do not apply (the message says so).
TEST(Section, TwoDimensionalModelIsItsOwnSection)
{
  Model m;
  m.domain.section2D = true;
  m.domain.size = Vec3(0.02, 0.02, 0.001);
  for (int i = 0; i < 5; ++i) {
    m.particles.append(Vec3(0.003 + 0.003 * i, 0.01, m.domain.midPlaneZ()), 0.0012, i);
  }
  m.nextId = 5;
  updateMassProperties(m);
  SectionParameters params;
  params.orientation = SectionOrientation::YZ;
  const ModelSection s = sectionModel(m, params);
  ASSERT_EQ(s.circles.size(), 5u);
  EXPECT_TRUE(s.modelPlane);
  for (const SectionCircle& c : s.circles) {
    EXPECT_EQ(c.radius, 0.0012);
    EXPECT_EQ(c.centre, m.particles.position[c.particle]);
  }
  EXPECT_EQ(s.normal, Vec3::UnitZ());
  EXPECT_NE(s.message.find("2D section model is its own section"), std::string::npos) << s.message;
}

// ---------------------------------------------------------------------------------------
// Voxel models

// A sphere centred on the middle node of a 2 x 2 x 2 grid fills each voxel with an
// eighth of its volume; total solid volume = the particle's.
TEST(Voxelize, SingleSphereSplitAcrossEightVoxelsMatchesTheAnalyticSplit)
{
  const double R = 0.004;
  const Model m = spheres({ Vec3(0.1, -0.2, 0.3) }, { R });
  VoxelParameters params;
  params.sizing = VoxelSizing::NumberOfVoxels;
  params.numberOfVoxels = 2;
  params.margin = 0.0;
  const VoxelModel vox = voxelize(m, params, particleStresses(m), nullptr);
  ASSERT_EQ(vox.grid.count(), 8u);
  const double V = 4.0 / 3.0 * Pi * R * R * R;
  for (std::size_t v = 0; v < 8; ++v) {
    EXPECT_NEAR(vox.solidFraction[v] * vox.grid.voxelVolume(), V / 8.0, 1e-12 * V) << "voxel " << v;
    EXPECT_NEAR(vox.solidFraction[v], Pi / 6.0, 1e-12) << "an eighth of the sphere in a voxel of edge R";
  }
  // Voxels of 1.5 R: the grid (2 x 2 x 2, centred on the sphere's extent) still has its
  // middle node at the sphere's centre.
  params.sizing = VoxelSizing::VoxelSize;
  params.voxelSize = 1.5 * R;
  const VoxelModel vox2 = voxelize(m, params, particleStresses(m), nullptr);
  ASSERT_EQ(vox2.grid.count(), 8u);
  for (std::size_t v = 0; v < 8; ++v) {
    EXPECT_NEAR(vox2.solidFraction[v] * vox2.grid.voxelVolume(), V / 8.0, 1e-12 * V);
  }
}

// Over a pack of 300 spheres (and the same pack periodic in X, and a 2D section model)
// the voxels' solid volume adds up to the particles' total volume (the issue's bar 0.1 %;
// the closed form gives rounding).
TEST(Voxelize, SolidFractionSumsToTheParticleVolume)
{
  for (int variant = 0; variant < 3; ++variant) {
    Model m = variant == 1 ? cementedPack(true) : specimen(300, 0.01, 0.0006, 0.0009, 9);
    if (variant == 2) { // a 2D section: discs through a slab
      m = Model();
      m.domain.section2D = true;
      m.domain.size = Vec3(0.02, 0.02, 0.001);
      Random rng(3);
      for (int i = 0; i < 64; ++i) { // an 8 x 8 lattice of discs of random radius, not touching
        m.particles.append(Vec3(0.00125 + 0.0025 * (i % 8), 0.00125 + 0.0025 * (i / 8), 0.0005),
                           0.0004 + 0.0008 * rng.uniform(), i);
      }
      m.nextId = 64;
      updateMassProperties(m);
    }
    double total = 0.0;
    for (double r : m.particles.radius) {
      total += particleVolume(m.domain, r);
    }
    VoxelParameters params;
    params.sizing = VoxelSizing::VoxelSize;
    params.voxelSize = 0.00071;
    params.margin = variant * 0.1; // a margin adds empty voxels only
    const VoxelModel vox = voxelize(m, params, std::vector<StressTensor>(m.particles.size()), nullptr);
    double sum = 0.0;
    for (double f : vox.solidFraction) {
      EXPECT_GE(f, 0.0);
      EXPECT_LE(f, 1.0 + 1e-12) << "overlaps aside, a voxel is at most full";
      sum += f * vox.grid.voxelVolume();
    }
    EXPECT_NEAR(sum, total, 1e-10 * total) << "variant " << variant;
    EXPECT_NEAR(vox.solidVolume, total, 1e-10 * total);
    EXPECT_NEAR(vox.particleVolume, total, 1e-12 * total);
    if (variant == 1) {
      EXPECT_TRUE(vox.grid.wraps[0]);
      EXPECT_NEAR(vox.grid.dimensions[0] * vox.grid.spacing.x(), m.domain.size.x(), 1e-15);
    }
    if (variant == 2) {
      EXPECT_EQ(vox.grid.dimensions[2], 1);
      EXPECT_EQ(vox.grid.spacing.z(), m.domain.slabThickness());
    }
  }
}

// Bonds per voxel, broken bonds per voxel and the damage, against a count that tests each
// bond's midpoint against each voxel's bounds.
TEST(Voxelize, DamagePerVoxelEqualsAnIndependentCount)
{
  const Model m = cementedPack();
  VoxelParameters params;
  params.numberOfVoxels = 6;
  const VoxelModel vox = voxelize(m, params, particleStresses(m), nullptr);
  const VoxelGrid& g = vox.grid;
  const BondGeometry geometry = bondGeometry(m);
  std::size_t totalBroken = 0;
  for (int k = 0; k < g.dimensions[2]; ++k) {
    for (int j = 0; j < g.dimensions[1]; ++j) {
      for (int i = 0; i < g.dimensions[0]; ++i) {
        const Vec3 lo = g.origin + Vec3(i * g.spacing.x(), j * g.spacing.y(), k * g.spacing.z());
        const Vec3 hi = lo + g.spacing;
        int bonds = 0;
        int broken = 0;
        for (std::size_t b = 0; b < m.bonds.size(); ++b) {
          const Vec3 mid = geometry.start[b] + 0.5 * geometry.branch[b];
          if ((mid.array() >= lo.array()).all() && (mid.array() < hi.array()).all()) {
            ++bonds;
            broken += m.bonds.broken(b) ? 1 : 0;
          }
        }
        const std::size_t v = static_cast<std::size_t>(i + g.dimensions[0] * (j + g.dimensions[1] * k));
        EXPECT_EQ(vox.bonds[v], bonds) << "voxel " << i << " " << j << " " << k;
        EXPECT_EQ(vox.brokenBonds[v], broken);
        EXPECT_DOUBLE_EQ(vox.damage[v], bonds ? static_cast<double>(broken) / bonds : 0.0);
        EXPECT_DOUBLE_EQ(vox.brokenBondDensity[v], broken / g.voxelVolume());
        totalBroken += static_cast<std::size_t>(broken);
      }
    }
  }
  EXPECT_EQ(totalBroken, countBonds(m.bonds).broken) << "every bond counted once";
}

// The voxels' stress, volume-averaged, is the particles' volume-weighted stress; a
// voxel's displacement is the volume-weighted mean of its particles'.
TEST(Voxelize, StressAverageIsTheParticles)
{
  Model m = cementedPack();
  for (std::size_t i = 0; i < m.particles.size(); ++i) { // stir, so that bonds and contacts carry force
    m.particles.velocity[i] = Vec3(0.01 * std::sin(1.0 * i), 0.01 * std::cos(1.3 * i), 0.01 * std::sin(0.7 * i));
  }
  Simulation sim(m);
  sim.advance(50);
  const std::vector<StressTensor> s = particleStresses(m);
  VoxelParameters params;
  params.numberOfVoxels = 5;
  const VoxelModel vox = voxelize(m, params, s, nullptr);
  StressTensor fromParticles{ { 0, 0, 0, 0, 0, 0 } };
  for (std::size_t i = 0; i < s.size(); ++i) {
    for (int q = 0; q < 6; ++q) {
      fromParticles[q] += particleVolume(m.domain, m.particles.radius[i]) * s[i][q];
    }
  }
  StressTensor fromVoxels{ { 0, 0, 0, 0, 0, 0 } };
  for (std::size_t v = 0; v < vox.grid.count(); ++v) {
    for (int q = 0; q < 6; ++q) {
      fromVoxels[q] += vox.grid.voxelVolume() * vox.stress[v][q];
    }
    EXPECT_DOUBLE_EQ(vox.meanStress[v], meanStress(vox.stress[v], false));
    EXPECT_DOUBLE_EQ(vox.deviatoricStress[v], vonMisesStress(vox.stress[v], false));
  }
  double scale = 0.0;
  for (int q = 0; q < 6; ++q) {
    scale = std::max(scale, std::abs(fromParticles[q]));
  }
  ASSERT_GT(scale, 0.0);
  for (int q = 0; q < 6; ++q) {
    EXPECT_NEAR(fromVoxels[q], fromParticles[q], 1e-10 * scale) << "component " << q;
  }
}

// A fracture polygon rasterises to its area: P32 x voxel volume summed over the grid is
// the area inside the grid; a horizontal square across the grid gives P32 = 1 / h in the
// voxels it crosses; a non-convex (L-shaped) polygon is clipped exactly.
TEST(Voxelize, FracturesRasteriseToTheirArea)
{
  const double R = 0.004;
  const Model m = spheres({ Vec3(0, 0, 0) }, { R });
  VoxelParameters params;
  params.numberOfVoxels = 4; // voxels of R / 2 over [-R, R]^3
  params.margin = 0.0;
  FractureSetPolygons dfn;
  const double z = 0.3 * R; // inside the voxel layer [0, R/2)
  dfn.polygons.push_back({ Vec3(-2 * R, -2 * R, z), Vec3(2 * R, -2 * R, z), Vec3(2 * R, 2 * R, z), Vec3(-2 * R, 2 * R, z) });
  dfn.sets.push_back(0);
  // An L in the plane x = 0.1 R: the square [-R/2, R/2]^2 (y, z) minus its upper-right quarter.
  const double x = 0.1 * R;
  const double h = 0.5 * R;
  dfn.polygons.push_back({ Vec3(x, -h, -h), Vec3(x, h, -h), Vec3(x, h, 0), Vec3(x, 0, 0), Vec3(x, 0, h), Vec3(x, -h, h) });
  dfn.sets.push_back(1);
  const VoxelModel vox = voxelize(m, params, particleStresses(m), &dfn);
  const VoxelGrid& g = vox.grid;
  ASSERT_EQ(g.dimensions[0], 4);
  double area = 0.0;
  for (std::size_t v = 0; v < g.count(); ++v) {
    area += vox.fractureIntensity[v] * g.voxelVolume();
  }
  const double square = 4 * R * R; // the grid's [-R, R]^2 part of the square
  const double ell = 0.75 * 4 * h * h;
  EXPECT_NEAR(area, square + ell, 1e-12 * square);
  EXPECT_NEAR(vox.fractureArea, square + ell, 1e-12 * square);
  // Layer k = 2 ([0, R/2) in z) holds the square: h x h in every voxel, plus in voxel
  // (2, 1) the L's upper-left quarter (its upper-right quarter is cut away); layer k = 1
  // holds the L's lower half in voxels (2, 1) and (2, 2).
  for (int k = 0; k < 4; ++k) {
    for (int j = 0; j < 4; ++j) {
      for (int i = 0; i < 4; ++i) {
        const std::size_t v = static_cast<std::size_t>(i + 4 * (j + 4 * k));
        double expected = 0.0;
        int set = -1;
        if (k == 2) {
          expected = (i == 2 && j == 1) ? 2 * h * h : h * h;
          set = (i == 2 && j == 1) ? vox.fractureSet[v] : 0; // a tie: either polygon's set
        } else if (k == 1 && i == 2 && (j == 1 || j == 2)) {
          expected = h * h;
          set = 1;
        }
        EXPECT_NEAR(vox.fractureIntensity[v] * g.voxelVolume(), expected, 1e-12 * h * h)
          << "voxel " << i << " " << j << " " << k;
        EXPECT_EQ(vox.fractureSet[v], set) << "voxel " << i << " " << j << " " << k;
      }
    }
  }
  EXPECT_NEAR(vox.fractureIntensity[static_cast<std::size_t>(0 + 4 * (0 + 4 * 2))], 1.0 / g.spacing.x(),
              1e-9 / g.spacing.x()) << "P32 = 1 / h where the square crosses a voxel";
}

TEST(Voxelize, BadInputIsNamed)
{
  const Model m = cementedPack();
  const std::vector<StressTensor> s = particleStresses(m);
  auto message = [&](const VoxelParameters& p) {
    try {
      voxelize(m, p, s, nullptr);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  VoxelParameters p;
  p.sizing = VoxelSizing::VoxelSize;
  p.voxelSize = 0.0;
  EXPECT_NE(message(p).find("Voxel Size = 0 m"), std::string::npos) << message(p);
  p.voxelSize = -0.001;
  EXPECT_NE(message(p).find("Voxel Size = -0.001 m"), std::string::npos) << message(p);
  p.voxelSize = 1e-6; // 10^12 voxels
  const std::string big = message(p);
  EXPECT_NE(big.find("Voxel Size = 1e-06 m"), std::string::npos) << big;
  EXPECT_NE(big.find("the Memory Limit is 2048 MiB"), std::string::npos) << big;
  p.voxelSize = 0.0005;
  p.memoryLimit = 0.5; // MiB
  const std::string limited = message(p);
  EXPECT_NE(limited.find("the Memory Limit is 0.5 MiB"), std::string::npos) << limited;
  p.memoryLimit = -1.0;
  EXPECT_NE(message(p).find("Memory Limit = -1 MiB"), std::string::npos) << message(p);
  VoxelParameters q;
  q.numberOfVoxels = 0;
  EXPECT_NE(message(q).find("Number Of Voxels = 0"), std::string::npos) << message(q);
  EXPECT_THROW(voxelize(m, VoxelParameters(), std::vector<StressTensor>(3), nullptr), InputError);
}

// A grid fitted to one state of a run serves another: the particles that moved out of it
// are not counted (and the message says how much); what is counted is each sphere's part
// inside the grid.
TEST(Voxelize, GridFittedToOneStateServesAnother)
{
  const Model before = cementedPack();
  VoxelParameters params;
  params.numberOfVoxels = 6;
  params.margin = 0.0;
  const VoxelGrid grid = planVoxelGrid(before, params, false);
  Model after = before;
  for (Vec3& x : after.particles.position) {
    x.x() += 0.3 * grid.dimensions[0] * grid.spacing.x(); // a third of the particles leave the grid
  }
  const VoxelModel vox = voxelize(after, grid, std::vector<StressTensor>(after.particles.size()), nullptr);
  const Vec3 hi = grid.origin + Vec3(grid.dimensions[0] * grid.spacing.x(), grid.dimensions[1] * grid.spacing.y(),
                                     grid.dimensions[2] * grid.spacing.z());
  double inside = 0.0;
  for (std::size_t i = 0; i < after.particles.size(); ++i) {
    inside += sphereBoxVolume(after.particles.position[i], after.particles.radius[i], grid.origin, hi);
  }
  EXPECT_NEAR(vox.solidVolume, inside, 1e-10 * inside);
  EXPECT_LT(vox.solidVolume, 0.9 * vox.particleVolume);
  EXPECT_GT(vox.bondsOutside, 0u);
  EXPECT_NE(vox.message.find("Outside the grid"), std::string::npos) << vox.message;
}
