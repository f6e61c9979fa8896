// The virtual press (reference guide "Loading the model", "Running a triaxial test";
// PHYSICS.md section 4): servo faces reach and hold the confining stress, the platen
// loads a cemented specimen to failure, Mode Off restores the box, the history has the
// documented columns.
#include "dem/Bonds.h"
#include "dem/Cement.h"
#include "dem/Errors.h"
#include "dem/LoadTest.h"
#include "dem/Pack.h"
#include "dem/Simulation.h"
#include "DynamicsFixtures.h"
#include "Specimens.h"
#include "StateFixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <Eigen/Dense>
#include <cstdio>
#include <cmath>
#include <initializer_list>
#include <map>
#include <string>

using namespace dem;

using namespace dem::testing;

namespace {

void runUntilDone(Model& m, Simulation& sim, int maxBatches, int batch = 500)
{
  for (int k = 0; k < maxBatches && m.test.stage != TestStage::Done; ++k) {
    sim.advance(batch);
  }
}

/// The index of a test-history column (historyColumns()).
std::size_t column(const char* name)
{
  const auto& columns = historyColumns();
  return static_cast<std::size_t>(std::find(columns.begin(), columns.end(), name) - columns.begin());
}

/// The test-history rows of the shear stage.
std::vector<std::array<double, HistoryColumnCount>> shearRows(const Model& m)
{
  std::vector<std::array<double, HistoryColumnCount>> rows;
  for (const auto& row : m.test.history) {
    if (static_cast<TestStage>(row[column("Stage")]) == TestStage::Shear) {
      rows.push_back(row);
    }
  }
  return rows;
}

} // namespace

// Isotropic: every face reaches Confining Stress within 2 % and holds it.
TEST(Press, IsotropicReachesAndHoldsConfiningStress)
{
  Model m = specimen(1500, 0.03, 0.001, 0.0015);
  LoadTestSettings s;
  s.mode = TestMode::Isotropic;
  s.confiningStress = 1e5;
  s.sampleInterval = 200;
  startLoadTest(m, s);
  Simulation sim(m);
  runUntilDone(m, sim, 100);
  ASSERT_EQ(m.test.stage, TestStage::Done) << "stops once settled";
  for (int extra = 0; extra < 3; ++extra) {
    const TestMeasurements me = sim.measurements();
    for (int w = 0; w < 6; ++w) {
      EXPECT_NEAR(me.faceStress[w], 1e5, 0.02e5) << "face " << w;
    }
    sim.advance(1000); // the walls stop and the specimen stays at the stress
  }
  EXPECT_NEAR(sim.measurements().meanStress, 1e5, 0.03e5) << "Love-Weber mean stress agrees";
}

// Triaxial: consolidation reaches the target, then through shear the side faces hold it
// within 2 % while the deviator stress rises.
TEST(Press, TriaxialConsolidatesThenSidesHoldThroughShear)
{
  Model m = specimen(1500, 0.03, 0.001, 0.0015);
  LoadTestSettings s;
  s.mode = TestMode::Triaxial;
  s.axis = 2;
  s.confiningStress = 1e5;
  s.strainRate = 0.5;
  s.maxStrain = 0.02;
  s.sampleInterval = 200;
  startLoadTest(m, s);
  Simulation sim(m);
  runUntilDone(m, sim, 200);
  ASSERT_EQ(m.test.stage, TestStage::Done);
  const auto rows = shearRows(m);
  for (const auto& row : rows) {
    for (const char* side : { "Stress X- (Pa)", "Stress X+ (Pa)", "Stress Y- (Pa)", "Stress Y+ (Pa)" }) {
      EXPECT_NEAR(row[column(side)], 1e5, 0.02e5) << side << " at strain " << row[column("Strain Z")];
    }
  }
  ASSERT_GT(rows.size(), 10u);
  EXPECT_GT(rows.back()[column("Deviator Stress (Pa)")], 0.1e5) << "the platen loads the specimen";
  EXPECT_GE(m.test.history.back()[column("Strain Z")], 0.02 - 1e-3);
}

// Unconfined compression of a cemented specimen: elastic rise, a peak, post-peak
// softening, broken bonds (the character of a UCS test).
TEST(Press, UnconfinedCompressionOfCementedSpecimenFails)
{
  Model m = specimen(400, 0.016, 0.0008, 0.0012, 3);
  consolidate(m, 2e4); // close the pack a little so the cement has contacts to bond
  ASSERT_GT(cement(m, testCement()).bonds, 500u);
  LoadTestSettings s;
  s.mode = TestMode::Compression;
  s.strainRate = 1.0;
  s.maxStrain = 0.03;
  s.sampleInterval = 100;
  startLoadTest(m, s);
  EXPECT_FALSE(m.walls[0].active) << "side walls are removed";
  EXPECT_TRUE(m.walls[4].active && m.walls[5].active) << "the platens stay";
  Simulation sim(m);
  runUntilDone(m, sim, 400);
  ASSERT_EQ(m.test.stage, TestStage::Done);
  const auto& h = m.test.history;
  std::size_t peakRow = 0;
  for (std::size_t r = 0; r < h.size(); ++r) {
    if (h[r][18] > h[peakRow][18]) {
      peakRow = r;
    }
  }
  const double peak = h[peakRow][18];
  EXPECT_NEAR(peak, m.test.peakStress, 1e-9 * peak);
  EXPECT_GT(peak, 0.0);
  EXPECT_GT(peakRow, h.size() / 10) << "elastic rise before the peak";
  EXPECT_LT(peakRow, h.size() - 3) << "the peak is not at the end";
  EXPECT_LT(h.back()[18], 0.7 * peak) << "post-peak softening";
  EXPECT_GT(countBonds(m.bonds).broken, 20u) << "bonds break";
  // Elastic rise: stress grows with strain in the first part of the curve.
  EXPECT_GT(h[peakRow / 2][18], 0.2 * peak);
}

// Lateral strain of an unconfined specimen (no side walls) follows the particle centres:
// a homogeneous lateral stretch x' = xbar + (1 + e)(x - xbar) reads back as strain -e
// (shortening positive; reference: the definition of homogeneous strain), and one grain
// flung far away moves it by at most 2 dx / (N spread) (the mean absolute deviation
// changes by at most 2 dx / N), where the particles' extent would follow the grain.
TEST(Press, UnconfinedLateralStrainFollowsTheCentres)
{
  Model m = specimen(300, 0.02, 0.001, 0.0015);
  LoadTestSettings s;
  s.mode = TestMode::Compression;
  startLoadTest(m, s);
  ASSERT_GT(m.test.initialSpread[0], 0.0);
  ASSERT_GT(m.test.initialSpread[2], 0.0) << "the Gauge Strain's reference along the platen axis";
  Simulation sim(m);
  EXPECT_NEAR(sim.measurements().strain[0], 0.0, 1e-15);
  EXPECT_NEAR(sim.measurements().gaugeStrain, 0.0, 1e-15);
  const double e = 0.01;
  Particles& p = m.particles;
  for (int k = 0; k < 2; ++k) {
    double mean = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      mean += p.position[i][k];
    }
    mean /= static_cast<double>(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) {
      p.position[i][k] = mean + (1.0 + (k == 0 ? e : 0.5 * e)) * (p.position[i][k] - mean);
    }
  }
  const TestMeasurements stretched = sim.measurements();
  EXPECT_NEAR(stretched.strain[0], -e, 1e-12);
  EXPECT_NEAR(stretched.strain[1], -0.5 * e, 1e-12);
  EXPECT_NEAR(stretched.gaugeStrain, 0.0, 1e-15) << "no axial stretch yet";
  // The Gauge Strain follows a homogeneous axial shortening of the centres; the platen
  // strain, measured between the platens that did not move, does not.
  {
    double mean = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      mean += p.position[i].z();
    }
    mean /= static_cast<double>(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) {
      p.position[i].z() = mean + (1.0 - 0.3 * e) * (p.position[i].z() - mean);
    }
    const TestMeasurements squeezed = sim.measurements();
    EXPECT_NEAR(squeezed.gaugeStrain, 0.3 * e, 1e-12);
    EXPECT_NEAR(squeezed.strain[2], 0.0, 1e-15);
  }
  const double dx = 10.0 * m.domain.size.x();
  p.position[0].x() += dx;
  const double bound = 2.0 * dx / (static_cast<double>(p.size()) * m.test.initialSpread[0]);
  EXPECT_LE(std::abs(sim.measurements().strain[0] - stretched.strain[0]), bound);
  EXPECT_GT(sim.measurements().strain[0], -0.5) << "not the extent (which would read about -10)";
}

// Young's modulus and Poisson's ratio read against the Gauge Strain are the specimen's.
// Reference: the affine (Voigt) estimate of a bonded random packing's stiffness from its
// bonds, C_ijkl = (1/V) sum_b L^2 [kn n_i n_j n_k n_l + ks (delta_ik n_j n_l - n_i n_j n_k n_l)]
// (Chang & Misra 1990, J. Eng. Mech. 116; Liao et al. 1997, Int. J. Solids Struct. 34),
// computed here from the bonds of the cemented specimen, against the measurement, as the
// ISRM suggested method measures strain on the specimen (Bieniawski & Bernede 1979). The
// platen strain holds the compliance of the spheres' Hertz contacts with the flat platens
// as well, and reads E far lower (Documentation/Press.md, "Measurements").
TEST(Press, GaugeStrainReadsTheSpecimenNotThePlatenContacts)
{
  constexpr double pi = 3.14159265358979323846;
  const double a = 0.001, b = 0.002, porosity = 0.36;
  const int n = 600;
  const double meanVolume = 4.0 / 3.0 * pi * (a + b) * (a * a + b * b) / 4.0;
  const double width = std::cbrt(n * meanVolume / (1.0 - porosity) / 2.0);
  const Vec3 size(width, width, 2.0 * width);
  const double grow = std::cbrt((1.0 - porosity) / 0.3); // placed loose, then scaled down
  Model m = placedPack(size * grow, false, n, a, b, 1);
  for (std::size_t i = 0; i < m.particles.size(); ++i) {
    m.particles.position[i] /= grow;
    m.particles.radius[i] /= grow;
  }
  m.domain.size = size;
  m.material.youngsModulus = 1e10;
  updateMassProperties(m);
  CompactParameters c;
  c.targetPorosity = porosity;
  compactElements(m, c);
  CementParameters cp;
  cp.bondRange = 1.4;
  cp.bondModulus = 1e10;
  cp.bondStiffnessRatio = 0.4;
  cp.tensileStrength = 1e12; // unbreakable: the elastic range only
  cp.cohesion = 1e12;
  cp.strengthScatter = 0.0;
  ASSERT_GT(cement(m, cp).bonds, 2500u);

  // The affine estimate from the bonds (stiffness per bond kn_bar A, ks_bar A).
  std::map<std::int64_t, std::size_t> slot;
  for (std::size_t i = 0; i < m.particles.size(); ++i) {
    slot[m.particles.id[i]] = i;
  }
  double C[3][3][3][3] = {};
  const double volume = size.x() * size.y() * size.z();
  for (std::size_t k = 0; k < m.bonds.size(); ++k) {
    const Vec3 d = m.particles.position[slot[m.bonds.idB[k]]] - m.particles.position[slot[m.bonds.idA[k]]];
    const double L = d.norm();
    const Vec3 u = d / L;
    const double area = pi * m.bonds.radius[k] * m.bonds.radius[k];
    const double kn = m.bonds.normalStiffness[k] * area;
    const double ks = m.bonds.shearStiffness[k] * area;
    for (int i = 0; i < 3; ++i) for (int j = 0; j < 3; ++j) for (int q = 0; q < 3; ++q) for (int l = 0; l < 3; ++l) {
      const double nn = u[i] * u[j] * u[q] * u[l];
      C[i][j][q][l] += L * L * (kn * nn + ks * ((i == q ? u[j] * u[l] : 0.0) - nn)) / volume;
    }
  }
  const int voigt[6][2] = { { 0, 0 }, { 1, 1 }, { 2, 2 }, { 1, 2 }, { 0, 2 }, { 0, 1 } };
  Eigen::Matrix<double, 6, 6> M;
  for (int r = 0; r < 6; ++r) {
    for (int s = 0; s < 6; ++s) {
      const int i = voigt[r][0], j = voigt[r][1], q = voigt[s][0], l = voigt[s][1];
      M(r, s) = 0.25 * (C[i][j][q][l] + C[j][i][q][l] + C[i][j][l][q] + C[j][i][l][q]) * (s >= 3 ? 2.0 : 1.0);
    }
  }
  const Eigen::Matrix<double, 6, 6> S = M.inverse();
  const double affineE = 1.0 / S(2, 2);
  const double affineNu = -0.5 * (S(0, 2) + S(1, 2)) / S(2, 2);

  LoadTestSettings s;
  s.mode = TestMode::Compression;
  s.maxStrain = 4e-4;
  s.sampleInterval = 50;
  startLoadTest(m, s);
  {
    Simulation probe(m);
    s.strainRate = 1e-7 / probe.timestep(); // 1e-7 platen strain per step: quasi-static
  }
  startLoadTest(m, s);
  Simulation sim(m);
  runUntilDone(m, sim, 100);
  ASSERT_EQ(m.test.stage, TestStage::Done);
  const std::size_t platen = column("Strain Z"), gauge = column("Gauge Strain"), stress = column("Axial Stress (Pa)");
  std::vector<double> ep, eg, lat, sig;
  for (const auto& row : m.test.history) {
    if (row[platen] > 1e-4) { // past the platens' seating
      ep.push_back(row[platen]);
      eg.push_back(row[gauge]);
      lat.push_back(0.5 * (row[column("Strain X")] + row[column("Strain Y")]));
      sig.push_back(row[stress]);
    }
  }
  ASSERT_GE(ep.size(), 20u);
  auto slope = [](const std::vector<double>& x, const std::vector<double>& y) {
    double mx = 0.0, my = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      mx += x[i];
      my += y[i];
    }
    mx /= static_cast<double>(x.size());
    my /= static_cast<double>(x.size());
    double sxy = 0.0, sxx = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      sxy += (x[i] - mx) * (y[i] - my);
      sxx += (x[i] - mx) * (x[i] - mx);
    }
    return sxy / sxx;
  };
  const double gaugeE = slope(eg, sig), gaugeNu = -slope(eg, lat);
  const double platenE = slope(ep, sig), platenNu = -slope(ep, lat);
  std::printf("[gauge] %zu bonds: affine E %.4g Pa nu %.4f; gauge E %.4g Pa nu %.4f; platen E %.4g Pa nu %.4f\n",
              m.bonds.size(), affineE, affineNu, gaugeE, gaugeNu, platenE, platenNu);
  EXPECT_NEAR(gaugeE / affineE, 1.0, 0.15);
  EXPECT_NEAR(gaugeNu, affineNu, 0.03);
  EXPECT_LT(platenE, 0.5 * gaugeE) << "the platen contacts' compliance is left out of the gauge";
}

// Setting Mode back to Off restores all six walls at the box.
TEST(Press, ModeOffRestoresTheBox)
{
  Model m = specimen(300, 0.02, 0.001, 0.0015);
  LoadTestSettings s;
  s.mode = TestMode::Compression;
  startLoadTest(m, s);
  ASSERT_FALSE(m.walls[0].active);
  s.mode = TestMode::Off;
  startLoadTest(m, s);
  for (int w = 0; w < 6; ++w) {
    EXPECT_TRUE(m.walls[w].active) << w;
    const double face = m.walls[w].side == 0 ? m.domain.origin[m.walls[w].axis]
                                             : m.domain.origin[m.walls[w].axis] + m.domain.size[m.walls[w].axis];
    EXPECT_EQ(m.walls[w].position, face) << w;
  }
  EXPECT_EQ(m.test.stage, TestStage::Idle);
}

TEST(Press, HistoryHasTheDocumentedColumns)
{
  const auto& c = historyColumns();
  ASSERT_EQ(c.size(), HistoryColumnCount);
  for (const char* name : { "Time (s)", "Strain X", "Strain Y", "Strain Z", "Volumetric Strain",
         "Stress Z+ (Pa)", "Sigma XX (Pa)", "Sigma ZX (Pa)", "Axial Stress (Pa)", "Lateral Stress (Pa)",
         "Deviator Stress (Pa)", "Broken In Tension", "Broken In Shear", "Unbalanced Force Ratio",
         "Inertial Number", "Stage" }) {
    EXPECT_NE(std::find(c.begin(), c.end(), name), c.end()) << name;
  }
}

TEST(Press, BadSettingsAreNamed)
{
  Model m = specimen(100, 0.02, 0.001, 0.0015);
  LoadTestSettings s;
  s.mode = TestMode::Triaxial;
  s.confiningStress = 0.0;
  try {
    startLoadTest(m, s);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("Confining Stress"), std::string::npos) << e.what();
  }
  s.confiningStress = 1e5;
  s.servoAlpha = 1.5;
  EXPECT_THROW(startLoadTest(m, s), InputError);
}

namespace {

// Each bad value of one press setting (`field`) is refused by startLoadTest, naming the
// parameter, its value and the valid range; `good` (the edge of the range) is accepted.
void expectOutOfRangeNamed(TestMode mode, double LoadTestSettings::*field, const std::string& name,
                           const std::string& range, std::initializer_list<double> bad, double good)
{
  Model m = specimen(100, 0.02, 0.001, 0.0015);
  LoadTestSettings s;
  s.mode = mode;
  for (double value : bad) {
    s.*field = value;
    try {
      startLoadTest(m, s);
      ADD_FAILURE() << name << " " << value << " accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(name + " = "), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("is out of range: valid range is " + range), std::string::npos) << e.what();
    }
  }
  s.*field = good;
  EXPECT_NO_THROW(startLoadTest(m, s)) << name << " " << good;
}

} // namespace

TEST(Press, PlatenFrictionOutOfRangeIsNamed)
{
  expectOutOfRangeNamed(TestMode::Compression, &LoadTestSettings::platenFriction, "Platen Friction", "[0, 1]",
                        { -0.1, 1.5, std::nan("") }, 1.0);
}

TEST(Press, ConsolidationDampingOutOfRangeIsNamed)
{
  expectOutOfRangeNamed(TestMode::Triaxial, &LoadTestSettings::consolidationDamping, "Consolidation Damping",
                        "[0, 1)", { -0.1, 1.0, std::nan("") }, 0.0);
}

// Consolidation Damping (LoadTest.md): a Triaxial test brings the specimen to the confining
// stress at it and shears at Settling Damping. Two runs that differ only in Settling Damping
// (0.7 and 0), both consolidating at 0.7, are the same bit for bit at every sample until the
// shear starts, and differ once it runs; a run consolidating at 0 differs from the start.
TEST(Press, TriaxialConsolidatesAtConsolidationDampingAndShearsAtSettlingDamping)
{
  Model base = specimen(400, 0.016, 0.0008, 0.0012, 3);
  consolidate(base, 2e4);
  ASSERT_GT(cement(base, testCement()).bonds, 500u);
  LoadTestSettings s;
  s.mode = TestMode::Triaxial;
  s.confiningStress = 2e5;
  s.strainRate = 1.0;
  s.maxStrain = 0.01;
  s.sampleInterval = 50;
  s.consolidationDamping = 0.7;
  Model damped = base;
  damped.solver.settlingDamping = 0.7;
  startLoadTest(damped, s);
  Model undamped = base;
  undamped.solver.settlingDamping = 0.0;
  startLoadTest(undamped, s);
  Model raw = base; // consolidates undamped too
  raw.solver.settlingDamping = 0.0;
  s.consolidationDamping = 0.0;
  startLoadTest(raw, s);
  Simulation a(damped), b(undamped), c(raw);
  EXPECT_EQ(localDamping(undamped.test, undamped.solver.settlingDamping), 0.7) << "consolidating";
  int samples = 0;
  for (; samples < 1000 && undamped.test.stage == TestStage::Consolidate; ++samples) {
    a.advance(50);
    b.advance(50);
    c.advance(50);
    const std::string difference = statetest::firstDifference(damped, undamped);
    ASSERT_EQ(difference, "") << "Settling Damping acted while consolidating (sample " << samples << ")";
  }
  ASSERT_EQ(undamped.test.stage, TestStage::Shear) << "consolidated within " << samples << " samples";
  EXPECT_GT(samples, 2);
  EXPECT_NE(statetest::firstDifference(undamped, raw), "") << "the consolidation's damping is what it ran at";
  EXPECT_EQ(localDamping(undamped.test, undamped.solver.settlingDamping), 0.0) << "shearing";
  a.advance(500);
  b.advance(500);
  EXPECT_NE(statetest::firstDifference(damped, undamped), "") << "the shear runs at Settling Damping";
  // Outside a confined test's consolidation the solver's Settling Damping holds.
  LoadTestState off;
  EXPECT_EQ(localDamping(off, 0.25), 0.25);
  off.settings.mode = TestMode::Compression;
  off.stage = TestStage::Consolidate;
  EXPECT_EQ(localDamping(off, 0.25), 0.25);
  off.settings.mode = TestMode::Isotropic;
  EXPECT_EQ(localDamping(off, 0.25), 0.7);
}

// Platen Friction acts on the platens with the Coulomb coefficient given. Reference: a
// solid sphere sliding on a floor with friction mu decelerates at mu g while it slides
// and rolls on at 5/7 of its initial speed (rigid-body mechanics, e.g. Goldsmith 1960);
// on a frictionless platen it keeps its speed.
TEST(Press, PlatenFrictionIsCoulombFrictionOnThePlatens)
{
  const double v0 = 0.1; // m/s along X
  const double r = 0.001;
  const double g = 9.81;
  for (double mu : { 0.0, 0.3 }) {
    Model m = emptyModel(1e8, 0.3, 2600.0, 0.5, 0.02);
    m.gravity = Vec3(0.0, 0.0, -g);
    addSphere(m, Vec3(-0.008, 0.0, -0.01 + r), r, Vec3(v0, 0.0, 0.0));
    LoadTestSettings s;
    s.mode = TestMode::Compression; // platens on Z at the sphere's extent; no side walls
    s.strainRate = 1e-6;            // the upper platen hardly moves
    s.maxStrain = 0.5;
    s.platenFriction = mu;
    startLoadTest(m, s);
    Simulation sim(m);
    const double dt = sim.timestep();
    const double tSliding = 2.0 * v0 / (7.0 * 0.3 * g); // s, when rolling starts at mu 0.3
    const auto halfway = static_cast<int>(0.5 * tSliding / dt);
    sim.advance(halfway);
    const double t = halfway * dt;
    const double vHalf = m.particles.velocity[0].x();
    sim.advance(2 * halfway);
    const double vEnd = m.particles.velocity[0].x();
    if (mu == 0.0) {
      EXPECT_NEAR(vHalf, v0, 1e-9 * v0) << "a frictionless platen exerts no tangential force";
      EXPECT_NEAR(vEnd, v0, 1e-9 * v0);
    } else {
      EXPECT_NEAR(vHalf, v0 - mu * g * t, 0.02 * mu * g * t) << "sliding: deceleration mu g";
      EXPECT_NEAR(vEnd, 5.0 / 7.0 * v0, 0.01 * v0) << "rolling at 5/7 of the initial speed";
    }
  }
}

// A run that goes unstable keeps its last good state (DESIGN.md, Stability) in full: the
// bonds broken and the history rows written by the failed batch are taken back with the
// particles, so the model is the one from before the batch.
TEST(Press, UnstableBatchRestoresBondsAndTestState)
{
  Model m = specimen(150, 0.012, 0.0008, 0.0012, 2);
  ASSERT_GT(cement(m, testCement()).bonds, 50u);
  LoadTestSettings s;
  s.mode = TestMode::Compression;
  s.strainRate = 1.0;
  s.sampleInterval = 10;
  startLoadTest(m, s);
  {
    Simulation warmUp(m);
    warmUp.advance(200);
  }
  ASSERT_FALSE(m.test.history.empty());
  m.solver.allowUnsafeTimestep = true; // test-only switch: force the blow-up
  m.solver.settlingDamping = 0.0;
  m.solver.requestedTimestep = 5.0 * Simulation(m).criticalTimestep();
  Simulation sim(m);
  const Model before = m;
  EXPECT_THROW(sim.advance(100000), InstabilityError);
  EXPECT_EQ(m.clock.step, before.clock.step);
  EXPECT_EQ(m.particles.position, before.particles.position);
  EXPECT_EQ(m.bonds.failure, before.bonds.failure) << "bonds broken by the failed batch are restored";
  EXPECT_EQ(m.bonds.normalForce, before.bonds.normalForce);
  // Every array stepping changes (dem::BondStepState), and the others as they were.
  EXPECT_EQ(m.bonds.shearForce, before.bonds.shearForce);
  EXPECT_EQ(m.bonds.twistingMoment, before.bonds.twistingMoment);
  EXPECT_EQ(m.bonds.bendingMoment, before.bonds.bendingMoment);
  EXPECT_EQ(m.bonds.damage, before.bonds.damage);
  EXPECT_EQ(m.bonds.failureTime, before.bonds.failureTime);
  EXPECT_EQ(m.bonds.failurePosition, before.bonds.failurePosition);
  EXPECT_EQ(m.bonds.failureNormal, before.bonds.failureNormal);
  EXPECT_EQ(m.bonds.idA, before.bonds.idA);
  EXPECT_EQ(m.bonds.tensileStrength, before.bonds.tensileStrength);
  EXPECT_EQ(m.test.history, before.test.history) << "no history rows from the failed batch";
  EXPECT_EQ(m.test.peakStress, before.test.peakStress);
}

// A stage continues the input's test only when that test is in progress with exactly the
// stage's settings (a reopened state file), or when both are Off; anything else starts
// a new test (DESIGN.md, time contract; Documentation/StateFile.md).
TEST(Press, ContinuesOnlyATestInProgressWithTheSameSettings)
{
  LoadTestState t;
  t.settings.mode = TestMode::Triaxial;
  t.settings.confiningStress = 1e5;
  t.stage = TestStage::Shear;
  LoadTestSettings same = t.settings;
  EXPECT_TRUE(continuesTest(t, same));
  t.stage = TestStage::Consolidate;
  EXPECT_TRUE(continuesTest(t, same));
  LoadTestSettings faster = same;
  faster.strainRate *= 2.0;
  EXPECT_FALSE(continuesTest(t, faster)) << "another strain rate is another test";
  t.stage = TestStage::Done;
  EXPECT_FALSE(continuesTest(t, same)) << "a finished test is not continued";
  LoadTestSettings off;
  EXPECT_FALSE(continuesTest(t, off)) << "Mode Off after a press restores the box";
  LoadTestState idle;
  EXPECT_TRUE(continuesTest(idle, off)) << "Off after Off keeps the walls";
  EXPECT_FALSE(continuesTest(idle, same)) << "an idle model starts the test";
}

namespace {

/// A grown 2D section (discs in the XY plane, slab 1 mm) without gravity.
Model section2D(int n, double side, std::uint64_t seed = 5)
{
  Model m = placedPack(Vec3(side, side, 0.001), true, n, 0.0005, 0.00075, seed);
  growElements(m);
  return m;
}

} // namespace

// A 2D section is loaded in its plane: the slab axis Z has no walls and needs none, so the
// isotropic test (X and Y faces) and the biaxial test (Triaxial: X faces confining, Y
// platens) run (reference: plane-strain equilibrium, the servo's target), while loading
// along Z is refused, naming the axis.
TEST(Press, Section2DIsotropicAndBiaxialHoldTheConfiningStressInThePlane)
{
  Model iso = section2D(300, 0.03);
  LoadTestSettings s;
  s.mode = TestMode::Isotropic;
  s.axis = 1;
  s.confiningStress = 1e5;
  s.sampleInterval = 200;
  startLoadTest(iso, s);
  EXPECT_FALSE(iso.walls[4].active || iso.walls[5].active) << "no walls on the slab axis";
  Simulation sim(iso);
  runUntilDone(iso, sim, 100);
  ASSERT_EQ(iso.test.stage, TestStage::Done) << "stops once settled";
  TestMeasurements me = sim.measurements();
  for (int w = 0; w < 4; ++w) {
    EXPECT_NEAR(me.faceStress[w], 1e5, 0.02e5) << "face " << w;
  }
  EXPECT_EQ(me.faceStress[4], 0.0);
  EXPECT_EQ(me.faceStress[5], 0.0);
  EXPECT_NEAR(me.meanStress, 1e5, 0.03e5) << "Love-Weber mean stress of the section, (sxx + syy) / 2";

  Model bi = section2D(300, 0.03);
  s.mode = TestMode::Triaxial;
  s.axis = 1;
  s.strainRate = 0.5;
  s.maxStrain = 0.02;
  startLoadTest(bi, s);
  Simulation run(bi);
  runUntilDone(bi, run, 200);
  ASSERT_EQ(bi.test.stage, TestStage::Done);
  const auto rows = shearRows(bi);
  for (const auto& row : rows) {
    for (const char* side : { "Stress X- (Pa)", "Stress X+ (Pa)" }) {
      EXPECT_NEAR(row[column(side)], 1e5, 0.02e5) << side << " at strain " << row[column("Strain Y")];
    }
    EXPECT_EQ(row[column("Strain Z")], 0.0) << "the slab does not strain";
  }
  ASSERT_GT(rows.size(), 10u);
  EXPECT_GT(rows.back()[column("Deviator Stress (Pa)")], 0.1e5) << "the platen loads the section";
  for (const Vec3& x : bi.particles.position) {
    ASSERT_EQ(x.z(), bi.domain.midPlaneZ()) << "the discs stay in the plane";
  }

  Model flat = section2D(300, 0.03);
  s.axis = 2;
  for (const TestMode mode : { TestMode::Triaxial, TestMode::Isotropic, TestMode::Compression }) {
    s.mode = mode;
    try {
      startLoadTest(flat, s);
      FAIL() << modeName(mode) << " along the slab axis";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("Axis = Z"), std::string::npos) << e.what();
    }
  }
}

// Direct tension of a cemented 2D section along Y: the grips hold the discs next to each
// platen, the pull over the section's area (width x slab) reads negative, rises to a peak
// and falls as the bonds break between the grips; the discs stay in the plane.
TEST(Press, Section2DDirectTensionBreaksTheSectionBetweenTheGrips)
{
  Model m = section2D(300, 0.03, 7);
  ASSERT_EQ(m.particles.size(), 300u);
  CompactParameters dense;
  dense.targetPorosity = 0.18;
  compactElements(m, dense);
  CementParameters c = testCement();
  c.bondRange = 1.2;
  ASSERT_GT(cement(m, c).bonds, 2 * m.particles.size()) << "bonded coordination above 4";
  LoadTestSettings s;
  s.mode = TestMode::Tension;
  s.axis = 1;
  s.strainRate = 1.0;
  s.maxStrain = 0.05;
  s.sampleInterval = 50;
  startLoadTest(m, s);
  double rmax = 0.0;
  for (double r : m.particles.radius) {
    rmax = std::max(rmax, r);
  }
  const double low = m.walls[2].position + 2.0 * rmax; // Grip Length 1: one largest diameter
  const double high = m.walls[3].position - 2.0 * rmax;
  Simulation sim(m);
  double least = 0.0;
  while (m.test.stage != TestStage::Done) {
    sim.advance(s.sampleInterval);
    const double sigma = sim.measurements().axialStress;
    least = std::min(least, sigma);
    if (m.test.peakStress > 0.0 && -sigma < 0.5 * m.test.peakStress) {
      break; // failed: the pull has fallen below half its peak
    }
  }
  EXPECT_GT(m.test.peakStress, 0.0);
  EXPECT_NEAR(-least, m.test.peakStress, 1e-9 * m.test.peakStress) << "Peak Stress is the largest pull";
  std::size_t broken = 0, gauge = 0;
  for (std::size_t b = 0; b < m.bonds.size(); ++b) {
    if (m.bonds.broken(b)) {
      ++broken;
      const double y = m.bonds.failurePosition[b].y();
      gauge += (y > low && y < high) ? 1 : 0;
    }
  }
  EXPECT_GT(broken, 5u);
  EXPECT_GE(static_cast<double>(gauge), 0.8 * static_cast<double>(broken)) << "the section breaks between the grips";
  for (const Vec3& x : m.particles.position) {
    ASSERT_EQ(x.z(), m.domain.midPlaneZ()) << "the discs stay in the plane";
  }
}
