// Parallel bonds (PHYSICS.md section 3; Potyondy & Cundall 2004, IJRMMS 41:1329).
//
// The bond law is checked under prescribed motion: both particles of a pair are kinematic
// (FlagFixed: forces do not move them, they keep the velocity and spin we give them), so
// the relative displacement and rotation are known exactly and the incremental law
// dFn = kn A d(delta_n), dFs = -ks A d(delta_s), dMt = -ks J d(theta_t),
// dMb = -kn I d(theta_b) can be compared with its closed form to roundoff. Then failure
// (tension, shear with the Mohr-Coulomb envelope, bending, twisting), rigid-body
// invariance, the fate of a broken bond, and a cantilever against beam theory.
#include "DynamicsFixtures.h"
#include "StateFixtures.h"

#include "dem/Bonds.h"
#include "dem/Cement.h"
#include "dem/Errors.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <vector>

using namespace dem;
using namespace dem::testing;

namespace {

constexpr double Pi = 3.14159265358979323846;
constexpr double R = 0.01;      // m, particle radius of the pair tests
constexpr double Slab = 0.005;  // m, slab thickness of the 2D pair tests
constexpr double Dt = 1.0e-7;   // s, prescribed step of the kinematic tests
constexpr double Ratio = 0.4;   // ks_bar / kn_bar

std::uint8_t mode(BondFailure f) { return static_cast<std::uint8_t>(f); }

CementParameters pairCement(double bondModulus, double sigmaC, double cohesion, double phiDeg)
{
  CementParameters cp;
  cp.gapTolerance = 0.05;
  cp.bondRadiusMultiplier = 1.0;
  cp.bondModulus = bondModulus;
  cp.bondStiffnessRatio = Ratio;
  cp.tensileStrength = sigmaC;
  cp.cohesion = cohesion;
  cp.frictionAngle = phiDeg;
  cp.strengthScatter = 0.0;
  return cp;
}

/// Two touching particles of radius R on the x axis (A, id 0, at -R; B, id 1, at +R),
/// both kinematic and at rest, cemented by one bond: spheres, or discs in a 2D section of
/// slab thickness Slab. No gravity, no damping, no friction, elastic contact (e = 1, no
/// dashpot). The solver steps exactly Dt.
Model bondedPair(bool planar, const CementParameters& cp)
{
  Model m = emptyModel(1e9, 0.25, 2650.0, 1.0, 2.0);
  if (planar) {
    m.domain.section2D = true;
    m.domain.origin.z() = -0.5 * Slab;
    m.domain.size.z() = Slab;
  }
  addSphere(m, Vec3(-R, 0, 0), R);
  addSphere(m, Vec3(R, 0, 0), R);
  m.particles.flags[0] |= FlagFixed;
  m.particles.flags[1] |= FlagFixed;
  m.solver.requestedTimestep = Dt;
  m.solver.allowUnsafeTimestep = true; // kinematic particles: no stability limit applies
  const CementReport report = cement(m, cp);
  EXPECT_EQ(report.bonds, 1u);
  EXPECT_EQ(m.bonds.size(), 1u);
  return m;
}

/// Section of the pair's bond (multiplier 1: Rb = R), from PHYSICS.md s.3 directly.
struct Section {
  double A, I, J, Rb;
};
Section pairSection(bool planar)
{
  const double rb = R;
  if (planar) {
    return { 2.0 * rb * Slab, 2.0 / 3.0 * Slab * rb * rb * rb, 0.0, rb };
  }
  return { Pi * rb * rb, Pi * std::pow(rb, 4) / 4.0, Pi * std::pow(rb, 4) / 2.0, rb };
}

double knOf(double bondModulus) { return bondModulus / (2.0 * R); }

/// Makes A an anchor instead of a kinematic particle: free, but so heavy (1e20 kg) that
/// no force in these tests moves it by one rounding unit. Used where the contact force
/// is checked (the contact between two kinematic particles has its own test).
void anchorA(Model& m)
{
  m.particles.flags[0] &= ~static_cast<std::uint32_t>(FlagFixed);
  m.particles.mass[0] = 1e20;
  m.particles.inertia[0] = 1e20;
}

double elongation(const Model& m)
{
  return (m.particles.position[1] - m.particles.position[0]).norm() - 2.0 * R;
}

/// Every force and moment the bond holds, as one number per kind, for "is it zero" checks.
double bondForceNorm(const Bonds& b) { return std::abs(b.normalForce[0]) + b.shearForce[0].norm(); }
double bondMomentNorm(const Bonds& b) { return std::abs(b.twistingMoment[0]) + b.bendingMoment[0].norm(); }

// ---------------------------------------------------------------------------------------
// 1. Pure tension

void pureTension(bool planar)
{
  const double Ebar = 1e9;
  const double sigmaC = 1e6;
  Model m = bondedPair(planar, pairCement(Ebar, sigmaC, 1e9, 30.0));
  const Section s = pairSection(planar);
  const double kn = knOf(Ebar);
  ASSERT_NEAR(m.bonds.normalStiffness[0], kn, 1e-12 * kn);
  ASSERT_NEAR(m.bonds.shearStiffness[0], Ratio * kn, 1e-12 * kn);
  ASSERT_NEAR(m.bonds.radius[0], R, 1e-15);
  // B pulled along the axis: the bond reaches sigma_c at elongation sigma_c / kn, half
  // way through step n0 + 1 (so that the step of failure is unambiguous).
  const int n0 = 400;
  const double deltaC = sigmaC / kn;
  const double v = deltaC / ((n0 + 0.5) * Dt);
  m.particles.velocity[1] = Vec3(v, 0, 0);
  Simulation sim(m);
  ASSERT_EQ(sim.timestep(), Dt);
  for (int k = 1; k <= n0; ++k) {
    sim.advance(1);
    ASSERT_FALSE(m.bonds.broken(0)) << "broke early, step " << k;
    const double expected = kn * s.A * elongation(m);
    ASSERT_NEAR(m.bonds.normalForce[0], expected, 1e-6 * expected) << "step " << k;
    ASSERT_LT(m.bonds.shearForce[0].norm(), 1e-9 * expected);
    ASSERT_LT(bondMomentNorm(m.bonds), 1e-9 * expected * R);
    // Tension pulls A towards B (+x) and B towards A.
    ASSERT_LT((m.particles.force[0] - Vec3(expected, 0, 0)).norm(), 1e-6 * expected) << "step " << k;
    ASSERT_LT((m.particles.force[1] + m.particles.force[0]).norm(), 1e-9 * expected);
  }
  EXPECT_LT(m.bonds.normalForce[0] / s.A, sigmaC);
  EXPECT_GT(m.bonds.normalForce[0] / s.A, sigmaC * (1.0 - 2.0 / n0));
  sim.advance(1);
  ASSERT_TRUE(m.bonds.broken(0)) << "sigma_max = " << kn * elongation(m) << " Pa >= sigma_c";
  EXPECT_EQ(m.bonds.failure[0], mode(BondFailure::Tension));
  const double tc = deltaC / v; // = (n0 + 0.5) Dt
  EXPECT_NEAR(m.bonds.failureTime[0], tc, Dt * (1.0 + 1e-6));
  EXPECT_LT((m.bonds.failureNormal[0] - Vec3(1, 0, 0)).norm(), 1e-9);
  const Vec3 middle = 0.5 * (m.particles.position[0] + m.particles.position[1]);
  EXPECT_LT((m.bonds.failurePosition[0] - middle).norm(), deltaC);
  // Broken: no force on either particle, and none stored, ever again.
  sim.advance(20);
  EXPECT_EQ(m.particles.force[0].norm(), 0.0);
  EXPECT_EQ(m.particles.force[1].norm(), 0.0);
  EXPECT_EQ(bondForceNorm(m.bonds), 0.0);
  EXPECT_EQ(bondMomentNorm(m.bonds), 0.0);
  const BondCounts counts = countBonds(m.bonds);
  EXPECT_EQ(counts.installed, 1u);
  EXPECT_EQ(counts.broken, 1u);
  EXPECT_EQ(counts.tension, 1u);
  EXPECT_EQ(counts.shear, 0u);
  EXPECT_DOUBLE_EQ(counts.damage(), 1.0);
}

// ---------------------------------------------------------------------------------------
// 4. Bending by opposite spins about an in-plane axis

void pureBending(bool planar)
{
  const double Ebar = 1e9;
  const double sigmaC = 1e6;
  Model m = bondedPair(planar, pairCement(Ebar, sigmaC, 1e9, 30.0));
  const Section s = pairSection(planar);
  const double kn = knOf(Ebar);
  // sigma_max = |Mb| Rb / I = kn Rb theta: failure at theta_c = sigma_c / (kn Rb).
  const int n0 = 400;
  const double thetaC = sigmaC / (kn * s.Rb);
  const double w = thetaC / ((n0 + 0.5) * Dt) / 2.0; // each spins at w, relative 2 w
  // 3D: about y. 2D: about z (the only spin a disc has). Opposite spins leave the
  // contact point at rest: no shear slip, pure bending.
  const Vec3 axis = planar ? Vec3(0, 0, 1) : Vec3(0, 1, 0);
  m.particles.angularVelocity[0] = w * axis;
  m.particles.angularVelocity[1] = -w * axis;
  Simulation sim(m);
  ASSERT_EQ(sim.timestep(), Dt);
  for (int k = 1; k <= n0; ++k) {
    sim.advance(1);
    ASSERT_FALSE(m.bonds.broken(0)) << "broke early, step " << k;
    const double theta = 2.0 * w * k * Dt; // rotation of A relative to B
    const Vec3 expected = -kn * s.I * theta * axis; // on A, opposing its rotation
    ASSERT_LT((m.bonds.bendingMoment[0] - expected).norm(), 1e-9 * expected.norm()) << "step " << k;
    ASSERT_EQ(m.bonds.twistingMoment[0], 0.0);
    ASSERT_LT(bondForceNorm(m.bonds), 1e-9 * expected.norm() / R);
    ASSERT_LT((m.particles.torque[0] - expected).norm(), 1e-9 * expected.norm()) << "step " << k;
    ASSERT_LT((m.particles.torque[1] + expected).norm(), 1e-9 * expected.norm());
  }
  const BondStresses st = bondStresses(bondSection(s.Rb, planar, Slab), s.Rb, m.bonds.normalForce[0],
    m.bonds.shearForce[0], m.bonds.twistingMoment[0], m.bonds.bendingMoment[0]);
  EXPECT_NEAR(st.sigmaMax, kn * s.Rb * 2.0 * w * n0 * Dt, 1e-9 * sigmaC);
  EXPECT_LT(st.sigmaMax, sigmaC);
  sim.advance(1);
  ASSERT_TRUE(m.bonds.broken(0));
  EXPECT_EQ(m.bonds.failure[0], mode(BondFailure::Tension)) << "bending fails the tensile fibre";
  EXPECT_NEAR(m.bonds.failureTime[0], (n0 + 0.5) * Dt, Dt * (1.0 + 1e-6));
  sim.advance(5);
  EXPECT_EQ(m.particles.torque[0].norm(), 0.0);
  EXPECT_EQ(bondMomentNorm(m.bonds), 0.0);
}

} // namespace

// ---------------------------------------------------------------------------------------
// Section and stress helpers (PHYSICS.md s.3 formulas)

TEST(BondFunctions, SectionProperties)
{
  const double rb = 0.003;
  const BondSection s3 = bondSection(rb, false, 0.01);
  EXPECT_NEAR(s3.area, Pi * rb * rb, 1e-15 * s3.area);
  EXPECT_NEAR(s3.inertia, Pi * std::pow(rb, 4) / 4.0, 1e-15 * s3.inertia);
  EXPECT_NEAR(s3.polar, Pi * std::pow(rb, 4) / 2.0, 1e-15 * s3.polar);
  const BondSection s2 = bondSection(rb, true, 0.01);
  EXPECT_NEAR(s2.area, 2.0 * rb * 0.01, 1e-15 * s2.area);
  EXPECT_NEAR(s2.inertia, 2.0 / 3.0 * 0.01 * rb * rb * rb, 1e-15 * s2.inertia);
  EXPECT_EQ(s2.polar, 0.0);
}

TEST(BondFunctions, PeripheralStressesAndFailureRule)
{
  const double rb = 0.002;
  const BondSection s = bondSection(rb, false, 0.0);
  const Vec3 fs(0, 3.0, 4.0);      // |Fs| = 5 N
  const Vec3 mb(0.0, -0.01, 0.0);  // |Mb| = 0.01 N m
  const double mt = -0.002;
  const BondStresses t = bondStresses(s, rb, 2.0, fs, mt, mb);
  EXPECT_NEAR(t.sigmaMax, 2.0 / s.area + 0.01 * rb / s.inertia, 1e-12 * t.sigmaMax);
  EXPECT_NEAR(t.tauMax, 5.0 / s.area + 0.002 * rb / s.polar, 1e-12 * t.tauMax);
  EXPECT_NEAR(t.compressive, -2.0 / s.area, 1e-12 * std::abs(t.compressive));
  // 2D: no twisting term (J = 0 must not produce NaN).
  const BondSection s2 = bondSection(rb, true, 0.004);
  const BondStresses t2 = bondStresses(s2, rb, -1.0, fs, 0.0, Vec3(0, 0, 0.01));
  EXPECT_NEAR(t2.tauMax, 5.0 / s2.area, 1e-12 * t2.tauMax);
  EXPECT_NEAR(t2.sigmaMax, -1.0 / s2.area + 0.01 * rb / s2.inertia, 1e-9 * t2.sigmaMax);
  EXPECT_NEAR(t2.compressive, 1.0 / s2.area, 1e-12 * t2.compressive);

  // Failure rule: tension first, then Mohr-Coulomb with the compressive stress.
  const double phi = 30.0 * Pi / 180.0;
  auto rule = [&](double sigmaMax, double tauMax, double sigma) {
    return bondFailure(BondStresses{ sigmaMax, tauMax, sigma }, 10e6, 20e6, phi);
  };
  EXPECT_EQ(rule(9.9e6, 19.9e6, 0.0), BondFailure::Intact);
  EXPECT_EQ(rule(10e6, 0.0, 0.0), BondFailure::Tension);
  EXPECT_EQ(rule(10e6, 50e6, 0.0), BondFailure::Tension);
  EXPECT_EQ(rule(0.0, 20e6, 0.0), BondFailure::Shear);
  const double envelope = 20e6 + 10e6 * std::tan(phi); // sigma = 10 MPa compression
  EXPECT_EQ(rule(-10e6, 0.999 * envelope, 10e6), BondFailure::Intact);
  EXPECT_EQ(rule(-10e6, 1.001 * envelope, 10e6), BondFailure::Shear);
  // Tension lowers the shear strength: c + sigma tan(phi) with sigma < 0.
  EXPECT_EQ(rule(5e6, 0.999 * (20e6 - 5e6 * std::tan(phi)), -5e6), BondFailure::Intact);
  EXPECT_EQ(rule(5e6, 1.001 * (20e6 - 5e6 * std::tan(phi)), -5e6), BondFailure::Shear);
}

TEST(BondFunctions, AppendClearAndCount)
{
  Bonds b;
  b.append(3, 7, 0.001, 1e12, 4e11, 5e6, 8e6, 0.5);
  b.append(4, 9, 0.002, 2e12, 8e11, 6e6, 9e6, 0.6);
  ASSERT_EQ(b.size(), 2u);
  EXPECT_EQ(b.idA[1], 4);
  EXPECT_EQ(b.idB[1], 9);
  EXPECT_EQ(b.normalForce[0], 0.0);
  EXPECT_EQ(b.shearForce[1].norm(), 0.0);
  EXPECT_FALSE(b.broken(0));
  b.failure[1] = mode(BondFailure::Shear);
  const BondCounts c = countBonds(b);
  EXPECT_EQ(c.installed, 2u);
  EXPECT_EQ(c.broken, 1u);
  EXPECT_EQ(c.shear, 1u);
  EXPECT_DOUBLE_EQ(c.damage(), 0.5);
  b.clear();
  EXPECT_EQ(b.size(), 0u);
  EXPECT_EQ(b.failure.size(), 0u);
  EXPECT_EQ(countBonds(b).damage(), 0.0);
}

// ---------------------------------------------------------------------------------------
// 1. Pure tension: Fn = kn A delta to roundoff; tensile failure exactly when Fn/A reaches
// sigma_c (within one step); then no force.

TEST(BondTension, LinearToFailureSpheres) { pureTension(false); }
TEST(BondTension, LinearToFailureDiscs) { pureTension(true); }

// Compression: the bond and the (Hertz) contact act in parallel, total = contact + bond.
TEST(BondTension, CompressionAddsContactAndBond)
{
  const double Ebar = 1e9;
  Model m = bondedPair(false, pairCement(Ebar, 1e7, 1e9, 30.0));
  anchorA(m);
  const Section s = pairSection(false);
  const double kn = knOf(Ebar);
  m.particles.velocity[1] = Vec3(-0.1, 0, 0);
  Simulation sim(m);
  const double Estar = 1e9 / (2.0 * (1.0 - 0.25 * 0.25));
  for (int k = 1; k <= 300; ++k) {
    sim.advance(1);
    const double overlap = -elongation(m);
    const double bond = kn * s.A * overlap;
    const double contact = 4.0 / 3.0 * Estar * std::sqrt(0.5 * R) * std::pow(overlap, 1.5);
    ASSERT_NEAR(m.bonds.normalForce[0], -bond, 1e-6 * bond) << "step " << k;
    // The force on A pushes it away from B (-x): contact + bond compression.
    ASSERT_NEAR(m.particles.force[0].x(), -(bond + contact), 1e-6 * (bond + contact)) << "step " << k;
  }
  EXPECT_FALSE(m.bonds.broken(0));
}

// Two kinematic (fixed) particles pressed together feel their contact like any other
// pair: with e = 1 the force on A is -(Hertz + bond); with e < 1 it is finite and at
// least that (the dashpot adds while they approach). Both masses are infinite here, so
// the contact law must not form 0 x infinity.
TEST(BondTension, KinematicPairFeelsItsContact)
{
  const double Ebar = 1e9;
  const Section s = pairSection(false);
  const double kn = knOf(Ebar);
  const double Estar = 1e9 / (2.0 * (1.0 - 0.25 * 0.25));
  for (double e : { 1.0, 0.5 }) {
    Model m = bondedPair(false, pairCement(Ebar, 1e7, 1e9, 30.0));
    m.material.restitution = e;
    m.particles.velocity[1] = Vec3(-0.1, 0, 0);
    Simulation sim(m);
    for (int k = 1; k <= 100; ++k) {
      ASSERT_NO_THROW(sim.advance(1)) << "e = " << e << ", step " << k;
      const double overlap = -elongation(m);
      const double bond = kn * s.A * overlap;
      const double contact = 4.0 / 3.0 * Estar * std::sqrt(0.5 * R) * std::pow(overlap, 1.5);
      const double fx = m.particles.force[0].x();
      ASSERT_TRUE(std::isfinite(fx)) << "e = " << e << ", step " << k;
      if (e == 1.0) {
        ASSERT_NEAR(fx, -(bond + contact), 1e-6 * (bond + contact)) << "e = 1, step " << k;
      } else {
        ASSERT_LE(fx, -(bond + contact) * (1.0 - 1e-9)) << "e = " << e << ", step " << k;
      }
    }
  }
}

// ---------------------------------------------------------------------------------------
// 2. Shear with no normal load: Fs = ks A delta_s; failure in shear when |Fs|/A = c.
// (phi = 0 so that the small tension that the sideways offset adds, kn delta_s^2 / 4R,
// does not move the threshold.)

TEST(BondShear, LinearToFailureAtCohesion)
{
  const double Ebar = 1e9;
  const double c = 1e6;
  Model m = bondedPair(false, pairCement(Ebar, 1e8, c, 0.0));
  const Section s = pairSection(false);
  const double ks = Ratio * knOf(Ebar);
  const int n0 = 400;
  const double deltaC = c / ks;
  const double v = deltaC / ((n0 + 0.5) * Dt);
  m.particles.velocity[1] = Vec3(0, v, 0); // B sideways: A moves -y relative to B
  Simulation sim(m);
  ASSERT_EQ(sim.timestep(), Dt);
  for (int k = 1; k <= n0; ++k) {
    sim.advance(1);
    ASSERT_FALSE(m.bonds.broken(0)) << "broke early, step " << k;
    const double ds = m.particles.position[1].y() - m.particles.position[0].y();
    // dFs = -ks A (displacement of A relative to B) = +ks A ds on A, along +y turned
    // into the current bond plane (the axis tilts by ds / 2R < 2.5e-3; the second-order
    // geometric terms are below 1e-5).
    const Vec3 axis = (m.particles.position[1] - m.particles.position[0]).normalized();
    const Vec3 expected = ks * s.A * ds * Vec3(0, 0, 1).cross(axis);
    ASSERT_LT((m.bonds.shearForce[0] - expected).norm(), 1e-4 * expected.norm()) << "step " << k;
    ASSERT_LT(bondMomentNorm(m.bonds), 1e-6 * expected.norm() * R);
  }
  const double tau = m.bonds.shearForce[0].norm() / s.A;
  EXPECT_LT(tau, c);
  EXPECT_GT(tau, c * (1.0 - 2.0 / n0));
  sim.advance(1);
  ASSERT_TRUE(m.bonds.broken(0));
  EXPECT_EQ(m.bonds.failure[0], mode(BondFailure::Shear));
  EXPECT_NEAR(m.bonds.failureTime[0], (n0 + 0.5) * Dt, Dt * (1.0 + 1e-6));
  const Vec3 axis = (m.particles.position[1] - m.particles.position[0]).normalized();
  EXPECT_LT((m.bonds.failureNormal[0] - axis).norm(), 1e-3);
  sim.advance(5);
  EXPECT_EQ(m.particles.force[0].norm(), 0.0);
  EXPECT_EQ(countBonds(m.bonds).shear, 1u);
}

// ---------------------------------------------------------------------------------------
// 3. Mohr-Coulomb envelope: pre-compress to sigma, then shear: failure at
// tau = c + sigma tan(phi) within 1% for sigma = 0, c/2, c, 2c.

TEST(BondShear, FailureTracesMohrCoulombEnvelope)
{
  const double Ebar = 2e10; // stiff: the sideways offset changes sigma by < 0.1%
  const double c = 2e6;
  const double phiDeg = 30.0;
  const double tanPhi = std::tan(phiDeg * Pi / 180.0);
  const Section s = pairSection(false);
  const double kn = knOf(Ebar);
  const double ks = Ratio * kn;
  const double speed = 0.02; // m/s, both phases (kinetic energy of B stays constant)
  for (double sigmaTarget : { 0.0, 0.5 * c, c, 2.0 * c }) {
    Model m = bondedPair(false, pairCement(Ebar, 1e9, c, phiDeg));
    const long compressSteps = std::lround(sigmaTarget / kn / (speed * Dt));
    m.particles.velocity[1] = compressSteps > 0 ? Vec3(-speed, 0, 0) : Vec3(0, speed, 0);
    Simulation sim(m);
    sim.advance(compressSteps);
    const double sigma = kn * compressSteps * speed * Dt; // compression reached
    ASSERT_NEAR(-m.bonds.normalForce[0] / s.A, sigma, 1e-6 * c) << "sigma " << sigmaTarget;
    m.particles.velocity[1] = Vec3(0, speed, 0);
    const double envelope = c + sigma * tanPhi;
    const long limit = 3 * std::lround(envelope / ks / (speed * Dt));
    double tauLast = 0.0;
    double sigmaLast = 0.0;
    long k = 0;
    for (; k < limit && !m.bonds.broken(0); ++k) {
      tauLast = m.bonds.shearForce[0].norm() / s.A;
      sigmaLast = -m.bonds.normalForce[0] / s.A;
      sim.advance(1);
    }
    ASSERT_TRUE(m.bonds.broken(0)) << "sigma " << sigma;
    EXPECT_EQ(m.bonds.failure[0], mode(BondFailure::Shear)) << "sigma " << sigma;
    std::printf("Mohr-Coulomb: sigma %.4g Pa: shear failure at tau %.6g Pa, c + sigma tan(phi) "
                "= %.6g Pa (%+.3f%%)\n", sigma, tauLast, envelope, 100.0 * (tauLast / envelope - 1.0));
    // tauLast: the shear stress of the last intact state (one step, 0.02%, below failure).
    EXPECT_NEAR(tauLast, envelope, 0.01 * envelope) << "sigma " << sigma << " Pa";
    EXPECT_LT(tauLast, c + sigmaLast * tanPhi) << "intact state must lie inside the envelope";
    EXPECT_NEAR(sigmaLast, sigma, 0.001 * c + 0.001 * sigma);
  }
}

// ---------------------------------------------------------------------------------------
// 4. Bending: Mb = -kn I theta to roundoff; tensile failure when |Mb| Rb / I = sigma_c.

TEST(BondBending, LinearToFailureSpheres) { pureBending(false); }
TEST(BondBending, LinearToFailureDiscs) { pureBending(true); } // I = 2/3 t Rb^3, no Mt

// Moment contribution factor beta (PFC's moment-contribution factor): the bond carries the
// same moment, but only beta of its peripheral stress counts. Bending to failure takes
// 1/beta times the rotation; with beta = 0 bending never breaks it.
TEST(BondBending, MomentContributionScalesTheMomentInTheFailureStresses)
{
  const double rb = 0.002;
  const BondSection s = bondSection(rb, false, 0.0);
  const Vec3 mb(0.0, 0.01, 0.0);
  const double mt = 0.004;
  for (double beta : { 0.0, 0.3, 1.0 }) {
    const BondStresses t = bondStresses(s, rb, 2.0, Vec3(0, 3, 4), mt, mb, beta);
    EXPECT_NEAR(t.sigmaMax, 2.0 / s.area + beta * 0.01 * rb / s.inertia, 1e-12 * (2.0 / s.area));
    EXPECT_NEAR(t.tauMax, 5.0 / s.area + beta * mt * rb / s.polar, 1e-12 * (5.0 / s.area));
  }
  for (double beta : { 0.5, 0.0 }) {
    const double Ebar = 1e9;
    const double sigmaC = 1e6;
    CementParameters cp = pairCement(Ebar, sigmaC, 1e9, 30.0);
    cp.momentContribution = beta;
    Model m = bondedPair(false, cp);
    EXPECT_EQ(m.bonds.momentContribution[0], beta);
    const Section sec = pairSection(false);
    const double kn = knOf(Ebar);
    // Full moments: failure at theta_c = sigma_c / (kn Rb); with beta at theta_c / beta.
    const int n0 = 200;
    const double thetaC = sigmaC / (kn * sec.Rb);
    const double w = thetaC / (n0 * Dt) / 2.0;
    m.particles.angularVelocity[0] = Vec3(0, w, 0);
    m.particles.angularVelocity[1] = Vec3(0, -w, 0);
    Simulation sim(m);
    sim.advance(3 * n0 / 2); // 1.5 theta_c: beyond full-moment failure
    const double expected = kn * sec.I * 2.0 * w * sim.timestep() * (3 * n0 / 2);
    if (beta == 0.0) {
      EXPECT_FALSE(m.bonds.broken(0)) << "bending alone never breaks a bond with beta 0";
      EXPECT_NEAR(m.bonds.bendingMoment[0].norm(), expected, 1e-9 * expected) << "the moment is still carried";
    } else {
      EXPECT_FALSE(m.bonds.broken(0)) << "beta 0.5: fails at 2 theta_c, not yet";
      sim.advance(n0);
      EXPECT_TRUE(m.bonds.broken(0)) << "beta 0.5: failed by 2.5 theta_c";
      EXPECT_EQ(m.bonds.failure[0], mode(BondFailure::Tension));
    }
  }
}

// ---------------------------------------------------------------------------------------
// 5. Twisting (3D): Mt = -ks J theta to roundoff; shear failure when |Mt| Rb / J = c.

TEST(BondTwisting, LinearToShearFailure)
{
  const double Ebar = 1e9;
  const double c = 1e6;
  Model m = bondedPair(false, pairCement(Ebar, 1e9, c, 30.0));
  const Section s = pairSection(false);
  const double ks = Ratio * knOf(Ebar);
  const int n0 = 400;
  const double thetaC = c / (ks * s.Rb);
  const double w = thetaC / ((n0 + 0.5) * Dt) / 2.0;
  m.particles.angularVelocity[0] = Vec3(w, 0, 0); // spins about the bond axis
  m.particles.angularVelocity[1] = Vec3(-w, 0, 0);
  Simulation sim(m);
  for (int k = 1; k <= n0; ++k) {
    sim.advance(1);
    ASSERT_FALSE(m.bonds.broken(0)) << "broke early, step " << k;
    const double theta = 2.0 * w * k * Dt;
    const double expected = -ks * s.J * theta; // on A, about the axis A -> B (+x)
    ASSERT_NEAR(m.bonds.twistingMoment[0], expected, 1e-9 * std::abs(expected)) << "step " << k;
    ASSERT_LT(m.bonds.bendingMoment[0].norm(), 1e-9 * std::abs(expected));
    ASSERT_LT(bondForceNorm(m.bonds), 1e-9 * std::abs(expected) / R);
    ASSERT_LT((m.particles.torque[0] - Vec3(expected, 0, 0)).norm(), 1e-9 * std::abs(expected));
  }
  sim.advance(1);
  ASSERT_TRUE(m.bonds.broken(0));
  EXPECT_EQ(m.bonds.failure[0], mode(BondFailure::Shear));
  EXPECT_NEAR(m.bonds.failureTime[0], (n0 + 0.5) * Dt, Dt * (1.0 + 1e-6));
}

// ---------------------------------------------------------------------------------------
// 6. Rigid-body motion of a bonded pair creates no bond force or moment.

TEST(BondRigidMotion, TranslationCreatesNoForce)
{
  const double Ebar = 1e9;
  Model m = bondedPair(false, pairCement(Ebar, 1e6, 1e6, 30.0));
  const Vec3 v(0.3, -0.2, 0.1);
  m.particles.velocity[0] = v;
  m.particles.velocity[1] = v;
  Simulation sim(m);
  sim.advance(2000);
  // Reference: the same displacement as an elongation, kn A |v| t (= 2.7e4 N here).
  const double reference = knOf(Ebar) * pairSection(false).A * v.norm() * m.clock.time;
  EXPECT_LT(bondForceNorm(m.bonds), 1e-9 * reference);
  EXPECT_LT(bondMomentNorm(m.bonds), 1e-9 * reference * R);
  EXPECT_FALSE(m.bonds.broken(0));
}

namespace {
/// Prescribes a rigid rotation omega about the fixed point c: v_i = omega x (x_i - c),
/// spin omega, from the current positions (kinematic particles keep their velocities,
/// so this is re-set every step).
void setRigidRotation(Model& m, const Vec3& c, const Vec3& omega)
{
  for (std::size_t i = 0; i < m.particles.size(); ++i) {
    m.particles.velocity[i] = omega.cross(m.particles.position[i] - c);
    m.particles.angularVelocity[i] = omega;
  }
}

Eigen::Matrix3d rotation(const Vec3& axis, double angle)
{
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}
} // namespace

// Rigid rotation about the pair's centre. The relative spin is exactly zero, so the
// moments must stay zero to roundoff (asserted < 1e-9 of kn I theta). The prescribed
// motion itself is explicit (x += dt omega x (x - c)): each step moves the particles off
// the circle by (omega dt)^2 / 2 of the radius, so the separation grows by
// |xB - xA| theta (omega dt) / 2 over a rotation theta, and an incremental law that
// projects the relative velocity on the end-of-step normal sees a normal displacement
// of |xB - xA| theta (omega dt). Both are first order in omega dt: the bond force is
// asserted below 2 omega dt times kn A |xB - xA| theta (the force the same arc length
// would give as an elongation); here omega dt = 1e-5.
TEST(BondRigidMotion, RotationCreatesNoForce)
{
  const double Ebar = 1e9;
  const double omegaDt = 1e-5;
  const double w = omegaDt / Dt;
  const double theta = 0.2;
  const long steps = std::lround(theta / omegaDt);
  for (const Vec3& axis : { Vec3(0, 0, 1), Vec3(1, 1, 1).normalized(), Vec3(1, 0, 0) }) {
    Model m = bondedPair(false, pairCement(Ebar, 1e6, 1e6, 30.0));
    const Vec3 c = Vec3::Zero();
    setRigidRotation(m, c, w * axis);
    Simulation sim(m);
    for (long k = 0; k < steps; ++k) {
      setRigidRotation(m, c, w * axis);
      sim.advance(1);
    }
    ASSERT_FALSE(m.bonds.broken(0));
    const Section s = pairSection(false);
    const double kn = knOf(Ebar);
    const double arc = 2.0 * R * theta;
    const double forceReference = kn * s.A * arc;
    const double momentReference = kn * s.I * theta;
    std::printf("rigid rotation about (%.3f %.3f %.3f): |Fn| / ref %.3e, |Fs| / ref %.3e "
                "(bound %.1e), moments / ref %.3e\n", axis.x(), axis.y(), axis.z(),
                std::abs(m.bonds.normalForce[0]) / forceReference, m.bonds.shearForce[0].norm() / forceReference,
                2.0 * omegaDt, bondMomentNorm(m.bonds) / momentReference);
    EXPECT_LT(std::abs(m.bonds.normalForce[0]), 2.0 * omegaDt * forceReference) << axis.transpose();
    EXPECT_LT(m.bonds.shearForce[0].norm(), 2.0 * omegaDt * forceReference) << axis.transpose();
    EXPECT_LT(bondMomentNorm(m.bonds), 1e-9 * momentReference) << axis.transpose();
    // The pair did turn.
    const Vec3 branch = (m.particles.position[1] - m.particles.position[0]).normalized();
    EXPECT_NEAR(branch.dot(rotation(axis, theta) * Vec3(1, 0, 0)), 1.0, 1e-6);
  }
}

// A loaded bond turned rigidly (about an axis normal to the bond) keeps its load in the
// turning frame: shear force and bending moment are rotated with the contact plane,
// normal force and magnitudes unchanged. Tolerance 1% of the shear preload: the explicit
// prescription adds a normal displacement |xB - xA| theta omega dt = 1e-7 m (see above),
// a normal force 2.6e-3 of the shear force of the 1e-4 m preload.
TEST(BondRigidMotion, LoadedBondTurnsWithThePair)
{
  const double Ebar = 1e9;
  Model m = bondedPair(false, pairCement(Ebar, 1e9, 1e9, 30.0));
  // Preload: B 1e-4 m sideways (+y), then a relative bending rotation about y.
  const double offset = 1e-4;
  const double ks = Ratio * knOf(Ebar);
  m.particles.velocity[1] = Vec3(0, 0.5, 0);
  {
    Simulation preload(m);
    preload.advance(std::lround(offset / (0.5 * Dt)));
    m.particles.velocity[1].setZero();
    m.particles.angularVelocity[0] = Vec3(0, 0.25, 0);
    m.particles.angularVelocity[1] = Vec3(0, -0.25, 0);
    preload.advance(4000); // relative rotation 2e-4 rad
  }
  const double fn0 = m.bonds.normalForce[0];
  const Vec3 fs0 = m.bonds.shearForce[0];
  const Vec3 mb0 = m.bonds.bendingMoment[0];
  ASSERT_NEAR(fs0.y(), ks * pairSection(false).A * offset, 1e-3 * fs0.norm());
  ASSERT_GT(mb0.norm(), 0.0);
  // Turn the pair by 30 degrees about z through its centre. A new solver (the bond state
  // lives in the model), built after the rotation is prescribed: its energy check
  // starts from the kinetic energy of the turning pair.
  const double omegaDt = 1e-5;
  const double w = omegaDt / Dt;
  const double angle = 30.0 * Pi / 180.0;
  const Vec3 c = 0.5 * (m.particles.position[0] + m.particles.position[1]);
  const long steps = std::lround(angle / omegaDt);
  setRigidRotation(m, c, Vec3(0, 0, w));
  Simulation sim(m);
  for (long k = 0; k < steps; ++k) {
    setRigidRotation(m, c, Vec3(0, 0, w));
    sim.advance(1);
  }
  const Eigen::Matrix3d Q = rotation(Vec3(0, 0, 1), steps * omegaDt);
  std::printf("loaded bond turned 30 deg: |dFs| / |Fs| %.3e, |dMb| / |Mb| %.3e, |dFn| / |Fs| %.3e\n",
              (m.bonds.shearForce[0] - Q * fs0).norm() / fs0.norm(),
              (m.bonds.bendingMoment[0] - Q * mb0).norm() / mb0.norm(),
              std::abs(m.bonds.normalForce[0] - fn0) / fs0.norm());
  EXPECT_LT((m.bonds.shearForce[0] - Q * fs0).norm(), 0.01 * fs0.norm())
    << "got " << m.bonds.shearForce[0].transpose() << ", expected " << (Q * fs0).transpose();
  EXPECT_LT((m.bonds.bendingMoment[0] - Q * mb0).norm(), 0.01 * mb0.norm())
    << "got " << m.bonds.bendingMoment[0].transpose() << ", expected " << (Q * mb0).transpose();
  EXPECT_NEAR(m.bonds.normalForce[0], fn0, 0.01 * fs0.norm());
}

// ---------------------------------------------------------------------------------------
// 7. A broken bond never re-forms: pushed back together the pair feels only the contact
// (the same force, step by step, as an identical pair that was never cemented), and
// pulled apart again it feels nothing.

TEST(BondBroken, NeverReforms)
{
  const double Ebar = 1e9;
  const double sigmaC = 1e6;
  Model m = bondedPair(false, pairCement(Ebar, sigmaC, 1e9, 30.0));
  anchorA(m);
  Model twin = m; // same particles and motion, no bond
  twin.bonds.clear();
  const double deltaC = sigmaC / knOf(Ebar);
  const double v = deltaC / (100.5 * Dt);
  m.particles.velocity[1] = twin.particles.velocity[1] = Vec3(v, 0, 0);
  Simulation sim(m);
  Simulation simTwin(twin);
  long k = 0;
  for (; k < 200 && !m.bonds.broken(0); ++k) {
    sim.advance(1);
    simTwin.advance(1);
  }
  ASSERT_TRUE(m.bonds.broken(0));
  EXPECT_EQ(k, 101);
  // Push back through contact to an overlap of about deltaC, then pull apart again.
  const double Estar = 1e9 / (2.0 * (1.0 - 0.25 * 0.25));
  double maxOverlap = 0.0;
  for (double direction : { -1.0, 1.0 }) {
    m.particles.velocity[1] = twin.particles.velocity[1] = Vec3(direction * v, 0, 0);
    for (int j = 0; j < 300; ++j) {
      sim.advance(1);
      simTwin.advance(1);
      ASSERT_TRUE(m.bonds.broken(0));
      ASSERT_EQ(bondForceNorm(m.bonds) + bondMomentNorm(m.bonds), 0.0);
      const Vec3 f = m.particles.force[0];
      ASSERT_LE((f - twin.particles.force[0]).norm(), 1e-12 * (1.0 + f.norm())) << "step " << j;
      const double overlap = -elongation(m);
      maxOverlap = std::max(maxOverlap, overlap);
      if (overlap > 0.0) {
        const double hertz = 4.0 / 3.0 * Estar * std::sqrt(0.5 * R) * std::pow(overlap, 1.5);
        ASSERT_NEAR(f.x(), -hertz, 1e-9 * hertz) << "contact only, step " << j;
      } else {
        ASSERT_EQ(f.norm(), 0.0) << "no tension once broken, step " << j;
      }
    }
  }
  EXPECT_GT(maxOverlap, 0.5 * deltaC);
  EXPECT_GT(elongation(m), 0.0); // ended apart
  EXPECT_LT(elongation(m), 3.0 * deltaC);
  EXPECT_EQ(countBonds(m.bonds).broken, 1u);
}

// ---------------------------------------------------------------------------------------
// 8. Cantilever (3D) against Euler-Bernoulli / Timoshenko beam theory.
//
// A row of N equal spheres (radius r, segment L = 2r) along x, the first one fixed
// (clamped: it does not rotate), loaded by gravity along -z, settled with local damping.
// Each bond is a hinge at the contact point with a rotational spring kn I = (Ebar / L) I
// and a transverse spring ks A. A chain of rotational springs EI / L spaced L apart is the
// rigid-body-spring discretisation of a beam with EI = Ebar I (clamp at the first
// centre, x = 0; the hinge between particles j and j+1 represents the segment
// [jL, (j+1)L]). Shear: ks A per segment is a Timoshenko beam with kappa G A = ks A L.
// Beam theory, loads P = m g at x_k = k L (k = 1..n, n = N - 1), l = n L:
//   w = sum_k P x_k^2 (3 l - x_k) / (6 Ebar I)  +  sum_k P x_k / (ks A L).
// The exact static solution of the discrete chain (hinges at h_j = (j + 1/2) L):
//   w = sum_j M_j (l - h_j) / (kn I) + V_j / (ks A),  M_j = sum_{k>j} P (x_k - h_j),
//   V_j = (n - j) P
// differs from beam theory by the midpoint rule, O(1/n^2) (0.1% here). Tolerances:
// 5% against beam theory (the requirement), 1% against the discrete solution.
TEST(BondCantilever, TipDeflectionMatchesBeamTheory)
{
  const int N = 16;
  const double r = 0.01;
  const double L = 2.0 * r;
  const double Ebar = 1e9;
  Model m = emptyModel(1e8, 0.25, 2650.0, 1.0, 2.0);
  for (int k = 0; k < N; ++k) {
    addSphere(m, Vec3(-0.2 + k * L, 0, 0), r);
  }
  m.particles.flags[0] |= FlagFixed;
  CementParameters cp = pairCement(Ebar, 1e12, 1e12, 30.0);
  const CementReport report = cement(m, cp);
  ASSERT_EQ(report.bonds, static_cast<std::size_t>(N - 1));
  m.gravity = Vec3(0, 0, -9.81);
  // Heavy local damping converges fastest here (the slow first bending mode); it
  // vanishes at equilibrium, so the static answer does not depend on it.
  m.solver.settlingDamping = 0.9;
  const double mass = m.particles.mass[1];
  const double kn = Ebar / L;
  const double ks = Ratio * kn;
  const double A = Pi * r * r;
  const double I = Pi * std::pow(r, 4) / 4.0;
  // Step at most 0.1 sqrt(m / (kn A)) (a request above the solver's safe step is overridden).
  m.solver.requestedTimestep = 0.1 * std::sqrt(mass / (kn * A));
  Simulation sim(m);

  // Settled when the tip has moved less than 1e-5 of its deflection over the last 20000
  // steps (a third of the period of the first mode).
  std::vector<double> history;
  double w = 0.0;
  bool settled = false;
  for (int batch = 0; batch < 80 && !settled; ++batch) {
    sim.advance(5000);
    w = -m.particles.position[N - 1].z();
    history.push_back(w);
    if (history.size() >= 5) {
      const auto last = history.end() - 5;
      const auto [lo, hi] = std::minmax_element(last, history.end());
      settled = *hi - *lo < 1e-5 * w;
    }
  }
  ASSERT_TRUE(settled) << "tip still moving after " << m.clock.step << " steps";

  const int n = N - 1;
  const double P = mass * 9.81;
  const double ell = n * L;
  double bending = 0.0;
  double shear = 0.0;
  for (int k = 1; k <= n; ++k) {
    const double x = k * L;
    bending += P * x * x * (3.0 * ell - x) / (6.0 * Ebar * I);
    shear += P * x / (ks * A * L);
  }
  const double beam = bending + shear;
  double discrete = 0.0;
  for (int j = 0; j < n; ++j) {
    const double h = (j + 0.5) * L;
    double M = 0.0;
    for (int k = j + 1; k <= n; ++k) {
      M += P * (k * L - h);
    }
    discrete += M * (ell - h) / (kn * I) + (n - j) * P / (ks * A);
  }
  const Diagnostics d = sim.diagnostics();
  std::printf("cantilever (%d spheres, %lld steps): tip deflection %.6e m, beam theory %.6e m "
              "(bending %.6e + shear %.6e), discrete chain %.6e m; sim/beam - 1 = %+.3f%%, "
              "sim/discrete - 1 = %+.4f%%; unbalanced force ratio %.3e\n",
              N, static_cast<long long>(m.clock.step), w, beam, bending, shear, discrete,
              100.0 * (w / beam - 1.0), 100.0 * (w / discrete - 1.0), d.unbalancedForceRatio);
  EXPECT_NEAR(w, beam, 0.05 * beam);
  EXPECT_NEAR(w, discrete, 0.01 * discrete);
  EXPECT_EQ(countBonds(m.bonds).broken, 0u);
  // Static: the free particles are in equilibrium. The clamped particle's net force is
  // the support reaction (it is kinematic), not an unbalanced force, so it must not count
  // in the ratio (PHYSICS.md s.4; equilibrium below about 0.01).
  EXPECT_LT(d.unbalancedForceRatio, 1e-3)
    << "the fixed support's reaction (the whole weight) counts as unbalanced force";
}

// ---------------------------------------------------------------------------------------
// 6. Tension softening (Softening Ratio r > 0; Cement.md "Tension softening")
//
// Closed form for a bond pulled along its axis (delta: elongation, delta0 = sigma_c / kn
// the elongation at the strength): F = kn A delta up to delta0, then F = sigma_c A (1 + r
// - delta / delta0) / r down to zero at (1 + r) delta0, where the bond breaks in tension.
// Unloading and reloading follow the secant to the origin, F = (1 - D) kn A delta, with the
// damage D reached on the softening line.

namespace {

double softeningForce(double delta, double delta0, double sigmaC, double area, double r)
{
  if (delta <= delta0) {
    return sigmaC / delta0 * area * delta;
  }
  return sigmaC * area * (1.0 + r - delta / delta0) / r;
}

void softeningPull(bool planar)
{
  const double Ebar = 1e9;
  const double sigmaC = 1e6;
  const double r = 2.5;
  CementParameters cp = pairCement(Ebar, sigmaC, 1e9, 30.0);
  cp.softeningRatio = r;
  Model m = bondedPair(planar, cp);
  ASSERT_EQ(m.bonds.softening[0], r);
  const Section s = pairSection(planar);
  const double kn = knOf(Ebar);
  const int n0 = 400; // the strength is reached half way through step n0 + 1
  const double delta0 = sigmaC / kn;
  const double v = delta0 / ((n0 + 0.5) * Dt);
  m.particles.velocity[1] = Vec3(v, 0, 0);
  Simulation sim(m);
  // (1 + r) delta0 is reached at step (1 + r)(n0 + 0.5) = 1401.75: the bond breaks in step 1402.
  const int breakStep = 1402;
  double largestError = 0.0;
  for (int k = 1; k < breakStep; ++k) {
    sim.advance(1);
    ASSERT_FALSE(m.bonds.broken(0)) << "broke early, step " << k;
    const double delta = elongation(m);
    const double expected = softeningForce(delta, delta0, sigmaC, s.A, r);
    const double error = std::abs(m.particles.force[0].x() - expected) / (sigmaC * s.A);
    largestError = std::max(largestError, error);
    ASSERT_LT(error, 1e-6) << "step " << k << ", elongation / delta0 " << delta / delta0;
    ASSERT_LT((m.particles.force[1] + m.particles.force[0]).norm(), 1e-9 * sigmaC * s.A);
    EXPECT_EQ(m.bonds.damage[0] > 0.0, delta > delta0) << "step " << k;
  }
  EXPECT_GT(m.bonds.damage[0], 0.999);
  sim.advance(1);
  ASSERT_TRUE(m.bonds.broken(0));
  EXPECT_EQ(m.bonds.failure[0], mode(BondFailure::Tension));
  EXPECT_EQ(m.particles.force[0].norm(), 0.0);
  std::printf("tension softening (%s, r = %g): force within %.2e sigma_c A of the closed form over %d steps, "
              "broken at elongation %.6f delta0 (closed form %.6f)\n", planar ? "discs" : "spheres", r,
              largestError, breakStep, elongation(m) / delta0, 1.0 + r);
}

} // namespace

TEST(BondSoftening, ForceFollowsTheLinearSofteningLineToFailureSpheres) { softeningPull(false); }
TEST(BondSoftening, ForceFollowsTheLinearSofteningLineToFailureDiscs) { softeningPull(true); }

TEST(BondSoftening, UnloadsAndReloadsAlongTheSecantToTheOrigin)
{
  const double Ebar = 1e9;
  const double sigmaC = 1e6;
  const double r = 2.5;
  CementParameters cp = pairCement(Ebar, sigmaC, 1e9, 30.0);
  cp.softeningRatio = r;
  Model m = bondedPair(false, cp);
  const Section s = pairSection(false);
  const double kn = knOf(Ebar);
  const double delta0 = sigmaC / kn;
  const int n0 = 400;
  const double v = delta0 / (n0 * Dt);
  m.particles.velocity[1] = Vec3(v, 0, 0);
  Simulation sim(m);
  sim.advance(2 * n0); // to 2 delta0 on the softening line
  const double x = elongation(m) / delta0;
  ASSERT_NEAR(x, 2.0, 1e-9);
  const double D = m.bonds.damage[0];
  EXPECT_NEAR(D, 1.0 - (1.0 + r - x) / (r * x), 1e-9); // (1 - D) x = (1 + r - x) / r: 0.7
  // Unload to a quarter of delta0, reload to just under 2 delta0: the secant, the damage
  // unchanged.
  for (double direction : { -1.0, 1.0 }) {
    m.particles.velocity[1] = Vec3(direction * v, 0, 0);
    const int steps = direction < 0.0 ? 7 * n0 / 4 : 7 * n0 / 4 - 4;
    for (int k = 0; k < steps; ++k) {
      sim.advance(1);
      const double delta = elongation(m);
      ASSERT_NEAR(m.particles.force[0].x(), (1.0 - D) * kn * s.A * delta, 1e-6 * sigmaC * s.A) << "step " << k;
      ASSERT_EQ(m.bonds.damage[0], D) << "the damage does not heal or grow below its envelope";
    }
  }
  ASSERT_NEAR(elongation(m) / delta0, 2.0 - 4.0 / n0, 1e-9);
  // Past 2 delta0 the softening line again.
  sim.advance(n0 / 2 + 4);
  const double delta = elongation(m);
  EXPECT_NEAR(m.particles.force[0].x(), softeningForce(delta, delta0, sigmaC, s.A, r), 1e-6 * sigmaC * s.A);
  EXPECT_GT(m.bonds.damage[0], D);
  EXPECT_FALSE(m.bonds.broken(0));
}

TEST(BondSoftening, RatioZeroIsTheBrittleLaw)
{
  const BondSection s = bondSection(0.01, false, 0.0);
  double damage = 0.0;
  for (double sigma : { 0.5e6, 0.999e6, 1e6, 1.5e6 }) {
    for (double tau : { 0.0, 3e6, 5e6 }) {
      const BondStresses st = bondStresses(s, 0.01, sigma * s.area, Vec3(tau * s.area, 0, 0), 0.0, Vec3::Zero());
      EXPECT_EQ(softenedBondFailure(st, 1e6, 4e6, 0.5, 0.0, damage), bondFailure(st, 1e6, 4e6, 0.5));
      EXPECT_EQ(damage, 0.0);
    }
  }
  // r > 0: no tension failure below (1 + r) sigma_c, the damage of the closed form.
  const BondStresses at2 = bondStresses(s, 0.01, 2e6 * s.area, Vec3::Zero(), 0.0, Vec3::Zero());
  EXPECT_EQ(softenedBondFailure(at2, 1e6, 4e6, 0.5, 2.5, damage), BondFailure::Intact);
  EXPECT_DOUBLE_EQ(damage, 0.7);
  EXPECT_EQ(softeningDamage(0.9, 2.5), 0.0);
  EXPECT_EQ(softeningDamage(3.5, 2.5), 1.0);
  const BondStresses at36 = bondStresses(s, 0.01, 3.6e6 * s.area, Vec3::Zero(), 0.0, Vec3::Zero());
  EXPECT_EQ(softenedBondFailure(at36, 1e6, 4e6, 0.5, 2.5, damage), BondFailure::Tension);
  // Bending enters through the peripheral stress as in the brittle law (beta = 1).
  const BondStresses bent = bondStresses(s, 0.01, 0.0, Vec3::Zero(), 0.0, Vec3(0, 2e6 * s.inertia / 0.01, 0));
  double bentDamage = 0.0;
  EXPECT_EQ(softenedBondFailure(bent, 1e6, 4e6, 0.5, 2.5, bentDamage), BondFailure::Intact);
  EXPECT_DOUBLE_EQ(bentDamage, 0.7);
}

// The CPU backend gives the shear test the tangent it computed once for a run of bonds
// (softenedBondFailureWithTan): the same failure and the same damage as the law that
// takes the angle, bit for bit, on either side of each boundary, with and without
// softening, at friction angles 0 to 89 deg.
TEST(Bonds, FailureWithTheTangentGivenIsTheFailureWithTheAngle)
{
  const BondSection s = bondSection(0.01, false, 0.0);
  int shear = 0, tension = 0, intact = 0;
  for (double angle : { 0.0, 0.3, 0.5235987755982988, 1.0, 1.5533430342749532 }) {
    for (double softening : { 0.0, 2.5 }) {
      for (double sigma : { -3e6, -1e6, 0.0, 0.5e6, 0.999e6, 1e6, 2e6, 3.5e6 }) {
        // tau on both sides of c + sigma tan(phi) (sigma compressive: -Fn / A).
        const double edge = 4e6 + (-sigma) * std::tan(angle);
        for (double tau : { 0.0, std::nextafter(edge, 0.0), edge, std::nextafter(edge, 1e99), 2.0 * edge }) {
          const BondStresses st =
            bondStresses(s, 0.01, sigma * s.area, Vec3(tau * s.area, 0, 0), 0.0, Vec3::Zero());
          double damageAngle = 0.1;
          double damageTan = 0.1;
          const BondFailure byAngle = softenedBondFailure(st, 1e6, 4e6, angle, softening, damageAngle);
          const BondFailure byTan =
            softenedBondFailureWithTan(st, 1e6, 4e6, std::tan(angle), softening, damageTan);
          EXPECT_EQ(byAngle, byTan) << "angle " << angle << " sigma " << sigma << " tau " << tau;
          EXPECT_EQ(std::memcmp(&damageAngle, &damageTan, sizeof(double)), 0);
          if (softening == 0.0) {
            EXPECT_EQ(byTan, bondFailure(st, 1e6, 4e6, angle));
          }
          shear += byTan == BondFailure::Shear;
          tension += byTan == BondFailure::Tension;
          intact += byTan == BondFailure::Intact;
        }
      }
    }
  }
  // Every outcome occurs.
  EXPECT_GT(shear, 0);
  EXPECT_GT(tension, 0);
  EXPECT_GT(intact, 0);
}

TEST(BondSoftening, SameBitsOnOneAndTwoThreads)
{
  const Model start = statetest::softeningMidCompression();
  Model a = start;
  Model b = start;
  a.solver.threads = 1;
  b.solver.threads = 2;
  a.solver.parallelThreshold = b.solver.parallelThreshold = 0;
  {
    Simulation sa(a);
    sa.advance(1500);
  }
  {
    Simulation sb(b);
    sb.advance(1500);
  }
  EXPECT_GE(statetest::softeningBonds(a.bonds), 10u);
  EXPECT_EQ(statetest::firstDifference(a, b), "");
}

TEST(BondSoftening, RatioOutsideItsRangeIsAnErrorNamingIt)
{
  for (double bad : { -0.5, 100.5, std::nan("") }) {
    CementParameters p;
    p.softeningRatio = bad;
    try {
      validate(p);
      ADD_FAILURE() << "Softening Ratio = " << bad << " accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("Softening Ratio"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("100"), std::string::npos) << "names the range: " << e.what();
    }
  }
  for (double good : { 0.0, 2.0, 100.0 }) {
    CementParameters p;
    p.softeningRatio = good;
    EXPECT_NO_THROW(validate(p));
  }
}


// dem::BondStepState (the rollback of Simulation::advance) takes back every array that
// stepping changes, and leaves the others to the model; a model with another bond count is
// refused rather than half restored.
TEST(Bonds, StepStateRestoresWhatSteppingChanges)
{
  dem::Bonds b;
  b.append(0, 1, 1e-3, 1e12, 4e11, 1e6, 2e6, 0.5, 0.5, 2.0);
  b.append(1, 2, 2e-3, 2e12, 8e11, 3e6, 4e6, 0.6, 1.0, 0.0);
  b.normalForce[0] = 3.0;
  b.shearForce[1] = dem::Vec3(1.0, 2.0, 0.0);
  b.damage[0] = 0.25;
  const dem::Bonds before = b;
  dem::BondStepState saved;
  saved.save(b);
  // A step's changes: forces and moments, damage, a failure with its record.
  b.normalForce[0] = -7.0;
  b.shearForce[0] = dem::Vec3(0.5, 0.0, 0.1);
  b.twistingMoment[1] = 0.01;
  b.bendingMoment[0] = dem::Vec3(0.0, 0.02, 0.0);
  b.damage[0] = 0.5;
  b.markBroken(1, dem::BondFailure::Shear, 1e-3, dem::Vec3(1.0, 2.0, 3.0), dem::Vec3(0.0, 0.0, 1.0));
  saved.restore(b);
  EXPECT_EQ(b.normalForce, before.normalForce);
  EXPECT_EQ(b.shearForce, before.shearForce);
  EXPECT_EQ(b.twistingMoment, before.twistingMoment);
  EXPECT_EQ(b.bendingMoment, before.bendingMoment);
  EXPECT_EQ(b.damage, before.damage);
  EXPECT_EQ(b.failure, before.failure);
  EXPECT_EQ(b.failureTime, before.failureTime);
  EXPECT_EQ(b.failurePosition, before.failurePosition);
  EXPECT_EQ(b.failureNormal, before.failureNormal);
  EXPECT_EQ(b.radius, before.radius);
  b.append(2, 3, 1e-3, 1e12, 4e11, 1e6, 2e6, 0.5);
  EXPECT_THROW(saved.restore(b), std::logic_error);
}
