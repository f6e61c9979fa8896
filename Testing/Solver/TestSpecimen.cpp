// DEM Specimen (dem/Specimen.h): carving a box, a cylinder or a disc out of a dense pack,
// in 3D and in a 2D section, and the errors for specimens that cannot be carved.
#include "Specimens.h"

#include "dem/Errors.h"
#include "dem/Membrane.h"
#include "dem/Specimen.h"
#include "dem/WallControl.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

using namespace dem;
using dem::testing::specimen;

namespace {

constexpr double kPi = 3.14159265358979323846;

double solidVolume(const Model& m)
{
  double v = 0.0;
  for (double r : m.particles.radius) {
    v += particleVolume(m.domain, r);
  }
  return v;
}

/// A grown 2D section pack: n discs with radii in [rmin, rmax] m in a square of the given
/// side (m), slab thickness `slab` (m), without gravity.
Model section2DPack(int n, double side, double slab, double rmin, double rmax, std::uint64_t seed = 1)
{
  Model m = dem::testing::placedPack(Vec3(side, side, slab), true, n, rmin, rmax, seed);
  growElements(m);
  return m;
}

/// Checks that `carved` holds exactly the particles of `pack` whose centres lie inside the
/// specimen (by id, same positions), that its box is their bounding box and that its
/// walls stand at that box, with no test running.
void expectCarvedFrom(const Model& pack, const Model& carved, const SpecimenSettings& s)
{
  std::size_t inside = 0;
  for (std::size_t i = 0; i < pack.particles.size(); ++i) {
    inside += insideSpecimen(s, pack.domain, pack.particles.position[i]) ? 1 : 0;
  }
  ASSERT_EQ(carved.particles.size(), inside);
  ASSERT_GT(inside, 0u);
  const Vec3 c = specimenCenter(s, pack.domain);
  Vec3 lo = Vec3::Constant(1e300);
  Vec3 hi = -lo;
  for (std::size_t i = 0; i < carved.particles.size(); ++i) {
    const Vec3& x = carved.particles.position[i];
    EXPECT_TRUE(insideSpecimen(s, pack.domain, x)) << "particle " << carved.particles.id[i];
    const Vec3 r = x - c;
    if (s.shape != SpecimenShape::Box) {
      const int a = pack.domain.section2D ? 2 : s.axis;
      const double radial = std::hypot(r[(a + 1) % 3], r[(a + 2) % 3]);
      EXPECT_LE(radial, 0.5 * s.diameter);
      if (!pack.domain.section2D) {
        EXPECT_LE(std::abs(r[a]), 0.5 * s.length);
      }
    }
    lo = lo.cwiseMin(x - Vec3::Constant(carved.particles.radius[i]));
    hi = hi.cwiseMax(x + Vec3::Constant(carved.particles.radius[i]));
  }
  const int dims = pack.domain.section2D ? 2 : 3;
  for (int k = 0; k < dims; ++k) {
    EXPECT_DOUBLE_EQ(carved.domain.origin[k], lo[k]);
    EXPECT_DOUBLE_EQ(carved.domain.size[k], hi[k] - lo[k]);
    EXPECT_DOUBLE_EQ(carved.walls[2 * k].position, lo[k]);
    EXPECT_DOUBLE_EQ(carved.walls[2 * k + 1].position, hi[k]);
  }
  if (pack.domain.section2D) {
    EXPECT_EQ(carved.domain.size.z(), pack.domain.size.z()); // the slab is kept
  }
  EXPECT_EQ(carved.test.settings.mode, TestMode::Off);
}

std::string errorOf(const Model& pack, const SpecimenSettings& s)
{
  Model m = pack;
  try {
    carveSpecimen(m, s);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

/// Shape Cylinder, 12 mm across and 18 mm long along `axis`.
SpecimenSettings cylinderSettings(int axis = 2)
{
  SpecimenSettings s;
  s.axis = axis;
  s.diameter = 0.012;
  s.length = 0.018;
  return s;
}

/// The cylinder the press tests use: 12 mm across, 18 mm long along `axis`, carved from
/// the 1,500-grain pack in a 20 mm cube.
Model carvedCylinder(int axis = 2)
{
  Model m = specimen(1500, 0.02, 0.0005, 0.0008, 3);
  carveSpecimen(m, cylinderSettings(axis));
  return m;
}

} // namespace

TEST(Specimen, CylinderKeepsTheCentresInsideAndShrinksTheBox)
{
  const Model pack = specimen(1500, 0.02, 0.0005, 0.0008, 3);
  for (int axis = 0; axis < 3; ++axis) {
    SpecimenSettings s;
    s.shape = SpecimenShape::Cylinder;
    s.axis = axis;
    s.diameter = 0.012;
    s.length = 0.018;
    Model m = pack;
    const SpecimenReport r = carveSpecimen(m, s);
    expectCarvedFrom(pack, m, s);
    EXPECT_EQ(r.kept + r.removed.particles, pack.particles.size());
    EXPECT_DOUBLE_EQ(r.porosity, 1.0 - solidVolume(m) / (0.25 * kPi * s.diameter * s.diameter * s.length));
    // The box along the axis is the long one, the two others about the diameter.
    EXPECT_GT(m.domain.size[axis], 0.016);
    EXPECT_NEAR(m.domain.size[(axis + 1) % 3], 0.012, 0.002);
    EXPECT_NEAR(m.domain.size[(axis + 2) % 3], 0.012, 0.002);
  }
}

TEST(Specimen, BoxAndDiscOffCentre)
{
  const Model pack = specimen(1500, 0.02, 0.0005, 0.0008, 3);
  SpecimenSettings box;
  box.shape = SpecimenShape::Box;
  box.centerOnModel = false;
  box.center = Vec3(0.008, 0.011, 0.01);
  box.size = Vec3(0.01, 0.014, 0.006);
  Model m = pack;
  carveSpecimen(m, box);
  expectCarvedFrom(pack, m, box);

  SpecimenSettings disc;
  disc.shape = SpecimenShape::Disc;
  disc.axis = 1;
  disc.diameter = 0.016;
  disc.length = 0.008;
  Model d = pack;
  carveSpecimen(d, disc);
  expectCarvedFrom(pack, d, disc);
  const double rmax = *std::max_element(pack.particles.radius.begin(), pack.particles.radius.end());
  EXPECT_LE(d.domain.size.y(), disc.length + 2.0 * rmax); // the thin axis of the disc
}

TEST(Specimen, TwoDimensionalRectangleAndDisc)
{
  const Model pack = section2DPack(800, 0.03, 0.001, 0.0004, 0.0006, 2);
  SpecimenSettings disc;
  disc.shape = SpecimenShape::Disc;
  disc.diameter = 0.024;
  Model d = pack;
  const SpecimenReport r = carveSpecimen(d, disc);
  expectCarvedFrom(pack, d, disc);
  EXPECT_DOUBLE_EQ(r.porosity, 1.0 - solidVolume(d) / (0.25 * kPi * disc.diameter * disc.diameter * 0.001));

  SpecimenSettings rectangle;
  rectangle.shape = SpecimenShape::Box;
  rectangle.size = Vec3(0.01, 0.02, 0.0); // Size Z is not used in 2D: the slab is the thickness
  Model b = pack;
  carveSpecimen(b, rectangle);
  expectCarvedFrom(pack, b, rectangle);
}

TEST(Specimen, CarvedSpecimenRunsAndTests)
{
  Model m = carvedCylinder();
  LoadTestSettings ucs;
  ucs.mode = TestMode::Compression;
  ucs.strainRate = 0.05;
  startLoadTest(m, ucs);
  EXPECT_DOUBLE_EQ(m.walls[4].position, m.domain.origin.z()); // the platens start on the specimen
  EXPECT_DOUBLE_EQ(m.walls[5].position, m.domain.upper().z());
  Simulation sim(m);
  sim.advance(400);
  EXPECT_GT(sim.measurements().strain[2], 0.0);
  EXPECT_EQ(m.test.stage, TestStage::Shear);
}

namespace {

/// The particles' extent along axis k (m): their surfaces, min to max.
double extent(const Model& m, int k)
{
  double lo = 1e300;
  double hi = -1e300;
  for (std::size_t i = 0; i < m.particles.size(); ++i) {
    lo = std::min(lo, m.particles.position[i][k] - m.particles.radius[i]);
    hi = std::max(hi, m.particles.position[i][k] + m.particles.radius[i]);
  }
  return hi - lo;
}

/// Runs `steps` steps of a load test and returns the press's measurements.
TestMeasurements runTest(Model& m, const LoadTestSettings& s, int steps)
{
  startLoadTest(m, s);
  Simulation sim(m);
  sim.advance(steps);
  return sim.measurements();
}

/// The grown pack is loose (no gravity, no cement): the grains a platen first touches are
/// knocked away, and the platens push the specimen only once they have closed its surface
/// gaps. The first multiple of 500 steps, from 1,500 to 10,000, after which they push.
int stepsUntilPushed(const Model& m, const LoadTestSettings& s)
{
  Model run = m;
  startLoadTest(run, s);
  Simulation sim(run);
  int steps = 1500;
  sim.advance(steps);
  while (!(sim.measurements().axialStress > 0.0) && steps < 10000) {
    sim.advance(500);
    steps += 500;
  }
  std::printf("[cylinder] the platens push after %d steps\n", steps);
  return steps;
}

} // namespace

TEST(Specimen, CarvingSetsTheOutlineThePressMeasuresWith)
{
  const Model pack = specimen(1500, 0.02, 0.0005, 0.0008, 3);
  EXPECT_EQ(pack.domain.cylinderAxis, -1); // a pack is a box
  for (int axis = 0; axis < 3; ++axis) {
    SpecimenSettings s;
    s.shape = axis == 1 ? SpecimenShape::Disc : SpecimenShape::Cylinder;
    s.axis = axis;
    s.diameter = 0.012;
    s.length = axis == 1 ? 0.006 : 0.018;
    Model m = pack;
    carveSpecimen(m, s);
    EXPECT_EQ(m.domain.cylinderAxis, axis) << specimenShapeName(s.shape) << " along " << axis;
    SpecimenSettings box;
    box.shape = SpecimenShape::Box;
    box.size = Vec3(0.004, 0.004, 0.004);
    carveSpecimen(m, box); // a box carved out of the cylinder is a box again
    EXPECT_EQ(m.domain.cylinderAxis, -1);
  }
  const Model section = section2DPack(800, 0.03, 0.001, 0.0004, 0.0006, 2);
  SpecimenSettings disc;
  disc.shape = SpecimenShape::Disc;
  disc.diameter = 0.024;
  Model d = section;
  carveSpecimen(d, disc);
  EXPECT_EQ(d.domain.cylinderAxis, 2); // a 2D disc: a cylinder along Z through the slab
}

// A carved cylinder's axial stress is the platen force over its circular cross-section,
// pi D^2 / 4 (ISRM 1979, the suggested method for the UCS of cylinders), not over the
// square of its bounding box. D starts as twice the mean outer reach of the surface
// grains, the membrane's radius; the same grains measured as a box read the push over the
// square of their extents.
TEST(Specimen, CompressionOfACylinderDividesThePlatenForceByItsCircularSection)
{
  const SpecimenSettings s = cylinderSettings();
  Model cylinder = carvedCylinder();
  ASSERT_EQ(cylinder.domain.cylinderAxis, 2);
  const double extentX = extent(cylinder, 0);
  const double extentY = extent(cylinder, 1);
  Model box = cylinder;
  box.domain.cylinderAxis = -1; // the same grains, measured as a box
  Model membrane = cylinder;
  LoadTestSettings ucs;
  ucs.mode = TestMode::Compression;
  ucs.strainRate = 2.0;
  const int steps = stepsUntilPushed(cylinder, ucs);
  const TestMeasurements c = runTest(cylinder, ucs, steps);
  ASSERT_GT(c.axialStress, 0.0);
  // The diameter at the start: the surface grains' mean outer reach, below the grains'
  // extent (their outermost points) and near the carved diameter (this grown pack is not
  // compacted: its surface is rough, and the mean reach falls 7 % short of the carved one).
  const double d0 = cylinder.test.initialLength[0];
  EXPECT_EQ(cylinder.test.initialLength[1], d0);
  EXPECT_NEAR(d0 / s.diameter, 1.0, 0.1);
  EXPECT_LT(d0, std::min(extentX, extentY));
  // ... the membrane's diameter at the start of an isotropic test of the same grains.
  LoadTestSettings iso;
  iso.mode = TestMode::Isotropic;
  iso.confinement = Confinement::Membrane;
  iso.confiningStress = 1e4;
  startLoadTest(membrane, iso);
  EXPECT_EQ(membrane.test.initialLength[0], d0);
  // The stress: the mean push of the two platens over the ellipse of the lateral lengths.
  const double push = -0.5 * (cylinder.walls[4].force.dot(cylinder.walls[4].normal()) +
                              cylinder.walls[5].force.dot(cylinder.walls[5].normal()));
  const std::array<double, 3> length = specimenLengths(cylinder);
  EXPECT_NEAR(c.axialStress, push / (0.25 * kPi * length[0] * length[1]), 1e-12 * c.axialStress);
  EXPECT_NEAR(length[0] / d0, 1.0, 0.01); // a small lateral strain
  // The same grains as a box: the box's extents (the outermost grains) and no pi/4.
  const TestMeasurements b = runTest(box, ucs, steps);
  ASSERT_EQ(cylinder.particles.position, box.particles.position); // the outline changes no motion
  const std::array<double, 3> boxLength = specimenLengths(box);
  EXPECT_NEAR(b.axialStress, push / (boxLength[0] * boxLength[1]), 1e-12 * b.axialStress);
  EXPECT_NEAR(box.test.initialLength[0], extentX, 1e-15);
  const double sectionRatio = (0.25 * kPi * length[0] * length[1]) / (boxLength[0] * boxLength[1]);
  EXPECT_NEAR(c.axialStress * sectionRatio / b.axialStress, 1.0, 1e-12);
  EXPECT_NEAR(c.faceStress[5] * sectionRatio / b.faceStress[5], 1.0, 1e-12);
  // Love-Weber: the same internal forces over the cylinder's volume.
  const double volumeRatio = sectionRatio * length[2] / boxLength[2];
  EXPECT_NEAR(c.stressTensor[2] * volumeRatio / b.stressTensor[2], 1.0, 1e-12);

  // Across its axis the section through a cylinder's middle is the rectangle D x L: a
  // cylinder along Y compressed along Z reads as the box does (its lengths the extents).
  Model across = carvedCylinder(1);
  Model acrossBox = across;
  acrossBox.domain.cylinderAxis = -1;
  const int acrossSteps = stepsUntilPushed(across, ucs);
  const TestMeasurements ca = runTest(across, ucs, acrossSteps);
  const TestMeasurements ba = runTest(acrossBox, ucs, acrossSteps);
  ASSERT_GT(ca.axialStress, 0.0);
  EXPECT_EQ(ca.axialStress, ba.axialStress);
  EXPECT_NEAR(ca.meanStress / ba.meanStress, 4.0 / kPi, 1e-12); // its volume is still pi/4 of the box
}

TEST(Specimen, DirectTensionOfACylinderDividesThePullByItsCircularSection)
{
  const SpecimenSettings s = cylinderSettings();
  Model cylinder = carvedCylinder();
  cement(cylinder, dem::testing::testCement());
  ASSERT_GT(cylinder.bonds.size(), 0u);
  Model box = cylinder;
  box.domain.cylinderAxis = -1;
  LoadTestSettings pull;
  pull.mode = TestMode::Tension;
  pull.strainRate = 0.05;
  const TestMeasurements c = runTest(cylinder, pull, 400);
  const TestMeasurements b = runTest(box, pull, 400);
  ASSERT_LT(c.axialStress, 0.0);
  ASSERT_EQ(cylinder.particles.position, box.particles.position);
  const std::array<double, 3> length = specimenLengths(cylinder);
  const std::array<double, 3> boxLength = specimenLengths(box);
  EXPECT_NEAR(cylinder.test.initialLength[0] / s.diameter, 1.0, 0.1); // the surface grains' reach
  EXPECT_LT(cylinder.test.initialLength[0], box.test.initialLength[0]); // not the outermost grain
  const double sectionRatio = (0.25 * kPi * length[0] * length[1]) / (boxLength[0] * boxLength[1]);
  EXPECT_NEAR(c.axialStress * sectionRatio / b.axialStress, 1.0, 1e-12);
  EXPECT_GT(cylinder.test.peakStress, box.test.peakStress); // Tensile Strength: the smaller section
}

TEST(Specimen, BadSpecimensAreRefusedNamingTheParameter)
{
  const Model pack = specimen(300, 0.02, 0.001, 0.0015, 4);
  SpecimenSettings tooWide;
  tooWide.diameter = 0.03;
  tooWide.length = 0.01;
  EXPECT_NE(errorOf(pack, tooWide).find("Diameter = 0.03 m is out of range"), std::string::npos)
    << errorOf(pack, tooWide);
  EXPECT_NE(errorOf(pack, tooWide).find("valid range is (0, 0.02] m"), std::string::npos);

  SpecimenSettings tooLong;
  tooLong.diameter = 0.01;
  tooLong.length = 0.025;
  EXPECT_NE(errorOf(pack, tooLong).find("Length = 0.025 m is out of range"), std::string::npos);

  SpecimenSettings thickDisc;
  thickDisc.shape = SpecimenShape::Disc;
  thickDisc.diameter = 0.01;
  thickDisc.length = 0.012;
  const std::string thick = errorOf(pack, thickDisc);
  EXPECT_NE(thick.find("Length = 0.012 m is out of range for Shape = Disc"), std::string::npos) << thick;
  EXPECT_NE(thick.find("valid range is (0, 0.01] m"), std::string::npos) << thick;

  SpecimenSettings zero;
  zero.diameter = 0.0;
  EXPECT_NE(errorOf(pack, zero).find("Diameter = 0 m is out of range: valid range is (0, inf) m"),
            std::string::npos);

  SpecimenSettings offCentre;
  offCentre.centerOnModel = false;
  offCentre.center = Vec3(0.005, 0.01, 0.01);
  offCentre.diameter = 0.012;
  offCentre.length = 0.01;
  EXPECT_NE(errorOf(pack, offCentre).find("valid range is (0, 0.01] m"), std::string::npos);

  SpecimenSettings outside;
  outside.centerOnModel = false;
  outside.center = Vec3(0.05, 0.01, 0.01);
  EXPECT_NE(errorOf(pack, outside).find("Center X = 0.05 m is out of range"), std::string::npos);

  SpecimenSettings badAxis;
  badAxis.axis = 3;
  EXPECT_NE(errorOf(pack, badAxis).find("Axis = 3 is out of range"), std::string::npos);
  EXPECT_THROW(specimenShape(3), InputError);

  Model flat;
  flat.domain.section2D = true;
  flat.domain.size = Vec3(0.02, 0.02, 0.001);
  flat.particles.append(Vec3(0.01, 0.01, 0.0005), 0.001, 0);
  SpecimenSettings cylinder2D;
  cylinder2D.diameter = 0.01;
  EXPECT_NE(errorOf(flat, cylinder2D).find("Shape = Cylinder needs a 3D pack"), std::string::npos);
  SpecimenSettings discAlongX;
  discAlongX.shape = SpecimenShape::Disc;
  discAlongX.axis = 0;
  discAlongX.diameter = 0.01;
  EXPECT_NE(errorOf(flat, discAlongX).find("Axis = X is out of range for Shape = Disc"), std::string::npos);

  // A failed carve leaves the model as it was (errors come before any change).
  Model kept = pack;
  EXPECT_THROW(carveSpecimen(kept, tooWide), InputError);
  EXPECT_EQ(kept.particles.size(), pack.particles.size());
  EXPECT_EQ(kept.domain.size, pack.domain.size);
}
