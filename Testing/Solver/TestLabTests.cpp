// The laboratory's tests on carved specimens (dem/Specimen.h, dem/LoadTest.h): the
// Brazilian test on a 2D disc and a 3D short cylinder against the elastic solution, and
// direct tension with gripped ends. SI units.
#include "Specimens.h"

#include "dem/Bonds.h"
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

/// A cemented disc: carved (Shape Disc, axis Z) out of a dense pack and cemented with the
/// lab cement.
Model cementedDisc(bool twoD)
{
  Model m = twoD ? densePack(true, Vec3(0.03, 0.03, 0.001), 1400, 0.0003, 0.0005, 11)
                 : densePack(false, Vec3(0.016, 0.016, 0.008), 4000, 0.0003, 0.0004, 12);
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

/// The mean of the particle stresses of the particles whose centres lie within `radius`
/// (m, in the XY plane) of `centre`, as a continuum stress: sum V_p sigma_p over the
/// region's particles divided by their volume over the specimen's solid fraction.
StressTensor regionStress(const Model& m, const std::vector<StressTensor>& stress, const Vec3& centre,
                          double radius, double solidFraction)
{
  StressTensor sum{};
  double volume = 0.0;
  for (std::size_t i = 0; i < m.particles.size(); ++i) {
    const Vec3 r = m.particles.position[i] - centre;
    if (std::hypot(r.x(), r.y()) <= radius) {
      const double v = particleVolume(m.domain, m.particles.radius[i]);
      for (int k = 0; k < 6; ++k) {
        sum[k] += v * stress[i][k];
      }
      volume += v;
    }
  }
  for (double& s : sum) {
    s *= solidFraction / volume;
  }
  return sum;
}

struct BrazilianResult {
  double elastic = 0.0;     ///< Pa, 2P/(pi D t) at the last sample before the first break
  double horizontal = 0.0;  ///< Pa, mean horizontal stress in the central region then (compression positive)
  double vertical = 0.0;    ///< Pa, mean vertical stress there
  double strength = 0.0;    ///< Pa, Peak Stress (Brazilian Strength)
  double centralBand = 0.0; ///< -, share of the broken bonds within D/6 of the loaded diameter
  std::size_t broken = 0;
  std::size_t discs = 0;    ///< DEM Fractures To DFN discs (default parameters)
  double dip = 0.0;         ///< degrees, of the disc with the most cracks
  double strikeAlongLoad = 0.0; ///< |strike . loading axis| of that disc
  double normalAcross = 0.0;    ///< |normal . X| of that disc (X: across the load, in the disc plane)
};

/// Squeezes the disc along Y until its load has fallen below half the peak (or Max Strain).
BrazilianResult brazilian(Model m, double strainRate)
{
  LoadTestSettings s;
  s.mode = TestMode::Brazilian;
  s.axis = 1;
  s.strainRate = strainRate;
  s.maxStrain = 0.05;
  s.sampleInterval = 50;
  startLoadTest(m, s);
  const std::array<double, 2> disc = brazilianDisc(m);
  Vec3 centre = Vec3::Zero(); // the disc's centre: the mean of the particle centres
  double solid = 0.0;
  for (std::size_t i = 0; i < m.particles.size(); ++i) {
    centre += m.particles.position[i];
    solid += particleVolume(m.domain, m.particles.radius[i]);
  }
  centre /= static_cast<double>(m.particles.size());
  const double solidFraction = solid / (0.25 * kPi * disc[0] * disc[0] * disc[1]);
  Simulation sim(m);
  BrazilianResult r;
  while (m.test.stage != TestStage::Done) {
    sim.advance(s.sampleInterval);
    const TestMeasurements me = sim.measurements();
    if (countBonds(m.bonds).broken == 0) {
      // Before the first break: the central region's stress against the elastic solution.
      const StressTensor sigma =
        regionStress(m, particleStresses(m, sim.interactionForces()), centre, disc[0] / 8.0, solidFraction);
      r.elastic = me.axialStress;
      r.horizontal = sigma[0];
      r.vertical = sigma[1];
    }
    if (m.test.peakStress > 0.0 && me.axialStress < 0.5 * m.test.peakStress) {
      break;
    }
  }
  r.strength = m.test.peakStress;
  std::size_t band = 0;
  for (std::size_t b = 0; b < m.bonds.size(); ++b) {
    if (m.bonds.broken(b)) {
      ++r.broken;
      band += std::abs(m.bonds.failurePosition[b].x() - centre.x()) <= disc[0] / 6.0 ? 1 : 0;
    }
  }
  r.centralBand = r.broken ? static_cast<double>(band) / static_cast<double>(r.broken) : 0.0;
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
  std::printf("DFN: %zu disc(s); the largest (%zu cracks): dip %.1f deg, |strike . Y| %.3f, |normal . X| %.3f\n",
              r.discs, largest ? largest->bonds.size() : std::size_t(0), r.dip, r.strikeAlongLoad, r.normalAcross);
  std::printf("Brazilian %s: D %.4g m, t %.4g m, %zu particles; before the first break 2P/(pi D t) = %.4g Pa, "
              "central sigma_xx = %.4g Pa (ratio %.3f), sigma_yy = %.4g Pa (ratio %.3f, elastic 3); "
              "Brazilian Strength %.4g Pa; %zu broken bonds, %.2f within D/6 of the loaded diameter\n",
              m.domain.section2D ? "2D disc" : "3D short cylinder", disc[0], disc[1], m.particles.size(),
              r.elastic, r.horizontal, -r.horizontal / r.elastic, r.vertical, r.vertical / r.elastic,
              r.strength, r.broken, r.centralBand);
  return r;
}

/// The Brazilian test of the carved disc: the central stress state before the first break
/// and the split. `elasticBar`: the bar on the central tension against the elastic
/// solution, or 0 to check only its sign (see the 3D test).
void expectBrazilianAgreesWithTheElasticSolution(bool twoD, double elasticBar)
{
  // Strain rates: the fastest at which the central stress no longer depends on the rate
  // by more than a few per cent (2D: the same ratio within 0.5 % from 0.2 to 4 /s).
  const BrazilianResult r = brazilian(cementedDisc(twoD), twoD ? 4.0 : 8.0);
  ASSERT_GT(r.elastic, 0.0);
  // Hondros (1959) / Timoshenko and Goodier: at the centre sigma_xx = -2P/(pi D t)
  // (tension), sigma_yy = 6P/(pi D t); averaged over the central disc of radius D/8 the
  // tension is 6 % lower and the compression 2 % lower.
  if (elasticBar > 0.0) {
    EXPECT_NEAR(-r.horizontal / r.elastic, 1.0, elasticBar);
  }
  EXPECT_LT(r.horizontal, 0.0) << "the centre is in tension across the loaded diameter";
  EXPECT_GT(r.vertical, 0.0);
  EXPECT_GT(r.strength, r.elastic);
  // It splits along the loaded diameter: the band within D/6 of it (a third of the
  // diameter) holds most of the broken bonds.
  EXPECT_GT(r.broken, 0u);
  EXPECT_GT(r.centralBand, 0.5);
  // What DEM Fractures To DFN makes of the split is printed, not asserted: with its
  // default parameters it does not yet export the split as one vertical disc along Y
  // (Documentation/Press.md, "Brazilian test": 3D one disc of dip 13 deg, 2D none).
}

} // namespace

TEST(LabTests, BrazilianDisc2DCentralStressIsTheElasticSolution)
{
  expectBrazilianAgreesWithTheElasticSolution(true, 0.15); // bar: 15 % (issue 13)
}

TEST(LabTests, BrazilianShortCylinder3DTensionAtTheCentreAndSplitAlongTheLoadedDiameter)
{
  // The 3D short cylinder does not meet the 15 % bar of issue 13 robustly: its central
  // tension over the elastic solution depends on the realisation of its 1,900-grain pack,
  // 0.861 (2 % compaction stages), 0.822 (5 % stages), 0.670 (5 % stages stepped in
  // Morton order: the same recipe, another summation order). Documentation/Press.md,
  // "Brazilian test". Checked here: tension at the centre, compression along the load,
  // the split along the loaded diameter; the ratio is printed.
  expectBrazilianAgreesWithTheElasticSolution(false, 0.0);
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
    const BrazilianResult b = brazilian(cementedDisc(false), rate);
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
