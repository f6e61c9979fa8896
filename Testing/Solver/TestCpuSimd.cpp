// The CPU backend's AVX2 kernels give the bits of its scalar loops. The touching-pair kernel
// (Solver/src/backends/cpu/TouchingPairsAvx2.cpp): on the law's edge cases pair by pair, over
// whole runs with the scalar loop forced by ROCKDEM_CPU_SIMD=0, and its scan lists the pairs
// the scalar test lists. The bond kernel (IntactBondsAvx2.cpp): bond by bond in every state a
// bond can be in, and over whole cemented runs that break bonds. Skipped (and says so) on a
// processor or build without the kernels.
#include "StateFixtures.h"
#include "backends/ContactState.h"
#include "backends/cpu/IntactBond.h"
#include "backends/cpu/TouchingPair.h"

#include "dem/BondLaw.h"
#include "dem/Cement.h"
#include "dem/ContactLaws.h"
#include "dem/LoadTest.h"
#include "dem/Model.h"
#include "dem/Simulation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

using namespace dem;

namespace {

template <class T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b)
{
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

/// Sets or clears ROCKDEM_CPU_SIMD for the lifetime of the object.
class SimdSetting {
public:
  explicit SimdSetting(const char* value)
  {
    const char* old = std::getenv("ROCKDEM_CPU_SIMD");
    hadOld_ = old != nullptr;
    if (hadOld_) {
      old_ = old;
    }
    if (value) {
      setenv("ROCKDEM_CPU_SIMD", value, 1);
    } else {
      unsetenv("ROCKDEM_CPU_SIMD");
    }
  }
  ~SimdSetting()
  {
    if (hadOld_) {
      setenv("ROCKDEM_CPU_SIMD", old_.c_str(), 1);
    } else {
      unsetenv("ROCKDEM_CPU_SIMD");
    }
  }

private:
  bool hadOld_ = false;
  std::string old_;
};

/// The kernel is there and enabled (ROCKDEM_CPU_SIMD unset).
bool kernelAvailable()
{
  SimdSetting on(nullptr);
  return touchingPairsAvx2Enabled();
}

/// A jittered cubic lattice of 10 x 10 x 10 grains (radii 1 mm +- 5 %, centres 1.96 mm
/// apart, so that most neighbours overlap and some do not) with random velocities and
/// spins, in a box whose walls hold it together, under gravity, undamped, friction 0.3, without rolling resistance (the kernel's
/// case): contacts stick, slide, open and close from the first step.
Model lattice(ContactLaw law)
{
  Model m;
  // The box's walls press on the outer grains (their gaps 0.98 mm, radii about 1 mm).
  m.domain.origin = Vec3(0.00202, 0.00202, 0.00202);
  m.domain.size = Vec3(0.0196, 0.0196, 0.0196);
  m.material.youngsModulus = 1e8;
  m.material.poissonsRatio = 0.25;
  m.material.density = 2650.0;
  m.material.restitution = 0.5;
  m.material.friction = 0.3;
  m.material.rollingFriction = 0.0;
  m.gravity = Vec3(0.0, 0.0, -9.81);
  m.solver.settlingDamping = 0.0;
  m.solver.contactLaw = law;
  std::mt19937_64 random(17);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int a = 0; a < 10; ++a) {
    for (int b = 0; b < 10; ++b) {
      for (int c = 0; c < 10; ++c) {
        const Vec3 x = Vec3(0.003 + 1.96e-3 * a + 2e-5 * unit(random),
                            0.003 + 1.96e-3 * b + 2e-5 * unit(random),
                            0.003 + 1.96e-3 * c + 2e-5 * unit(random));
        const std::size_t slot = m.particles.size();
        m.particles.append(x, 1e-3 * (1.0 + 0.05 * unit(random)), m.nextId++);
        m.particles.velocity[slot] = 0.05 * Vec3(unit(random), unit(random), unit(random));
        m.particles.angularVelocity[slot] = 20.0 * Vec3(unit(random), unit(random), unit(random));
      }
    }
  }
  updateMassProperties(m);
  return m;
}

} // namespace

// Pair by pair: the lanes against touchingPairForce<double> on random touching pairs and
// the law's branches: new contacts (zero spring), a spring along the normal (projected to
// zero), springs beyond the Coulomb limit (sliding), pulling pairs (force cut off at zero:
// limit 0, spring scaled by 0), zero tangential stiffness, partial last groups (lists of
// 1 to 4 lanes of a group), fixed particles (inverse mass 0).
TEST(CpuSimd, KernelGivesTheScalarLawBitsPairByPair)
{
  if (!kernelAvailable()) {
    GTEST_SKIP() << "no AVX2 kernel on this processor or build: the scalar loop runs alone";
  }
  std::mt19937_64 random(20);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const std::size_t particles = 40;
  const std::size_t pairs = 61;
  std::vector<double> position(3 * particles), velocity(3 * particles), spin(3 * particles),
    lastForce(3 * particles), radius(particles), inverseMass(particles);
  for (std::size_t i = 0; i < particles; ++i) {
    radius[i] = 1e-3 * (1.0 + 0.5 * (unit(random) + 1.0));
    inverseMass[i] = i % 13 == 5 ? 0.0 : 1.0 / (2650.0 * 4.19 * radius[i] * radius[i] * radius[i]);
    for (int c = 0; c < 3; ++c) {
      velocity[3 * i + c] = 0.05 * unit(random);
      spin[3 * i + c] = 20.0 * unit(random);
      lastForce[3 * i + c] = 0.01 * unit(random);
    }
  }
  std::vector<std::uint32_t> pairI(pairs), pairJ(pairs);
  std::vector<double> constants(3 * pairs), spring(3 * pairs);
  for (std::size_t k = 0; k < pairs; ++k) {
    pairI[k] = static_cast<std::uint32_t>(k % particles);
    pairJ[k] = static_cast<std::uint32_t>((k * 7 + 3) % particles);
    if (pairJ[k] == pairI[k]) {
      pairJ[k] = (pairI[k] + 1) % particles;
    }
    constants[3 * k + 0] = 1e7 * (1.0 + unit(random) * 0.3);         // K, N/m^1.5
    constants[3 * k + 1] = k % 5 == 0 ? 0.0 : (k % 11 == 0 ? 200.0 : 2.0) * (1.0 + unit(random)); // c sqrt(m* K)
    constants[3 * k + 2] = k % 17 == 4 ? 0.0 : 1e7 * (1.0 + unit(random) * 0.3);
    for (int c = 0; c < 3; ++c) {
      spring[3 * k + c] = k % 4 == 0 ? 0.0 : 1e-5 * unit(random) * (k % 3 == 0 ? 100.0 : 1.0);
    }
  }
  // Positions: each pair is evaluated on its own position array, in which its two
  // particles overlap (the kernel reads only position[i] and position[j]).
  for (const bool hertz : { true, false }) {
    for (std::size_t k = 0; k < pairs; ++k) {
      std::vector<double> pos(3 * particles, 0.0);
      const std::uint32_t i = pairI[k], j = pairJ[k];
      double d[3] = { unit(random), unit(random), unit(random) };
      const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      const double overlap = (k % 11 == 0 ? 1e-5 : 0.02) * (radius[i] + radius[j]) * (0.5 + 0.5 * std::abs(unit(random)));
      const double distance = radius[i] + radius[j] - overlap;
      for (int c = 0; c < 3; ++c) {
        pos[3 * i + c] = 0.01 * unit(random);
        pos[3 * j + c] = pos[3 * i + c] + distance * d[c] / length;
      }
      // A spring along the normal (rotated into the plane: projected to zero, so zero).
      std::vector<double> springK(spring.begin() + 3 * k, spring.begin() + 3 * k + 3);
      if (k % 23 == 7) {
        for (int c = 0; c < 3; ++c) {
          springK[c] = 1e-5 * d[c] / length;
        }
      }
      // Scalar reference: the scalar loop's instance (Eigen vectors).
      const Vec3 branch(pos[3 * j] - pos[3 * i], pos[3 * j + 1] - pos[3 * i + 1], pos[3 * j + 2] - pos[3 * i + 2]);
      const double separation = std::sqrt(branch.squaredNorm());
      const double depth = (radius[i] + radius[j]) - separation;
      ASSERT_GT(depth, 0.0);
      const Vec3 velocityI(velocity[3 * i], velocity[3 * i + 1], velocity[3 * i + 2]);
      const Vec3 velocityJ(velocity[3 * j], velocity[3 * j + 1], velocity[3 * j + 2]);
      const Vec3 spinI(spin[3 * i], spin[3 * i + 1], spin[3 * i + 2]);
      const Vec3 spinJ(spin[3 * j], spin[3 * j + 1], spin[3 * j + 2]);
      const Vec3 lastForceI(lastForce[3 * i], lastForce[3 * i + 1], lastForce[3 * i + 2]);
      const Vec3 lastForceJ(lastForce[3 * j], lastForce[3 * j + 1], lastForce[3 * j + 2]);
      const TouchingPairInput<Vec3> in{ branch, separation, depth, radius[i], radius[j],
        velocityI, velocityJ, spinI, spinJ, lastForceI, lastForceJ, inverseMass[i], inverseMass[j],
        constants[3 * k], constants[3 * k + 1], constants[3 * k + 2] };
      const double dt = 5e-6;
      Vec3 springScalar(springK[0], springK[1], springK[2]);
      const TouchingPairResult<Vec3> expected =
        touchingPairForce(in, hertz, 0.3, dt, 0.5 * dt, springScalar);

      // The kernel on lists of 1 to 4 copies of this pair's slot in fresh output arrays:
      // each list length leaves a different number of lanes unused.
      for (std::size_t listLength = 1; listLength <= 4; ++listLength) {
        std::vector<double> springOut(spring), normal(pairs, -7.0);
        std::vector<PairResult> rows(pairs); // force, n x Ft, the two arms: 8 doubles per pair
        double* const row = reinterpret_cast<double*>(rows.data());
        std::fill(row, row + 8 * pairs, -7.0);
        std::copy(springK.begin(), springK.end(), springOut.begin() + 3 * k);
        std::vector<std::uint8_t> live(pairs, 0), touching(particles, 0);
        const TouchingPairArrays arrays{ pos.data(), velocity.data(), spin.data(), lastForce.data(),
          radius.data(), inverseMass.data(), pairI.data(), pairJ.data(), constants.data(),
          springOut.data(), row, normal.data(),
          live.data(), touching.data(), hertz, 0.3, dt, 0.5 * dt };
        // The same pair in every listed lane: the results are stored once per lane, equal.
        const std::vector<std::uint32_t> list(listLength, static_cast<std::uint32_t>(k));
        touchingPairsAvx2(arrays, list.data(), list.size());
        EXPECT_EQ(std::memcmp(&springOut[3 * k], springScalar.data(), 3 * sizeof(double)), 0) << "pair " << k;
        EXPECT_EQ(std::memcmp(rows[k].force.data(), expected.force.data(), 3 * sizeof(double)), 0) << "pair " << k;
        EXPECT_EQ(std::memcmp(rows[k].normalCrossFt.data(), expected.normalCrossFt.data(), 3 * sizeof(double)), 0)
          << "pair " << k;
        EXPECT_EQ(std::memcmp(&rows[k].arm[0], &expected.armI, sizeof(double)), 0) << "pair " << k;
        EXPECT_EQ(std::memcmp(&rows[k].arm[1], &expected.armJ, sizeof(double)), 0) << "pair " << k;
        EXPECT_EQ(std::memcmp(&normal[k], &expected.normalForce, sizeof(double)), 0) << "pair " << k;
        EXPECT_EQ(live[k], 1);
        EXPECT_EQ(touching[i] == 1 && touching[j] == 1, expected.normalForce != 0.0) << "pair " << k;
        // Nothing else was written.
        for (std::size_t other = 0; other < pairs; ++other) {
          if (other != k) {
            EXPECT_EQ(normal[other], -7.0);
            for (int c = 0; c < 8; ++c) {
              EXPECT_EQ(row[8 * other + c], -7.0);
            }
            EXPECT_EQ(live[other], 0);
          }
        }
      }
    }
  }
}

// Whole runs: with the kernel and with the scalar loop forced (ROCKDEM_CPU_SIMD=0), on one
// thread and on two, Hertz-Mindlin and linear, the same bits after 1,500 steps of a
// lively confined lattice whose contacts stick, slide, open and close.
TEST(CpuSimd, RunsGiveTheScalarLoopBits)
{
  if (!kernelAvailable()) {
    GTEST_SKIP() << "no AVX2 kernel on this processor or build: the scalar loop runs alone";
  }
  for (const ContactLaw law : { ContactLaw::HertzMindlin, ContactLaw::Linear }) {
    const Model start = lattice(law);
    Model scalar = start;
    scalar.solver.threads = 1;
    {
      SimdSetting off("0");
      ASSERT_FALSE(touchingPairsAvx2Enabled());
      Simulation s(scalar);
      s.advance(1500);
      EXPECT_GT(s.diagnostics().contacts, 2000u); // about 2,500 pairs and 600 wall contacts
    }
    for (const int threads : { 1, 2 }) {
      Model vector = start;
      vector.solver.threads = threads;
      vector.solver.parallelThreshold = 0;
      SimdSetting on(nullptr);
      ASSERT_TRUE(touchingPairsAvx2Enabled());
      Simulation s(vector);
      s.advance(1500);
      SCOPED_TRACE(std::string(law == ContactLaw::HertzMindlin ? "Hertz-Mindlin" : "linear") +
                   ", threads " + std::to_string(threads));
      EXPECT_TRUE(sameBits(scalar.particles.position, vector.particles.position));
      EXPECT_TRUE(sameBits(scalar.particles.velocity, vector.particles.velocity));
      EXPECT_TRUE(sameBits(scalar.particles.angularVelocity, vector.particles.angularVelocity));
      EXPECT_TRUE(sameBits(scalar.particles.force, vector.particles.force));
      EXPECT_TRUE(sameBits(scalar.particles.torque, vector.particles.torque));
      EXPECT_TRUE(sameBits(scalar.contacts.shearSpring, vector.contacts.shearSpring));
      EXPECT_EQ(scalar.contacts.size(), vector.contacts.size());
    }
  }
}

// The AVX2 scan (scanPairsAvx2) lists exactly the pairs that the scalar loop's test says
// touch, and as ended exactly those that do not touch and may hold state, each list in
// pair order, for blocks of every length 1 to 40 (groups of four and a last partial group)
// and every mix of the four lanes: pairs apart, inside the kApart margin, just touching,
// at zero distance, and live or not. It writes nothing beyond its lists' kScanSlack spare
// entries.
TEST(CpuSimd, ScanListsWhatTheScalarTestLists)
{
  if (!kernelAvailable()) {
    GTEST_SKIP() << "no AVX2 kernel on this processor or build: the scalar loop runs alone";
  }
  std::mt19937_64 random(20261207);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int pairs = 400;
  std::vector<double> position(3 * 2 * pairs), radius(2 * pairs);
  std::vector<std::uint32_t> pairI(pairs), pairJ(pairs);
  std::vector<std::uint8_t> live(pairs);
  for (int k = 0; k < pairs; ++k) {
    const int i = 2 * k, j = 2 * k + 1;
    pairI[k] = static_cast<std::uint32_t>(i);
    pairJ[k] = static_cast<std::uint32_t>(j);
    radius[i] = 1e-3 * (0.5 + unit(random));
    radius[j] = 1e-3 * (0.5 + unit(random));
    const double reach = radius[i] + radius[j];
    // The gap along a random direction: apart, touching, at the edge, or at zero distance.
    double distance = 0.0;
    switch (k % 5) {
    case 0: distance = reach * (1.0 + 0.5 * unit(random)); break;  // apart
    case 1: distance = reach * (1.0 - 0.1 * unit(random)); break;  // touching
    case 2: distance = reach; break;                                // overlap 0 or within the margin
    case 3: distance = std::nextafter(reach, 0.0); break;            // just touching
    default: distance = (k % 10 == 4) ? 0.0 : reach * unit(random); // zero distance or deep
    }
    const double a = 2.0 * M_PI * unit(random), c = 2.0 * unit(random) - 1.0, s = std::sqrt(1.0 - c * c);
    for (int d = 0; d < 3; ++d) {
      position[3 * i + d] = 0.01 * unit(random);
    }
    position[3 * j + 0] = position[3 * i + 0] + distance * s * std::cos(a);
    position[3 * j + 1] = position[3 * i + 1] + distance * s * std::sin(a);
    position[3 * j + 2] = position[3 * i + 2] + distance * c;
    live[k] = static_cast<std::uint8_t>(random() % 2);
  }
  TouchingPairArrays arrays{};
  arrays.position = position.data();
  arrays.radius = radius.data();
  arrays.pairI = pairI.data();
  arrays.pairJ = pairJ.data();
  arrays.live = live.data();
  // The scalar loop's test (CpuBackend::computeForces).
  auto touches = [&](int k) {
    const int i = pairI[k], j = pairJ[k];
    const double dx = position[3 * j] - position[3 * i], dy = position[3 * j + 1] - position[3 * i + 1],
                 dz = position[3 * j + 2] - position[3 * i + 2];
    const double reach = radius[i] + radius[j];
    const double distance2 = (dx * dx + dy * dy) + dz * dz;
    const bool apart = distance2 > kApart * (reach * reach);
    const double distance = apart ? 0.0 : std::sqrt(distance2);
    const double overlap = reach - distance;
    return !(apart || overlap <= 0.0 || distance == 0.0);
  };
  int touching = 0, ended = 0;
  for (int first = 0; first + 40 <= pairs; first += 40) {
    for (int length = 1; length <= 40; ++length) {
      const std::uint32_t poison = 0xdeadbeef;
      std::vector<std::uint32_t> list(static_cast<std::size_t>(length) + kScanSlack + 4, poison);
      std::vector<std::uint32_t> endedList(list.size(), poison);
      std::size_t endedCount = 0;
      const std::size_t listed = scanPairsAvx2(arrays, static_cast<std::size_t>(first),
                                               static_cast<std::size_t>(first + length), list.data(),
                                               endedList.data(), endedCount);
      std::vector<std::uint32_t> expectList, expectEnded;
      for (int k = first; k < first + length; ++k) {
        if (touches(k)) {
          expectList.push_back(static_cast<std::uint32_t>(k));
        } else if (live[k]) {
          expectEnded.push_back(static_cast<std::uint32_t>(k));
        }
      }
      ASSERT_EQ(std::vector<std::uint32_t>(list.begin(), list.begin() + listed), expectList)
        << "pairs " << first << " + " << length;
      ASSERT_EQ(std::vector<std::uint32_t>(endedList.begin(), endedList.begin() + endedCount), expectEnded)
        << "pairs " << first << " + " << length;
      for (std::size_t e = static_cast<std::size_t>(length) + kScanSlack; e < list.size(); ++e) {
        ASSERT_EQ(list[e], poison) << "written beyond the slack";
        ASSERT_EQ(endedList[e], poison) << "written beyond the slack";
      }
      touching += static_cast<int>(listed);
      ended += static_cast<int>(endedCount);
    }
  }
  // Both lists were exercised.
  EXPECT_GT(touching, 1000);
  EXPECT_GT(ended, 500);
}

// ---------------------------------------------------------------------------------------
// The AVX2 bond kernel (IntactBondsAvx2.cpp).

namespace {

/// The bonds of the bond-by-bond test, as the kernel's plain arrays.
struct BondCase {
  std::vector<double> position, velocity, spin, radius;
  std::vector<std::uint32_t> bondI, bondJ;
  std::vector<std::uint8_t> failure;
  std::vector<double> bondRadius, kn, ks, tensile, cohesion, friction, beta, softening, damage;
  std::vector<double> normalForce, shearForce, twisting, bending;
  std::vector<double> force, torqueI, torqueJ;
  IntactBondArrays arrays(bool planar)
  {
    return { position.data(), velocity.data(), spin.data(), radius.data(), bondI.data(), bondJ.data(),
             failure.data(), bondRadius.data(), kn.data(), ks.data(), tensile.data(), cohesion.data(),
             friction.data(), beta.data(), softening.data(), damage.data(), normalForce.data(),
             shearForce.data(), twisting.data(), bending.data(), force.data(), torqueI.data(),
             torqueJ.data(), planar, 0.002, 2e-7 };
  }
};

Vec3 row(const std::vector<double>& a, std::size_t k) { return Vec3(a[3 * k], a[3 * k + 1], a[3 * k + 2]); }

/// One bond's step by the scalar loop's functions (Eigen vectors): its new state, its
/// loads and whether it breaks (the brittle law).
struct ScalarBond {
  double normalForce, twisting;
  Vec3 shearForce, bending;
  BondLoads<Vec3> loads;
  BondStresses stresses;
  bool breaks;
};

ScalarBond scalarBond(const BondCase& c, std::size_t k, bool planar)
{
  const std::uint32_t i = c.bondI[k], j = c.bondJ[k];
  Vec3 branch = row(c.position, j) - row(c.position, i);
  if (planar) {
    branch.z() = 0.0; // dem::minimumImage of a 2D section
  }
  const BondAxis<Vec3> axis = bondAxis(branch, c.radius[i], c.radius[j]);
  const BondSection section = bondSection(c.bondRadius[k], planar, 0.002);
  ScalarBond s{ c.normalForce[k], c.twisting[k], row(c.shearForce, k), row(c.bending, k), {}, {}, false };
  advanceBond(axis, section, c.kn[k], c.ks[k], planar, row(c.velocity, i), row(c.velocity, j), row(c.spin, i),
              row(c.spin, j), 2e-7, s.normalForce, s.shearForce, s.twisting, s.bending);
  s.stresses = bondStresses(section, c.bondRadius[k], s.normalForce, s.shearForce, s.twisting, s.bending, c.beta[k]);
  s.breaks = bondFailure(s.stresses, c.tensile[k], c.cohesion[k], c.friction[k]) != BondFailure::Intact;
  s.loads = bondLoads(axis, s.normalForce, s.shearForce, s.twisting, s.bending);
  return s;
}

/// 60 grains and 203 bonds between them in every state the bond loop meets: intact and
/// brittle, broken, softening, damaged without softening, two friction angles, moment
/// contributions 0.5 and 1, with random forces, moments, velocities and spins.
BondCase bondCase()
{
  std::mt19937_64 random(20261208);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  BondCase c;
  const std::size_t particles = 60, bonds = 203;
  for (std::size_t i = 0; i < particles; ++i) {
    c.radius.push_back(1e-3 * (1.0 + 0.3 * unit(random)));
    for (int d = 0; d < 3; ++d) {
      c.position.push_back(0.01 * unit(random));
      c.velocity.push_back(0.05 * unit(random));
      c.spin.push_back(20.0 * unit(random));
    }
  }
  for (std::size_t k = 0; k < bonds; ++k) {
    const std::uint32_t i = static_cast<std::uint32_t>(k % particles);
    std::uint32_t j = static_cast<std::uint32_t>((k * 7 + 3) % particles);
    j = j == i ? (i + 1) % particles : j;
    c.bondI.push_back(i);
    c.bondJ.push_back(j);
    c.failure.push_back(k % 9 == 4 ? static_cast<std::uint8_t>(BondFailure::Tension) : 0);
    c.bondRadius.push_back(0.8 * std::min(c.radius[i], c.radius[j]));
    c.kn.push_back(2e12 * (1.0 + 0.2 * unit(random)));
    c.ks.push_back(0.4 * c.kn.back());
    c.friction.push_back(k % 5 == 0 ? 0.6 : 0.5);
    c.beta.push_back(k % 3 == 0 ? 0.5 : 1.0);
    c.softening.push_back(k % 13 == 6 ? 2.0 : 0.0);
    c.damage.push_back(k % 19 == 5 ? 0.3 : 0.0);
    c.normalForce.push_back(k % 4 == 0 ? 0.0 : 5.0 * unit(random));
    c.twisting.push_back(1e-3 * unit(random));
    for (int d = 0; d < 3; ++d) {
      c.shearForce.push_back(k % 4 == 0 ? 0.0 : 2.0 * unit(random));
      c.bending.push_back(k % 6 == 1 ? 0.0 : 1e-3 * unit(random));
    }
  }
  c.tensile.assign(bonds, 1e30);
  c.cohesion.assign(bonds, 1e30);
  c.force.assign(3 * bonds, -7.0);
  c.torqueI.assign(3 * bonds, -7.0);
  c.torqueJ.assign(3 * bonds, -7.0);
  return c;
}

} // namespace

// Bond by bond: the kernel on ranges of 1 to 40 bonds at several offsets, 3D and 2D,
// against the scalar loop's functions: every bond it steps has the scalar bits (state and
// loads); it hands back exactly the intact bonds that soften or are damaged and every bond
// of a group of four in which one breaks (by tension or by shear, at the strength exactly),
// leaving their state untouched; it touches no broken bond and nothing outside the range,
// and writes nothing in `rest` beyond its kBondScanSlack spare entries.
TEST(CpuSimd, BondKernelGivesTheScalarBitsBondByBond)
{
  if (!kernelAvailable()) {
    GTEST_SKIP() << "no AVX2 kernel on this processor or build: the scalar loop runs alone";
  }
  for (const bool planar : { false, true }) {
    SCOPED_TRACE(planar ? "2D section" : "3D");
    BondCase start = bondCase();
    const std::size_t bonds = start.bondI.size();
    // Strengths at the stresses the step reaches: every 23rd bond breaks in tension at its
    // strength exactly, every 29th in shear at its strength exactly, the others hold.
    for (std::size_t k = 0; k < bonds; ++k) {
      const ScalarBond s = scalarBond(start, k, planar);
      if (k % 23 == 3) {
        start.tensile[k] = s.stresses.sigmaMax;
      } else if (k % 29 == 2) {
        start.tensile[k] = std::abs(s.stresses.sigmaMax) * 2.0 + 1.0;
        start.cohesion[k] = s.stresses.tauMax - s.stresses.compressive * std::tan(start.friction[k]);
      } else {
        start.tensile[k] = std::abs(s.stresses.sigmaMax) * 2.0 + 1.0;
      }
    }
    std::size_t stepped = 0, handedBack = 0, broke = 0;
    for (const std::size_t first : { std::size_t{ 0 }, std::size_t{ 1 }, std::size_t{ 50 }, std::size_t{ 163 } }) {
      for (std::size_t length = 1; length <= 40 && first + length <= bonds; ++length) {
        BondCase c = start;
        const std::uint32_t poison = 0xdeadbeef;
        std::vector<std::uint32_t> rest(length + kBondScanSlack + 4, poison);
        const std::size_t restCount = intactBondsAvx2(c.arrays(planar), first, first + length, rest.data());
        // What the kernel should do: the brittle undamaged intact bonds in groups of four.
        std::vector<std::uint32_t> listed, expectRest;
        for (std::size_t k = first; k < first + length; ++k) {
          if (start.failure[k] != 0) {
            continue;
          }
          if (start.softening[k] > 0.0 || start.damage[k] > 0.0) {
            expectRest.push_back(static_cast<std::uint32_t>(k));
          } else {
            listed.push_back(static_cast<std::uint32_t>(k));
          }
        }
        std::vector<bool> storedHere(bonds, false);
        for (std::size_t g = 0; g < listed.size(); g += 4) {
          const std::size_t end = std::min(listed.size(), g + 4);
          bool anyBreaks = false;
          for (std::size_t l = g; l < end; ++l) {
            anyBreaks = anyBreaks || scalarBond(start, listed[l], planar).breaks;
          }
          for (std::size_t l = g; l < end; ++l) {
            (anyBreaks ? expectRest.push_back(listed[l]) : static_cast<void>(storedHere[listed[l]] = true));
          }
          broke += anyBreaks ? 1 : 0;
        }
        std::vector<std::uint32_t> gotRest(rest.begin(), rest.begin() + static_cast<long>(restCount));
        std::sort(gotRest.begin(), gotRest.end());
        std::sort(expectRest.begin(), expectRest.end());
        ASSERT_EQ(gotRest, expectRest) << "bonds " << first << " + " << length;
        for (std::size_t e = length + kBondScanSlack; e < rest.size(); ++e) {
          ASSERT_EQ(rest[e], poison) << "written beyond the slack";
        }
        for (std::size_t k = 0; k < bonds; ++k) {
          SCOPED_TRACE("bond " + std::to_string(k));
          if (storedHere[k]) {
            const ScalarBond s = scalarBond(start, k, planar);
            ASSERT_EQ(std::memcmp(&c.normalForce[k], &s.normalForce, sizeof(double)), 0);
            ASSERT_EQ(std::memcmp(&c.twisting[k], &s.twisting, sizeof(double)), 0);
            ASSERT_EQ(std::memcmp(&c.shearForce[3 * k], s.shearForce.data(), 3 * sizeof(double)), 0);
            ASSERT_EQ(std::memcmp(&c.bending[3 * k], s.bending.data(), 3 * sizeof(double)), 0);
            ASSERT_EQ(std::memcmp(&c.force[3 * k], s.loads.force.data(), 3 * sizeof(double)), 0);
            ASSERT_EQ(std::memcmp(&c.torqueI[3 * k], s.loads.torqueI.data(), 3 * sizeof(double)), 0);
            ASSERT_EQ(std::memcmp(&c.torqueJ[3 * k], s.loads.torqueJ.data(), 3 * sizeof(double)), 0);
            ++stepped;
          } else { // untouched
            ASSERT_EQ(std::memcmp(&c.normalForce[k], &start.normalForce[k], sizeof(double)), 0);
            ASSERT_EQ(std::memcmp(&c.shearForce[3 * k], &start.shearForce[3 * k], 3 * sizeof(double)), 0);
            ASSERT_EQ(std::memcmp(&c.twisting[k], &start.twisting[k], sizeof(double)), 0);
            ASSERT_EQ(std::memcmp(&c.bending[3 * k], &start.bending[3 * k], 3 * sizeof(double)), 0);
            ASSERT_EQ(c.force[3 * k], -7.0);
            ASSERT_EQ(c.torqueI[3 * k + 2], -7.0);
            ASSERT_EQ(c.torqueJ[3 * k + 1], -7.0);
          }
        }
        handedBack += restCount;
      }
    }
    // Every path was taken.
    EXPECT_GT(stepped, 1500u);
    EXPECT_GT(handedBack, 1000u);
    EXPECT_GT(broke, 150u);
  }
}

// Whole runs of cemented specimens under unconfined compression, with the kernel and with
// the scalar loop forced (ROCKDEM_CPU_SIMD=0), on one thread and on two: the same bits
// (particles, contacts, bonds with their failures and damage) after 1,200 steps that break
// bonds; 3D with tension softening on every third bond, and a 2D section.
TEST(CpuSimd, BondedRunsGiveTheScalarLoopBits)
{
  if (!kernelAvailable()) {
    GTEST_SKIP() << "no AVX2 kernel on this processor or build: the scalar loop runs alone";
  }
  for (const bool planar : { false, true }) {
    SCOPED_TRACE(planar ? "2D section" : "3D");
    Model start = planar ? dem::testing::placedPack(Vec3(0.055, 0.055, 0.002), true, 450, 0.0008, 0.0012, 3)
                         : dem::testing::specimen(600, 0.021, 0.0008, 0.0012, 2);
    if (planar) {
      growElements(start);
    }
    cement(start, dem::testing::testCement());
    ASSERT_GT(start.bonds.size(), 300u);
    for (std::size_t k = 0; k < start.bonds.size(); ++k) {
      start.bonds.softening[k] = !planar && k % 3 == 2 ? 2.0 : 0.0;
    }
    LoadTestSettings press;
    press.mode = TestMode::Compression;
    press.strainRate = 50.0;
    press.maxStrain = 0.2;
    press.sampleInterval = 50;
    press.axis = planar ? 1 : 2; // a section is loaded in its plane
    startLoadTest(start, press);
    Model scalar = start;
    scalar.solver.threads = 1;
    {
      SimdSetting off("0");
      Simulation s(scalar);
      s.advance(1200);
    }
    EXPECT_GT(countBonds(scalar.bonds).broken, 10u) << "the test breaks bonds";
    if (!planar) {
      EXPECT_GT(statetest::softeningBonds(scalar.bonds), 0u) << "bonds are softening at the end";
    }
    for (const int threads : { 1, 2 }) {
      Model vector = start;
      vector.solver.threads = threads;
      vector.solver.parallelThreshold = 0;
      SimdSetting on(nullptr);
      Simulation s(vector);
      s.advance(1200);
      EXPECT_EQ(statetest::firstDifference(scalar, vector), "") << "threads " << threads;
    }
  }
}
