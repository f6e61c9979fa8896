// Contact dynamics against theory (PHYSICS.md section 1-2), determinism and stability.
#include "DynamicsFixtures.h"

#include "dem/ContactLaws.h"
#include "dem/Errors.h"
#include "dem/Pack.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

using namespace dem;
using namespace dem::testing;

namespace {

constexpr double Pi = 3.14159265358979323846;

/// Oblique impact of a sphere on the low Z wall: approach speed vn, tangential speed vt
/// (along +x), no spin. Returns (vx, vz, omega_y) after the collision.
Vec3 obliqueImpact(double vn, double vt, double mu, double e, bool disc, double* radiusOut)
{
  Model m = emptyModel(10e9, 0.25, 2650.0, e, 0.1);
  m.material.friction = mu;
  const double r = 0.002;
  if (disc) {
    m.domain.section2D = true;
    m.domain.origin = Vec3(-0.05, -0.05, -0.0005);
    m.domain.size = Vec3(0.1, 0.1, 0.001);
    addSphere(m, Vec3(0, m.domain.origin.y() + r + 1e-6, 0.0), r, Vec3(vt, -vn, 0));
  } else {
    addSphere(m, Vec3(0, 0, m.domain.origin.z() + r + 1e-6), r, Vec3(vt, 0, -vn));
  }
  *radiusOut = r;
  Simulation sim(m);
  const int axis = disc ? 1 : 2;
  const Collision c = followCollision(
    m, sim, [&](const Model& mm) { return r - (mm.particles.position[0][axis] - mm.domain.origin[axis]); },
    [](const Model& mm) { return mm.particles.force[0].norm(); });
  EXPECT_TRUE(c.ended);
  const Vec3& v = m.particles.velocity[0];
  const Vec3& w = m.particles.angularVelocity[0];
  // For a disc rolling in x on a floor normal to +y the spin is about -z; report it as
  // the spin that rolling without slip would give a positive value to.
  return disc ? Vec3(v.x(), v.y(), -w.z()) : Vec3(v.x(), v.z(), w.y());
}

} // namespace

// Rigid-body theory of an oblique impact on a plane (PHYSICS.md s.1): gross sliding when
// vt >= 3.5 mu (1+e) vn, then dvt = -mu (1+e) vn and R dw = 2.5 mu (1+e) vn. Within 2%.
TEST(ObliqueImpact, GrossSlidingMatchesRigidBodyTheory)
{
  const double mu = 0.3;
  const double e = 0.8;
  const double vn = 1.0;
  for (double angleDeg : { 65.0, 70.0, 75.0, 80.0, 85.0 }) { // incidence from the normal
    const double vt = vn * std::tan(angleDeg * Pi / 180.0);
    ASSERT_GE(vt, 3.5 * mu * (1.0 + e) * vn);
    double r = 0.0;
    const Vec3 after = obliqueImpact(vn, vt, mu, e, false, &r);
    const double impulse = mu * (1.0 + e) * vn;
    EXPECT_NEAR(vt - after.x(), impulse, 0.02 * impulse) << angleDeg << " deg";
    EXPECT_NEAR(r * after.z(), 2.5 * impulse, 0.02 * 2.5 * impulse) << angleDeg << " deg";
  }
}

// Below the transition angle the contact sticks (Maw, Barber & Fawcett 1976): the
// tangential impulse is less than the sliding impulse and the contact point's slip
// speed is mostly removed; rigid theory gives vt' = R w' = 5/7 vt.
TEST(ObliqueImpact, StickingRegimeBelowTransition)
{
  const double mu = 0.3;
  const double e = 0.8;
  const double vn = 1.0;
  const double transition = std::atan(3.5 * mu * (1.0 + e)) * 180.0 / Pi;
  for (double angleDeg : { 10.0, 20.0, 30.0, 40.0 }) {
    ASSERT_LT(angleDeg, transition);
    const double vt = vn * std::tan(angleDeg * Pi / 180.0);
    double r = 0.0;
    const Vec3 after = obliqueImpact(vn, vt, mu, e, false, &r);
    const double impulse = vt - after.x();
    EXPECT_LT(impulse, 0.98 * mu * (1.0 + e) * vn) << angleDeg << " deg";
    EXPECT_GT(impulse, 0.0);
    // With tangential compliance the contact point's velocity oscillates and may reverse
    // (Maw et al.): the impulse is at most twice the rigid sticking impulse 2/7 vt.
    EXPECT_LT(impulse, 2.0 * 2.0 / 7.0 * vt * 1.01) << angleDeg << " deg";
    EXPECT_GT(r * after.z(), 0.0) << "spin in the rolling sense, " << angleDeg << " deg";
  }
}

// 2D: a disc (I = m R^2 / 2) in gross sliding gets R dw = 2 mu (1+e) vn, not 2.5.
TEST(ObliqueImpact, DiscFollows2DInertia)
{
  const double mu = 0.3;
  const double e = 0.8;
  const double vn = 1.0;
  const double vt = 4.0;
  double r = 0.0;
  const Vec3 after = obliqueImpact(vn, vt, mu, e, true, &r);
  const double impulse = mu * (1.0 + e) * vn;
  EXPECT_NEAR(vt - after.x(), impulse, 0.02 * impulse);
  EXPECT_NEAR(r * after.z(), 2.0 * impulse, 0.02 * 2.0 * impulse);
}

// 2D disc normal impact on a wall: Hertz closed forms with the disc mass rho pi r^2 t.
TEST(HertzImpact, DiscOnWallUsesDiscMass)
{
  Model m = emptyModel(10e9, 0.25, 2650.0, 1.0, 0.1);
  m.domain.section2D = true;
  m.domain.origin = Vec3(-0.05, -0.05, -0.0005);
  m.domain.size = Vec3(0.1, 0.1, 0.001);
  const double r = 0.002;
  addSphere(m, Vec3(0, m.domain.origin.y() + r + 1e-6, 0), r, Vec3(0, -1.0, 0));
  const double mass = 2650.0 * Pi * r * r * 0.001;
  ASSERT_NEAR(m.particles.mass[0], mass, 1e-15);
  ASSERT_NEAR(m.particles.inertia[0], 0.5 * mass * r * r, 1e-20);
  Simulation sim(m);
  const HertzImpact ref = hertzImpact(10e9 / (1.0 - 0.0625), r, mass, 1.0);
  const Collision c = followCollision(
    m, sim, [&](const Model& mm) { return r - (mm.particles.position[0].y() - mm.domain.origin.y()); },
    [](const Model& mm) { return mm.particles.force[0].norm(); });
  ASSERT_TRUE(c.ended);
  EXPECT_NEAR(c.maxOverlap, ref.maxOverlap, 0.01 * ref.maxOverlap);
  EXPECT_NEAR(c.maxForce, ref.maxForce, 0.01 * ref.maxForce);
  EXPECT_NEAR(c.duration, ref.duration, 0.01 * ref.duration);
  EXPECT_EQ(m.particles.position[0].z(), 0.0) << "discs stay at mid-plane";
}

// Energy of an undamped elastic (frictionless, e = 1) system is conserved to 1e-4
// relative over 1e5 steps (velocity Verlet is symplectic for conservative forces; the
// residual error is the per-collision integration error, about dt^2). At Timestep Safety
// 0.05; at the default 0.1 the same system drifts 2.9e-4 (Documentation/SolverAccuracy.md).
TEST(Energy, UndampedElasticSystemConserved)
{
  Model m = emptyModel(1e8, 0.25, 2650.0, 1.0, 0.04);
  m.solver.timestepSafety = 0.05;
  Random rng(5);
  for (int k = 0; k < 40; ++k) {
    const Vec3 x(rng.uniform(-0.015, 0.015), rng.uniform(-0.015, 0.015), rng.uniform(-0.015, 0.015));
    bool clear = true;
    for (std::size_t j = 0; j < m.particles.size(); ++j) {
      clear = clear && (m.particles.position[j] - x).norm() > 0.0045;
    }
    if (clear) {
      addSphere(m, x, 0.002, Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)));
    }
  }
  ASSERT_GT(m.particles.size(), 20u);
  Simulation sim(m);
  const double e0 = sim.totalEnergy();
  double worst = 0.0;
  for (int batch = 0; batch < 100; ++batch) {
    sim.advance(1000);
    worst = std::max(worst, std::abs(sim.totalEnergy() - e0) / e0);
  }
  EXPECT_EQ(m.clock.step, 100000);
  EXPECT_LT(worst, 1e-4);
}

// A sphere resting on a wall under gravity settles to a wall force m g (statics).
TEST(Statics, SphereOnWallSettlesToWeight)
{
  Model m = emptyModel(1e9, 0.25, 2650.0, 0.5, 0.1);
  m.gravity = Vec3(0, 0, -9.81);
  m.solver.settlingDamping = 0.7;
  const double r = 0.005;
  addSphere(m, Vec3(0, 0, m.domain.origin.z() + r), r);
  Simulation sim(m);
  sim.advance(20000);
  const double weight = m.particles.mass[0] * 9.81;
  const Wall& floor = m.walls[4];
  EXPECT_NEAR(-floor.force.z(), weight, 1e-6 * weight); // the wall is pushed down by m g
  EXPECT_LT(m.particles.velocity[0].norm(), 1e-9);
}

// Rolling resistance (Ai et al. 2011): on a slope steeper than atan(mu_r) a sphere rolls
// with a = 5/7 g (sin t - mu_r cos t); below it stays.
TEST(RollingFriction, HoldsBelowLimitRollsAbove)
{
  const double muR = 0.1;
  const double limit = std::atan(muR);
  for (double factor : { 0.7, 1.5 }) {
    const double theta = factor * limit;
    Model m = emptyModel(1e9, 0.25, 2650.0, 0.5, 0.5);
    m.material.friction = 0.9;
    m.material.rollingFriction = muR;
    m.gravity = 9.81 * Vec3(std::sin(theta), 0, -std::cos(theta));
    const double r = 0.005;
    addSphere(m, Vec3(0, 0, m.domain.origin.z() + r), r);
    const double Estar = 1e9 / (1.0 - 0.0625);
    const double mg = m.particles.mass[0] * 9.81 * std::cos(theta);
    const double staticOverlap = std::pow(3.0 * mg / (4.0 * Estar * std::sqrt(r)), 2.0 / 3.0);
    m.particles.position[0].z() -= staticOverlap;
    Simulation sim(m);
    // Settle the contact (damped), then release the damping and watch.
    m.solver.settlingDamping = 0.0;
    const double t0 = m.clock.time;
    const double x0 = m.particles.position[0].x();
    sim.advance(200000);
    const double t = m.clock.time - t0;
    const double dx = m.particles.position[0].x() - x0;
    if (factor < 1.0) {
      EXPECT_LT(std::abs(dx), 0.01 * r) << "held below the rolling limit";
    } else {
      const double a = 5.0 / 7.0 * 9.81 * (std::sin(theta) - muR * std::cos(theta));
      EXPECT_NEAR(dx, 0.5 * a * t * t, 0.1 * 0.5 * a * t * t) << "rolls above the limit";
    }
  }
}

// A pair straddling a periodic seam gets the same force as the same pair in the interior.
TEST(Periodic, SeamPairFeelsInteriorForce)
{
  auto forceOf = [](double xa, double xb) {
    Model m = emptyModel(1e9, 0.25, 2650.0, 0.5, 0.01);
    m.domain.origin = Vec3(0, 0, 0);
    m.domain.size = Vec3(0.01, 0.01, 0.01);
    m.domain.periodic = { { true, false, false } };
    addSphere(m, Vec3(xa, 0.005, 0.005), 0.001, Vec3(0.1, 0.05, 0));
    addSphere(m, Vec3(xb, 0.005, 0.005), 0.001, Vec3(-0.1, 0, 0.02));
    Simulation sim(m);
    sim.advance(3);
    return std::make_pair(m.particles.force[0], m.particles.torque[0]);
  };
  const auto seam = forceOf(0.01 - 0.0009, 0.0009);     // 1.8 mm apart across x = 0.01
  const auto inside = forceOf(0.005 - 0.0009, 0.005 + 0.0009);
  ASSERT_GT(inside.first.norm(), 0.0);
  EXPECT_LT((seam.first - inside.first).norm(), 1e-6 * inside.first.norm());
  EXPECT_LT((seam.second - inside.second).norm(), 1e-6 * inside.second.norm() + 1e-18);
}

namespace {
Model settlingPack(int n, std::uint64_t seed)
{
  Model m;
  m.domain.size = Vec3(0.04, 0.04, 0.08);
  m.material.youngsModulus = 1e8;
  m.material.friction = 0.5;
  m.material.rollingFriction = 0.1;
  PackParameters params;
  params.initialElements = n;
  params.minimumSize = 0.001;
  params.maximumSize = 0.002;
  params.randomSeed = seed;
  buildPack(m, params);
  growElements(m); // every particle touches a neighbour: contacts from the first step
  return m;
}

template <class T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b)
{
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}
} // namespace

// Determinism: 1 and 2 threads give bitwise identical results.
TEST(Determinism, OneAndTwoThreadsBitwiseIdentical)
{
  Model a = settlingPack(1500, 3);
  Model b = a;
  a.solver.threads = 1;
  b.solver.threads = 2;
  a.solver.parallelThreshold = b.solver.parallelThreshold = 0;
  Simulation sa(a);
  Simulation sb(b);
  EXPECT_EQ(sb.path(), "CPU OpenMP (2 threads)");
  sa.advance(1500);
  sb.advance(1500);
  EXPECT_TRUE(sameBits(a.particles.position, b.particles.position));
  EXPECT_TRUE(sameBits(a.particles.velocity, b.particles.velocity));
  EXPECT_TRUE(sameBits(a.particles.angularVelocity, b.particles.angularVelocity));
  EXPECT_TRUE(sameBits(a.contacts.shearSpring, b.contacts.shearSpring));
  EXPECT_GT(sa.diagnostics().contacts, 0u);
}

// The serial/parallel switch weighs the work per step (particles + 5 x neighbour pairs +
// 6 x bonds, Documentation/Benchmarks-Solver.md "Serial or parallel"; Solver Path names
// it), decides again at
// every neighbour build, and never changes a bit: a run that starts serial just below the
// threshold and crosses it as the pack settles ends as the 1-thread run does.
TEST(Determinism, SerialParallelSwitchWeighsTheWorkPerStep)
{
  // The work in the path: "CPU serial (work W, below the parallel threshold of T...".
  auto workOf = [](const std::string& path) {
    long long work = -1;
    EXPECT_EQ(std::sscanf(path.c_str(), "CPU serial (work %lld,", &work), 1) << path;
    return work;
  };
  Model a = settlingPack(600, 5);
  // Stirred (undamped, +-0.1 m/s per axis): the pairs change at every neighbour build.
  a.solver.settlingDamping = 0.0;
  for (std::size_t i = 0; i < a.particles.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      a.particles.velocity[i][c] = 0.1 * (static_cast<double>((i * 7919 + c * 104729) % 2001) / 1000.0 - 1.0);
    }
  }
  a.solver.threads = 2;
  Model probe = a;
  const long long work = workOf(Simulation(probe).path());
  EXPECT_GT(work, 600 + 5 * 100); // 600 particles and their neighbour pairs (5 each)
  EXPECT_LT(work, a.solver.parallelThreshold);
  probe = a;
  probe.solver.parallelThreshold = work;
  EXPECT_EQ(Simulation(probe).path(), "CPU OpenMP (2 threads)");

  // The work after 1,500 steps (serial run): a threshold between the two makes
  // the 2-thread run change path at a neighbour build.
  probe = a;
  probe.solver.threads = 1;
  Simulation settle(probe);
  settle.advance(1500);
  const long long workEnd = workOf(settle.path());
  ASSERT_NE(workEnd, work) << "no change of the pair count to cross";
  a.solver.parallelThreshold = std::max(work, workEnd);
  Model one = a;
  one.solver.threads = 1;
  Simulation sa(one);
  Simulation sb(a);
  const std::string before = sb.path();
  sa.advance(1500);
  sb.advance(1500);
  const std::string after = sb.path();
  EXPECT_NE(before.substr(0, 10), after.substr(0, 10)) << before << " / " << after;
  std::printf("2 threads, threshold %lld: %s -> %s\n", static_cast<long long>(a.solver.parallelThreshold),
              before.c_str(), after.c_str());
  EXPECT_TRUE(sameBits(one.particles.position, a.particles.position));
  EXPECT_TRUE(sameBits(one.particles.velocity, a.particles.velocity));
  EXPECT_TRUE(sameBits(one.particles.angularVelocity, a.particles.angularVelocity));
  EXPECT_TRUE(sameBits(one.contacts.shearSpring, a.contacts.shearSpring));
  EXPECT_TRUE(sameBits(one.contacts.rollingSpring, a.contacts.rollingSpring));
}

// A model copied mid-run (as a saved state is) and stepped by a new solver continues
// exactly as the uninterrupted run.
TEST(Determinism, ResumedRunStepsExactlyLikeUninterrupted)
{
  Model a = settlingPack(800, 9);
  Model b = a;
  {
    Simulation sa(a);
    sa.advance(3000);
  }
  {
    Simulation sb(b);
    sb.advance(1500);
  }
  Model resumed = b; // what a state file holds
  Simulation sr(resumed);
  sr.advance(1500);
  EXPECT_EQ(a.clock.step, resumed.clock.step);
  EXPECT_TRUE(sameBits(a.particles.position, resumed.particles.position));
  EXPECT_TRUE(sameBits(a.particles.velocity, resumed.particles.velocity));
  EXPECT_TRUE(sameBits(a.particles.angularVelocity, resumed.particles.angularVelocity));
  EXPECT_TRUE(sameBits(a.contacts.idA, resumed.contacts.idA));
  EXPECT_TRUE(sameBits(a.contacts.shearSpring, resumed.contacts.shearSpring));
  EXPECT_TRUE(sameBits(a.contacts.rollingSpring, resumed.contacts.rollingSpring));
  EXPECT_GT(a.contacts.size(), 0u);
}

// Stability (PHYSICS.md s.2): a requested timestep above the safe value is overridden
// with a message and the run stays bounded.
TEST(Stability, LargeRequestedTimestepIsOverridden)
{
  Model m = settlingPack(400, 4);
  Simulation probe(m);
  const double safe = probe.timestep();
  m.solver.requestedTimestep = 10.0 * probe.criticalTimestep();
  Simulation sim(m);
  EXPECT_EQ(sim.timestep(), safe);
  EXPECT_NE(sim.timestepMessage().find("Timestep"), std::string::npos) << sim.timestepMessage();
  EXPECT_NO_THROW(sim.advance(3000));
  EXPECT_EQ(sim.diagnostics().escaped, 0u);
}

// The same run forced above critical (test-only switch) blows up; the instability is
// detected and reported, and the model keeps its last good state.
TEST(Stability, ForcedUnstableRunIsDetectedAndStateKept)
{
  Model m = settlingPack(400, 4);
  {
    Simulation settle(m);
    settle.advance(2000); // make contacts
  }
  m.solver.allowUnsafeTimestep = true;
  m.solver.settlingDamping = 0.0;
  Simulation probe(m);
  m.solver.requestedTimestep = 5.0 * probe.criticalTimestep();
  Simulation sim(m);
  const std::int64_t stepBefore = m.clock.step;
  const std::vector<Vec3> before = m.particles.position;
  bool detected = false;
  try {
    for (int k = 0; k < 200; ++k) {
      sim.advance(100);
    }
  } catch (const InstabilityError& e) {
    detected = true;
    EXPECT_NE(std::string(e.what()).find("unstable"), std::string::npos) << e.what();
  }
  ASSERT_TRUE(detected);
  EXPECT_GE(m.clock.step, stepBefore);
  for (const Vec3& x : m.particles.position) {
    ASSERT_TRUE(x.allFinite());
  }
  EXPECT_THROW(sim.advance(1), InstabilityError);
  static_cast<void>(before);
}

TEST(Stability, BadSettingsAreNamed)
{
  Model m = settlingPack(50, 1);
  m.solver.timestepSafety = 2.0;
  try {
    Simulation sim(m);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("Timestep Safety"), std::string::npos);
  }
}
