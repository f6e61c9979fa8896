// The laboratory's tests on carved specimens (dem/Specimen.h, dem/LoadTest.h): the
// Brazilian test on a 2D disc and a 3D short cylinder against the elastic solution, and
// direct tension with gripped ends. SI units.
#include "Specimens.h"

#include "dem/Bonds.h"
#include "dem/BrazilianSolution.h"
#include "dem/Errors.h"
#include "dem/Fractures.h"
#include "dem/ParticleStress.h"
#include "dem/Specimen.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

using namespace dem;
using dem::testing::testCement;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// A dense pack of n grains (radii in [rmin, rmax] m) placed in a box of the given size (m;
/// a 2D section when twoD, size.z the slab) without gravity and compacted (Compact
/// Elements: radius expansion with relaxation) to porosity 0.37 (3D) or 0.16 (2D), so that
/// the cement finds a dense contact network.
Model densePack(bool twoD, const Vec3& size, int n, double rmin, double rmax, std::uint64_t seed)
{
  Model m = dem::testing::placedPack(size, twoD, n, rmin, rmax, seed);
  CompactParameters c;
  c.targetPorosity = twoD ? 0.16 : 0.37;
  compactElements(m, c);
  return m;
}

/// The cement of the laboratory tests: the test cement with bonds ten times stiffer than
/// the grains, so that the parallel bonds carry tension and compression alike and the
/// specimen is close to a linear elastic body.
CementParameters labCement()
{
  CementParameters c = testCement();
  c.bondModulus = 1e9;
  return c;
}

/// A cemented disc: carved (Shape Disc, axis Z) out of a dense pack (pack seed `seed`)
/// and cemented with the lab cement.
Model cementedDisc(bool twoD, std::uint64_t seed)
{
  Model m = twoD ? densePack(true, Vec3(0.03, 0.03, 0.001), 1400, 0.0003, 0.0005, seed)
                 : densePack(false, Vec3(0.016, 0.016, 0.008), 4000, 0.0003, 0.0004, seed);
  SpecimenSettings disc;
  disc.shape = SpecimenShape::Disc;
  disc.axis = 2;
  disc.diameter = twoD ? 0.028 : 0.015;
  disc.length = 0.007;
  carveSpecimen(m, disc);
  cement(m, labCement());
  m.solver.timestepSafety = 0.3;
  return m;
}

/// The continuum stress over a region through the whole thickness: sum V_p sigma_p over
/// the particles whose centres lie within `radius` (m, in the XY plane) of `centre`,
/// divided by the region's volume pi radius^2 t, t the thickness of 2P/(pi D t). Summed
/// over all the particles (radius D/2) this is the Love-Weber stress of the whole disc,
/// fixed by the platen loads alone (its sigma_yy is 2 x 2P/(pi D t)).
StressTensor regionStress(const Model& m, const std::vector<StressTensor>& stress, const Vec3& centre,
                          double radius, double thickness, std::size_t* grains = nullptr)
{
  StressTensor sum{};
  std::size_t count = 0;
  for (std::size_t i = 0; i < m.particles.size(); ++i) {
    const Vec3 r = m.particles.position[i] - centre;
    if (std::hypot(r.x(), r.y()) <= radius) {
      const double v = particleVolume(m.domain, m.particles.radius[i]);
      for (int k = 0; k < 6; ++k) {
        sum[k] += v * stress[i][k];
      }
      ++count;
    }
  }
  for (double& s : sum) {
    s /= kPi * radius * radius * thickness;
  }
  if (grains) {
    *grains = count;
  }
  return sum;
}

struct BrazilianResult {
  std::size_t rows = 0;     ///< history rows in the elastic window (loading, the disc intact away from the platens)
  std::size_t grains = 0;   ///< particles in the central region
  double elastic = 0.0;     ///< Pa, 2P/(pi D t) at the end of the window
  double tension = 0.0;     ///< -, central sigma_xx over its elastic mean, load-weighted over the window
  double compression = 0.0; ///< -, the same for sigma_yy
  double strength = 0.0;    ///< Pa, Peak Stress (Brazilian Strength)
  double centralBand = 0.0; ///< -, share of the broken bonds within D/6 of the loaded diameter
  std::size_t broken = 0;
  std::size_t discs = 0;    ///< DEM Fractures To DFN discs (default parameters)
  double dip = 0.0;         ///< degrees, of the disc with the most cracks
  double strikeAlongLoad = 0.0; ///< |strike . loading axis| of that disc
  double normalAcross = 0.0;    ///< |normal . X| of that disc (X: across the load, in the disc plane)
};

/// Squeezes the disc along Y. The elastic window: every history row while the disc is
/// loaded and intact away from its platens (no bond broken farther than D/8 from both
/// platens; the grains a flat platen presses on may crush, which the point-load solution
/// does not describe). `toFailure`: then on until the disc has split (a bond broken away
/// from the platens and the load fallen below `residual` x its peak) or Max Strain; else
/// stop when the window closes.
BrazilianResult brazilian(Model m, double strainRate, bool toFailure, double residual = 0.5)
{
  LoadTestSettings s;
  s.mode = TestMode::Brazilian;
  s.axis = 1;
  s.strainRate = strainRate;
  s.maxStrain = 0.05;
  s.sampleInterval = 50;
  startLoadTest(m, s);
  const std::array<double, 2> disc = brazilianDisc(m);
  const double D = disc[0];
  const double t = disc[1];
  Vec3 centre = Vec3::Zero(); // the disc's centre: the mean of the particle centres
  for (std::size_t i = 0; i < m.particles.size(); ++i) {
    centre += m.particles.position[i];
  }
  centre /= static_cast<double>(m.particles.size());
  // A bond broken away from the platens: farther than D/8 from both.
  auto brokeAwayFromPlatens = [&]() {
    for (std::size_t b = 0; b < m.bonds.size(); ++b) {
      const double y = m.bonds.failurePosition[b].y();
      if (m.bonds.broken(b) && y > m.walls[2].position + D / 8.0 && y < m.walls[3].position - D / 8.0) {
        return true;
      }
    }
    return false;
  };
  Simulation sim(m);
  BrazilianResult r;
  double measuredX = 0.0; // sums over the window: the central region's stress ...
  double measuredY = 0.0;
  double elasticX = 0.0;  // ... and the elastic mean over the same region
  double elasticY = 0.0;
  bool intact = true;
  while (m.test.stage != TestStage::Done) {
    sim.advance(s.sampleInterval);
    const TestMeasurements me = sim.measurements();
    intact = intact && !brokeAwayFromPlatens();
    if (intact && me.axialStress > 0.0) {
      // The central region (radius D/8) against the elastic mean over it; sums over the
      // rows weight them by the load (the first rows, before the platens have seated, carry little).
      const double load = me.axialStress * kPi * D * t / 2.0; // P from 2P/(pi D t)
      const StressTensor sigma =
        regionStress(m, particleStresses(m, sim.interactionForces()), centre, D / 8.0, t, &r.grains);
      const StressTensor elastic = brazilianElasticMean(D / 8.0, load, D, t);
      measuredX += sigma[0];
      measuredY += sigma[1];
      elasticX += elastic[0];
      elasticY += elastic[1];
      r.elastic = me.axialStress;
      ++r.rows;
    }
    if (!intact && (!toFailure || (m.test.peakStress > 0.0 && me.axialStress < residual * m.test.peakStress))) {
      break;
    }
  }
  r.tension = elasticX != 0.0 ? measuredX / elasticX : 0.0;
  r.compression = elasticY != 0.0 ? measuredY / elasticY : 0.0;
  r.strength = m.test.peakStress;
  std::size_t band = 0;
  for (std::size_t b = 0; b < m.bonds.size(); ++b) {
    if (m.bonds.broken(b)) {
      ++r.broken;
      band += std::abs(m.bonds.failurePosition[b].x() - centre.x()) <= D / 6.0 ? 1 : 0;
    }
  }
  r.centralBand = r.broken ? static_cast<double>(band) / static_cast<double>(r.broken) : 0.0;
  std::printf("Brazilian %s: D %.4g m, t %.4g m, %zu particles (%zu within D/8 of the centre); over %zu rows "
              "before the first break away from the platens (2P/(pi D t) = %.4g Pa at the last), central "
              "sigma_xx / its elastic mean %.3f, sigma_yy / its elastic mean %.3f; ",
              m.domain.section2D ? "2D disc" : "3D short cylinder", D, t, m.particles.size(), r.grains, r.rows,
              r.elastic, r.tension, r.compression);
  if (!toFailure) {
    std::printf("stopped there\n");
    return r;
  }
  std::printf("Brazilian Strength %.4g Pa; %zu broken bonds, %.2f within D/6 of the loaded diameter\n", r.strength,
              r.broken, r.centralBand);
  // The split as DEM Fractures To DFN sees it: the disc with the most cracks.
  const FractureNetwork dfn = extractFractures(m, FractureParameters());
  r.discs = dfn.discs.size();
  const FractureDisc* largest = nullptr;
  for (const FractureDisc& d : dfn.discs) {
    if (!largest || d.bonds.size() > largest->bonds.size()) {
      largest = &d;
    }
  }
  if (largest) {
    r.dip = largest->dip;
    r.strikeAlongLoad = std::abs(largest->strike.y());
    r.normalAcross = std::abs(largest->normal.x());
  }
  std::printf("DFN: %zu disc(s); the largest (%zu cracks): dip %.1f deg, |strike . Y| %.3f, |normal . X| %.3f\n%s\n",
              r.discs, largest ? largest->bonds.size() : std::size_t(0), r.dip, r.strikeAlongLoad, r.normalAcross,
              dfn.report.summary().c_str());
  return r;
}

/// Hondros (1959) / Timoshenko and Goodier: at the centre sigma_xx = -2P/(pi D t)
/// (tension), sigma_yy = 6P/(pi D t); over the central disc of radius D/8 the elastic
/// means are 0.9375 and 2.9375 times 2P/(pi D t) (dem/BrazilianSolution.h). Bar: 15 %
/// (issue 13) on the tension.
void expectCentralStressIsElastic(const BrazilianResult& r)
{
  ASSERT_GT(r.rows, 0u);
  ASSERT_GT(r.elastic, 0.0);
  EXPECT_NEAR(r.tension, 1.0, 0.15);
  EXPECT_GT(r.compression, 0.0);
}

/// The split: the band within D/6 of the loaded diameter (a third of the diameter) holds
/// most of the broken bonds.
void expectSplitAlongTheLoadedDiameter(const BrazilianResult& r)
{
  EXPECT_GT(r.strength, r.elastic);
  EXPECT_GT(r.broken, 0u);
  EXPECT_GT(r.centralBand, 0.5);
}

} // namespace

// Strain rates: the fastest at which the central stress no longer depends on the rate by
// more than a few per cent (Documentation/Press.md, "Check against the elastic solution").
TEST(LabTests, BrazilianDisc2DCentralStressIsTheElasticSolution)
{
  // The 2D disc first crushes the grains under its platens (a load peak of 29 kPa, then a
  // drop to a quarter of it), reloads, and splits at 80 kPa: it runs until the load has
  // fallen below a tenth of its peak, so that the split is there.
  const BrazilianResult r = brazilian(cementedDisc(true, 11), 4.0, true, 0.1);
  expectCentralStressIsElastic(r);
  expectSplitAlongTheLoadedDiameter(r);
  // DEM Fractures To DFN (default parameters) exports the split: in a 2D section a
  // fracture is a line in the plane extruded through the slab, so a vertical plane (dip
  // 90 deg) whose strike is along the loading axis Y.
  ASSERT_GE(r.discs, 1u);
  EXPECT_GT(r.dip, 80.0);
  EXPECT_GT(r.strikeAlongLoad, std::cos(15.0 * kPi / 180.0));
}

// The 3D short cylinder on two realisations of its 1,900-grain pack (pack seeds 13 and
// 17): the check must not depend on one pack. Over eight realisations (seeds 12-19) the
// ratio is 0.86-1.07 (Documentation/Press.md, "Check against the elastic solution").
TEST(LabTests, BrazilianShortCylinder3DCentralStressIsTheElasticSolutionAndSplitsAlongTheLoadedDiameter)
{
  const BrazilianResult r = brazilian(cementedDisc(false, 13), 8.0, true);
  expectCentralStressIsElastic(r);
  expectSplitAlongTheLoadedDiameter(r);
}

TEST(LabTests, BrazilianShortCylinder3DCentralStressIsTheElasticSolutionOnAnotherPack)
{
  expectCentralStressIsElastic(brazilian(cementedDisc(false, 17), 8.0, false));
}

namespace {

/// A cemented cylinder along Z (diameter 7.5 mm, length 15 mm) carved out of a dense pack.
Model cementedCylinder()
{
  Model m = densePack(false, Vec3(0.008, 0.008, 0.016), 3000, 0.0003, 0.0004, 13);
  SpecimenSettings cylinder;
  cylinder.diameter = 0.0075;
  cylinder.length = 0.015;
  carveSpecimen(m, cylinder);
  cement(m, labCement());
  m.solver.timestepSafety = 0.3;
  return m;
}

struct TensionResult {
  double strength = 0.0;  ///< Pa, Tensile Strength (the largest pull)
  std::size_t broken = 0; ///< broken bonds when the pull has fallen below half its peak
  std::size_t gauge = 0;  ///< of which between the grips
};

/// Direct tension of the cemented cylinder with grips of `gripLength` diameters, until the
/// pull has fallen below half its peak.
TensionResult directTension(double gripLength, double strainRate)
{
  Model m = cementedCylinder();
  LoadTestSettings s;
  s.mode = TestMode::Tension;
  s.axis = 2;
  s.strainRate = strainRate;
  s.maxStrain = 0.05;
  s.sampleInterval = 50;
  s.gripLength = gripLength;
  startLoadTest(m, s);
  double rmax = 0.0;
  for (double r : m.particles.radius) {
    rmax = std::max(rmax, r);
  }
  const double grip = s.gripLength * 2.0 * rmax;
  const double low = m.walls[4].position + grip;  // the gauge length lies between the grips
  const double high = m.walls[5].position - grip;
  std::size_t held = 0;
  for (std::uint32_t f : m.particles.flags) {
    held += (f & (FlagAttachedLow | FlagAttachedHigh)) ? 1 : 0;
  }
  Simulation sim(m);
  while (m.test.stage != TestStage::Done) {
    sim.advance(s.sampleInterval);
    if (m.test.peakStress > 0.0 && -sim.measurements().axialStress < 0.5 * m.test.peakStress) {
      break; // failed: the pull has fallen below half its peak
    }
  }
  std::size_t broken = 0;
  std::size_t gauge = 0;
  for (std::size_t b = 0; b < m.bonds.size(); ++b) {
    if (m.bonds.broken(b)) {
      ++broken;
      const double z = m.bonds.failurePosition[b].z();
      gauge += (z > low && z < high) ? 1 : 0;
    }
  }
  std::printf("Direct tension: %zu particles, %zu held by the grips (Grip Length %.3g diameters = %.4g m); "
              "Tensile Strength %.4g Pa; %zu broken bonds, %.3f in the gauge length\n",
              m.particles.size(), held, s.gripLength, grip, m.test.peakStress, broken,
              broken ? static_cast<double>(gauge) / broken : 0.0);
  return { m.test.peakStress, broken, gauge };
}

} // namespace

TEST(LabTests, DirectTensionWithGripsBreaksInTheGaugeLength)
{
  const TensionResult r = directTension(2.0, 1.0);
  ASSERT_GT(r.broken, 0u);
  EXPECT_GT(r.strength, 0.0);
  EXPECT_GE(static_cast<double>(r.gauge), 0.8 * static_cast<double>(r.broken));
}

// A measurement, not a test (run by hand, Documentation/Press.md "Brazilian over direct
// tensile strength"): the same rock (pack, grain size, cement) as a 3D Brazilian disc and
// a gripped cylinder in direct tension, at the same strain rate.
TEST(LabTests, DISABLED_BrazilianOverDirectTensileStrengthOfTheSameRock)
{
  for (double grip : { 1.0, 2.0, 4.0 }) {
    const TensionResult t = directTension(grip, 1.0);
    std::printf("Grip Length %.3g: %zu of %zu broken bonds in the gauge length\n", grip, t.gauge, t.broken);
  }
  for (double rate : { 8.0 }) {
    const BrazilianResult b = brazilian(cementedDisc(false, 13), rate, true);
    const TensionResult t = directTension(2.0, rate);
    std::printf("strain rate %.3g /s: Brazilian Strength %.4g Pa, Tensile Strength %.4g Pa, ratio %.3f\n", rate,
                b.strength, t.strength, b.strength / t.strength);
    EXPECT_GT(t.strength, 0.0);
  }
}

TEST(LabTests, GripLengthMustBePositiveAndLeaveAGaugeLength)
{
  LoadTestSettings s;
  s.mode = TestMode::Tension;
  s.gripLength = 0.0;
  try {
    validate(s);
    FAIL() << "Grip Length 0 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("Grip Length = 0 largest particle diameters is out of range: valid "
                                         "range is (0, inf)"),
              std::string::npos)
      << e.what();
  }
  s.gripLength = 1.0;
  EXPECT_NO_THROW(validate(s));
  // Grips that would meet in the middle leave no gauge length.
  Model m = dem::testing::specimen(200, 0.01, 0.0008, 0.0012, 2);
  cement(m, testCement());
  const Model before = m;
  s.gripLength = 50.0;
  try {
    startLoadTest(m, s);
    FAIL() << "grips covering the specimen accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("Grip Length = 50 largest particle diameters"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("leaving no gauge length; valid range is (0, "), std::string::npos)
      << e.what();
  }
  EXPECT_EQ(m.test.settings.mode, before.test.settings.mode); // refused before any change
  EXPECT_EQ(m.particles.flags, before.particles.flags);
}

TEST(LabTests, BrazilianStressIsTwoPOverPiDtOfTheCarvedDisc)
{
  EXPECT_DOUBLE_EQ(brazilianStress(1.0, 0.02, 0.01), 2.0 / (kPi * 0.02 * 0.01));
  EXPECT_EQ(brazilianStress(1.0, 0.0, 0.01), 0.0);
  Model m = densePack(false, Vec3(0.014, 0.014, 0.008), 1500, 0.0004, 0.0005, 3);
  SpecimenSettings s;
  s.shape = SpecimenShape::Disc;
  s.diameter = 0.013;
  s.length = 0.0065;
  carveSpecimen(m, s);
  cement(m, labCement());
  LoadTestSettings b;
  b.mode = TestMode::Brazilian;
  b.axis = 0;
  b.strainRate = 20.0;
  b.sampleInterval = 20;
  startLoadTest(m, b);
  // D: the starting length along the loading axis X (the platens on the disc's extent);
  // t: the smaller extent across it, the disc's thickness along Z.
  const std::array<double, 2> disc = brazilianDisc(m);
  EXPECT_DOUBLE_EQ(disc[0], m.domain.size.x());
  EXPECT_DOUBLE_EQ(disc[1], m.domain.size.z());
  EXPECT_LT(disc[1], disc[0]);
  EXPECT_FALSE(m.walls[2].active || m.walls[3].active || m.walls[4].active || m.walls[5].active);
  EXPECT_TRUE(m.walls[0].active && m.walls[1].active);
  Simulation sim(m);
  sim.advance(2000);
  const TestMeasurements me = sim.measurements();
  const double load = 0.5 * (m.walls[1].force.x() - m.walls[0].force.x()); // the platens' push, N
  EXPECT_GT(load, 0.0) << "strain " << me.strain[0];
  EXPECT_DOUBLE_EQ(me.axialStress, brazilianStress(load, disc[0], disc[1]));
  EXPECT_EQ(m.test.history.back()[18], me.axialStress); // the Axial Stress column
  // A 2D section is squeezed in its plane: Axis Z (the slab axis) is refused.
  Model flat = dem::testing::placedPack(Vec3(0.01, 0.01, 0.001), true, 50, 0.0004, 0.0006, 1);
  b.axis = 2;
  EXPECT_THROW(startLoadTest(flat, b), InputError);
}

// The elastic solution of the diametrally loaded disc (dem/BrazilianSolution.h): Hertz
// (1883) / Frocht (1948), checked against its centre values and the integrals that the
// equilibrium of parts of the disc fixes, by quadrature of the point field.
TEST(LabTests, BrazilianElasticSolutionCentreValuesAndEquilibrium)
{
  const double D = 0.02;
  const double R = 0.5 * D;
  const double t = 0.01;
  const double P = 150.0;
  const double s0 = brazilianStress(P, D, t); // 2P/(pi D t)
  const double tol = 1e-12 * s0;
  // The centre: tension s0 across the loaded diameter, compression 3 s0 along it.
  const StressTensor c = brazilianElasticStress(0.0, 0.0, P, D, t);
  EXPECT_NEAR(c[0], -s0, tol);
  EXPECT_NEAR(c[1], 3.0 * s0, tol);
  EXPECT_NEAR(c[3], 0.0, tol);
  EXPECT_EQ(c[2], 0.0);
  // Along the loaded diameter the tension is s0 everywhere (ISRM: the split starts anywhere on it).
  for (double y : { -0.9 * R, -0.5 * R, 0.3 * R, 0.95 * R }) {
    EXPECT_NEAR(brazilianElasticStress(0.0, y, P, D, t)[0], -s0, 1e-9 * s0) << y;
  }
  // The rim is free of traction away from the two loads: sigma n = 0.
  for (double deg : { 0.0, 20.0, 45.0, 80.0, 135.0, 200.0, 300.0 }) {
    const double a = deg * kPi / 180.0;
    const double nx = std::cos(a);
    const double ny = std::sin(a);
    const double rim = R * (1.0 - 1e-12); // on the rim (rounding kept inside)
    const StressTensor s = brazilianElasticStress(rim * nx, rim * ny, P, D, t);
    EXPECT_NEAR(s[0] * nx + s[3] * ny, 0.0, 1e-9 * s0) << deg;
    EXPECT_NEAR(s[3] * nx + s[1] * ny, 0.0, 1e-9 * s0) << deg;
  }
  // Equilibrium of the upper half: the compression across the horizontal diameter sums to P / t.
  const int n = 20000;
  double sum = 0.0;
  for (int k = 0; k < n; ++k) {
    const double x = -R + (k + 0.5) * D / n;
    sum += brazilianElasticStress(x, 0.0, P, D, t)[1] * D / n;
  }
  EXPECT_NEAR(sum, P / t, 1e-6 * P / t);
  // Equilibrium of the part beyond a vertical chord x = c != 0: no horizontal load acts on
  // it, so sigma_xx sums to zero over the chord (the tension near the centre is balanced by
  // compression near the rim).
  for (double cx : { 0.2 * R, 0.5 * R }) {
    const double h = std::sqrt(R * R - cx * cx);
    double chord = 0.0;
    double magnitude = 0.0;
    for (int k = 0; k < n; ++k) {
      const double y = -h + (k + 0.5) * 2.0 * h / n;
      const double sxx = brazilianElasticStress(cx, y, P, D, t)[0];
      chord += sxx * 2.0 * h / n;
      magnitude += std::abs(sxx) * 2.0 * h / n;
    }
    EXPECT_NEAR(chord, 0.0, 1e-5 * magnitude) << cx;
  }
  // The mean over a concentric disc of radius a (closed form) against the quadrature of
  // the point field (polar: midpoint in r and in the angle).
  for (double a : { 0.0, 0.125 * D, 0.25 * D, 0.35 * D }) {
    const StressTensor mean = brazilianElasticMean(a, P, D, t);
    EXPECT_NEAR(mean[0], -s0 * (1.0 - a * a / (R * R)), tol);
    EXPECT_NEAR(mean[1], s0 * (3.0 - a * a / (R * R)), tol);
    if (a == 0.0) {
      continue;
    }
    const int nr = 400;
    const int nt = 256;
    StressTensor q{};
    for (int i = 0; i < nr; ++i) {
      const double r = (i + 0.5) * a / nr;
      for (int j = 0; j < nt; ++j) {
        const double th = (j + 0.5) * 2.0 * kPi / nt;
        const StressTensor s = brazilianElasticStress(r * std::cos(th), r * std::sin(th), P, D, t);
        for (int k = 0; k < 6; ++k) {
          q[k] += s[k] * r * (a / nr) * (2.0 * kPi / nt) / (kPi * a * a);
        }
      }
    }
    EXPECT_NEAR(q[0], mean[0], 1e-5 * s0) << a;
    EXPECT_NEAR(q[1], mean[1], 1e-5 * s0) << a;
    EXPECT_NEAR(q[3], 0.0, 1e-5 * s0) << a;
  }
  // The whole disc: its mean stress is fixed by the two loads alone, (1 / (pi R^2 t)) sum x (x) F.
  const StressTensor whole = brazilianElasticMean(R, P, D, t);
  EXPECT_NEAR(whole[0], 0.0, tol);
  EXPECT_NEAR(whole[1], 2.0 * P * R / (kPi * R * R * t), tol);
  // Bad input names the parameter.
  auto message = [](auto&& f) {
    try {
      f();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message([&] { brazilianElasticMean(0.6 * D, P, D, t); }).find("Radius = 0.012 m is out of range"),
            std::string::npos);
  EXPECT_NE(message([&] { brazilianElasticMean(0.0, P, 0.0, t); }).find("Diameter"), std::string::npos);
  EXPECT_NE(message([&] { brazilianElasticStress(0.0, 0.0, -1.0, D, t); }).find("Load"), std::string::npos);
  EXPECT_NE(message([&] { brazilianElasticStress(0.0, 0.0, P, D, 0.0); }).find("Thickness"), std::string::npos);
  EXPECT_NE(message([&] { brazilianElasticStress(0.0, R, P, D, t); }).find("load points"), std::string::npos);
  EXPECT_NE(message([&] { brazilianElasticStress(R, R, P, D, t); }).find("is out of range"), std::string::npos);
}

