// The resolution advice of DEM Load Test (dem/ResolutionAdvice.h): the specimen's width in
// mean grain diameters against its closed form on lattices, and the advice against the
// widths the atlas's resolution sweep measured (Documentation/SpeedAccuracy.md,
// "Resolution": E within 5 % of the finest size from 11.9 across, the direct tensile
// strength from 15.6 across, the UCS still rising at 20 across).
#include "dem/Bonds.h"
#include "dem/LoadTest.h"
#include "dem/Model.h"
#include "dem/ResolutionAdvice.h"

#include <gtest/gtest.h>

#include <string>

using namespace dem;

namespace {

/// nx x ny x nz grains of radius r on a simple cubic lattice of spacing 2 r (touching), so the
/// extent along each axis is n 2 r: n mean diameters. Neighbours along X bonded when `bonded`.
Model lattice(int nx, int ny, int nz, double r, bool bonded)
{
  Model m;
  m.domain.size = Vec3(nx * 2 * r, ny * 2 * r, nz * 2 * r);
  std::int64_t id = 1;
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        m.particles.append(Vec3((2 * i + 1) * r, (2 * j + 1) * r, (2 * k + 1) * r), r, id);
        if (bonded && i > 0) {
          m.bonds.append(id - 1, id, r, 1e10, 4e9, 1e6, 4e6, 0.5);
        }
        ++id;
      }
    }
  }
  updateMassProperties(m);
  return m;
}

LoadTestSettings mode(TestMode t)
{
  LoadTestSettings s;
  s.mode = t;
  return s;
}

} // namespace

TEST(ResolutionAdvice, GrainsAcrossIsTheNarrowestWidthAcrossTheLoadingAxisInMeanDiameters)
{
  const Model m = lattice(6, 9, 14, 0.001, false);
  EXPECT_NEAR(grainsAcross(m, 2), 6.0, 1e-12); // X 6, Y 9: the narrower
  EXPECT_NEAR(grainsAcross(m, 0), 9.0, 1e-12); // Y 9, Z 14
  EXPECT_NEAR(grainsAcross(m, 1), 6.0, 1e-12); // X 6, Z 14
  const Model empty;
  EXPECT_EQ(grainsAcross(empty, 2), 0.0);
  EXPECT_EQ(grainsAcross(m, 3), 0.0);
  // A 2D section: the in-plane axis only (Z is the slab).
  Model section = lattice(12, 30, 1, 0.001, false);
  section.domain.section2D = true;
  EXPECT_NEAR(grainsAcross(section, 1), 12.0, 1e-12);
}

TEST(ResolutionAdvice, ANarrowCementedSpecimenIsRiskyWithWhatTheAtlasMeasuredThere)
{
  const Model m = lattice(7, 7, 14, 0.001, true);
  const double across = grainsAcross(m, 2);
  for (TestMode t : { TestMode::Compression, TestMode::Triaxial, TestMode::Tension }) {
    const std::string advice = resolutionAdvice(across, m, mode(t));
    EXPECT_NE(advice.find("The specimen is 7 mean grain diameters across"), std::string::npos) << advice;
    // The nearest measured width, 7.0 across: UCS 40.5 %, E 19 % and sigma_t 15.7 % low.
    EXPECT_NE(advice.find("a specimen 7 across measured the UCS 40.5 %, Young's modulus 19 % and the direct "
                          "tensile strength 15.7 % below"),
              std::string::npos)
      << advice;
    EXPECT_NE(advice.find("at least 11.9 across"), std::string::npos) << advice;
  }
  // The nearest measured width is quoted: 10 across is nearer 9.0 than 11.9.
  EXPECT_NE(resolutionAdvice(10.0, m, mode(TestMode::Compression)).find("a specimen 9 across measured the UCS 32.9 %"),
            std::string::npos);
  // The UCS did not converge within 40 across, and Settling Damping (the default 0.7) doubled it:
  // the advice says both.
  const std::string damped = resolutionAdvice(7.0, m, mode(TestMode::Compression));
  EXPECT_NE(damped.find("Settling Damping 0.7, Documentation/SpeedAccuracy.md"), std::string::npos) << damped;
  EXPECT_NE(damped.find("it rose with the width up to the widest measured (40 across damped, 28 undamped"), std::string::npos) << damped;
  EXPECT_NE(damped.find("about 2 x the undamped UCS from 12 across on"), std::string::npos) << damped;
  // At and above 11.9 across a damped compression test gets no advice (the UCS has no converged
  // width to be wasteful beyond).
  EXPECT_EQ(resolutionAdvice(11.9, m, mode(TestMode::Compression)), "");
  EXPECT_EQ(resolutionAdvice(80.0, m, mode(TestMode::Triaxial)), "");
}

TEST(ResolutionAdvice, UndampedTheUcsNeedsSixteenAcrossAndTheUndampedSweepIsQuoted)
{
  Model m = lattice(7, 7, 14, 0.001, true);
  m.solver.settlingDamping = 0.0;
  // The undamped sweep at 7.0 across: UCS 25.2 %, E 42.7 %, sigma_t 11.4 % low.
  const std::string advice = resolutionAdvice(7.0, m, mode(TestMode::Compression));
  EXPECT_NE(advice.find("(3D boxes, undamped, Documentation/SpeedAccuracy.md"), std::string::npos) << advice;
  EXPECT_NE(advice.find("a specimen 7 across measured the UCS 25.2 %, Young's modulus 42.7 % and the direct "
                        "tensile strength 11.4 % below"),
            std::string::npos)
    << advice;
  EXPECT_NE(advice.find("though undamped it was within 5 % of 20 across from 15.6 across"), std::string::npos)
    << advice;
  // Between 11.9 and 15.6 across an undamped compression or triaxial test is still risky (the UCS
  // 14.4 % low at 11.9), a tension test is not.
  EXPECT_NE(resolutionAdvice(13.0, m, mode(TestMode::Triaxial)).find("a specimen 11.9 across measured the UCS 14.4 %"),
            std::string::npos);
  EXPECT_EQ(resolutionAdvice(13.0, m, mode(TestMode::Tension)), "");
  EXPECT_EQ(resolutionAdvice(15.6, m, mode(TestMode::Compression)), "");
}

TEST(ResolutionAdvice, AWideTensionSpecimenIsWastefulWithItsCost)
{
  const Model m = lattice(4, 4, 8, 0.001, true);
  EXPECT_EQ(resolutionAdvice(31.2, m, mode(TestMode::Tension)), ""); // 2 x 15.6: not yet
  const std::string advice = resolutionAdvice(46.8, m, mode(TestMode::Tension));
  // (46.8 / 15.6)^3 = 27 x the particle-steps.
  EXPECT_NE(advice.find("costs about 27 x the particle-steps"), std::string::npos) << advice;
  EXPECT_NE(advice.find("Advised: 15.6 to 31.2 across"), std::string::npos) << advice;
}

TEST(ResolutionAdvice, SilentWhereTheSweepMeasuredNothing)
{
  const Model cemented = lattice(5, 5, 10, 0.001, true);
  const Model loose = lattice(5, 5, 10, 0.001, false);
  // Grains without intact bonds, the tests the sweep did not run, a 2D section.
  EXPECT_EQ(resolutionAdvice(5.0, loose, mode(TestMode::Compression)), "");
  Model broken = cemented;
  for (std::size_t k = 0; k < broken.bonds.size(); ++k) {
    broken.bonds.failure[k] = static_cast<std::uint8_t>(BondFailure::Tension);
  }
  EXPECT_EQ(resolutionAdvice(5.0, broken, mode(TestMode::Compression)), "");
  for (TestMode t : { TestMode::Off, TestMode::Isotropic, TestMode::Brazilian }) {
    EXPECT_EQ(resolutionAdvice(5.0, cemented, mode(t)), "");
  }
  Model section = cemented;
  section.domain.section2D = true;
  EXPECT_EQ(resolutionAdvice(5.0, section, mode(TestMode::Compression)), "");
  EXPECT_NE(resolutionAdvice(5.0, cemented, mode(TestMode::Compression)), "");
}
