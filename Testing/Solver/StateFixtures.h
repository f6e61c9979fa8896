// The three specimens of the exact-resume tests (TestStateFile.cpp and the separate-
// process check rockdem_state_resume): a settling pack, a cemented specimen in the middle
// of an unconfined compression test with bonds already broken, and a triaxial test in
// the middle of its shearing stage. SI units.
#pragma once

#include "dem/Bonds.h"
#include "dem/Cement.h"
#include "dem/LoadTest.h"
#include "dem/Model.h"
#include "dem/Pack.h"
#include "dem/ParticleStress.h"
#include "dem/Simulation.h"
#include "dem/Specimen.h"
#include "Specimens.h"

#include <cstring>
#include <stdexcept>
#include <string>

namespace dem {
namespace statetest {

/// Loose pack settling under gravity with friction and rolling friction (so contacts
/// carry both shear and rolling springs), after 1000 steps.
inline Model settlingPack()
{
  Model m;
  m.domain.size = Vec3(0.04, 0.04, 0.08);
  m.material.youngsModulus = 1e8;
  m.material.friction = 0.5;
  m.material.rollingFriction = 0.1;
  PackParameters params;
  params.initialElements = 600;
  params.minimumSize = 0.001;
  params.maximumSize = 0.002;
  params.randomSeed = 9;
  buildPack(m, params);
  growElements(m);
  Simulation sim(m);
  sim.advance(1000);
  return m;
}

/// A cemented specimen (400 grains, consolidated at 20 kPa, cemented with `cement`) under
/// unconfined compression, stopped at the first 250-step batch after which `enough(m)`
/// holds; throws naming `name` if the test ends first.
template <class Enough>
inline Model compressedUntil(const CementParameters& cement, Enough enough, const char* name)
{
  Model m = testing::specimen(400, 0.016, 0.0008, 0.0012, 3);
  testing::consolidate(m, 2e4);
  dem::cement(m, cement);
  LoadTestSettings s;
  s.mode = TestMode::Compression;
  s.strainRate = 1.0;
  s.maxStrain = 0.03;
  s.sampleInterval = 100;
  startLoadTest(m, s);
  Simulation sim(m);
  for (int k = 0; k < 400 && !enough(m); ++k) {
    sim.advance(250);
  }
  if (!enough(m) || m.test.stage != TestStage::Shear) {
    throw std::runtime_error(std::string(name) + ": the test ended before the state it waits for");
  }
  return m;
}

/// Cemented specimen under unconfined compression, stopped once bonds have broken.
inline Model cementedMidCompression()
{
  return compressedUntil(testing::testCement(), [](const Model& m) { return countBonds(m.bonds).broken >= 10; },
                         "cementedMidCompression");
}

/// Intact bonds that are softening (0 < damage < 1).
inline std::size_t softeningBonds(const Bonds& b)
{
  std::size_t n = 0;
  for (std::size_t k = 0; k < b.size(); ++k) {
    n += !b.broken(k) && b.damage[k] > 0.0;
  }
  return n;
}

/// The same specimen with tension-softening bonds (Softening Ratio 2), stopped while at
/// least 10 intact bonds are softening.
inline Model softeningMidCompression()
{
  CementParameters c = testing::testCement();
  c.softeningRatio = 2.0;
  return compressedUntil(c, [](const Model& m) { return softeningBonds(m.bonds) >= 10; }, "softeningMidCompression");
}

/// A triaxial test on `m` at 100 kPa with the given confinement, past consolidation, in
/// the middle of shear (between two samples); `name` names it in the error.
inline Model shearing(Model m, Confinement confinement, const char* name)
{
  LoadTestSettings s;
  s.mode = TestMode::Triaxial;
  s.confinement = confinement;
  s.confiningStress = 1e5;
  s.strainRate = 0.5;
  s.sampleInterval = 100;
  startLoadTest(m, s);
  Simulation sim(m);
  for (int k = 0; k < 400 && m.test.stage != TestStage::Shear; ++k) {
    sim.advance(100);
  }
  sim.advance(750);
  if (m.test.stage != TestStage::Shear) {
    throw std::runtime_error(std::string(name) + ": the test is not shearing");
  }
  return m;
}

/// Triaxial test past consolidation, in the middle of shear (between two samples).
inline Model triaxialMidShear()
{
  return shearing(testing::specimen(500, 0.02, 0.001, 0.0015, 1), Confinement::RigidWalls, "triaxialMidShear");
}

/// A cylinder along Z (diameter 10 mm, length 17 mm, about 1000 grains of radius 0.5 to
/// 0.6 mm grown by Compact Elements to porosity 0.37 in a 10 x 10 x 17.6 mm box, carved by
/// DEM Specimen), without gravity, grain modulus 1e8 Pa.
inline Model membraneCylinder()
{
  Model m = testing::placedPack(Vec3(0.0104, 0.0104, 0.0176), false, 1400, 0.0005, 0.0006, 21);
  CompactParameters c;
  c.targetPorosity = 0.37;
  compactElements(m, c);
  SpecimenSettings cylinder;
  cylinder.shape = SpecimenShape::Cylinder;
  cylinder.axis = 2;
  cylinder.diameter = 0.01;
  cylinder.length = 0.017;
  carveSpecimen(m, cylinder);
  return m;
}

/// A triaxial test in a membrane (membraneCylinder), past consolidation at 100 kPa, in the
/// middle of shear (between two samples).
inline Model membraneTriaxialMidShear()
{
  return shearing(membraneCylinder(), Confinement::Membrane, "membraneTriaxialMidShear");
}

inline Model byName(const std::string& name)
{
  if (name == "settling") {
    return settlingPack();
  }
  if (name == "cemented") {
    return cementedMidCompression();
  }
  if (name == "triaxial") {
    return triaxialMidShear();
  }
  if (name == "membrane") {
    return membraneTriaxialMidShear();
  }
  throw std::invalid_argument("unknown specimen '" + name + "' (settling, cemented, triaxial, membrane)");
}

template <class T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b)
{
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

/// The two lists of interaction forces (Simulation::interactionForces) are bitwise
/// identical, entry for entry.
inline bool sameForces(const InteractionForces& a, const InteractionForces& b)
{
  return sameBits(a.slotA, b.slotA) && sameBits(a.slotB, b.slotB) && sameBits(a.force, b.force) &&
    sameBits(a.armA, b.armA) && sameBits(a.armB, b.armB);
}

/// Empty when the particles, contacts, bonds, walls, test state and clock of the two
/// models are bitwise identical; otherwise the name of the first difference.
inline std::string firstDifference(const Model& a, const Model& b)
{
  const Particles& p = a.particles;
  const Particles& q = b.particles;
#define ROCKDEM_SAME(x, y, name) \
  if (!sameBits(x, y)) return name
  ROCKDEM_SAME(p.position, q.position, "particles/position");
  ROCKDEM_SAME(p.velocity, q.velocity, "particles/velocity");
  ROCKDEM_SAME(p.angularVelocity, q.angularVelocity, "particles/angular_velocity");
  ROCKDEM_SAME(p.displacement, q.displacement, "particles/displacement");
  ROCKDEM_SAME(p.force, q.force, "particles/force");
  ROCKDEM_SAME(p.torque, q.torque, "particles/torque");
  ROCKDEM_SAME(p.radius, q.radius, "particles/radius");
  ROCKDEM_SAME(p.mass, q.mass, "particles/mass");
  ROCKDEM_SAME(p.inertia, q.inertia, "particles/inertia");
  ROCKDEM_SAME(p.id, q.id, "particles/id");
  ROCKDEM_SAME(p.flags, q.flags, "particles/flags");
  ROCKDEM_SAME(a.contacts.idA, b.contacts.idA, "contacts/id_a");
  ROCKDEM_SAME(a.contacts.idB, b.contacts.idB, "contacts/id_b");
  ROCKDEM_SAME(a.contacts.shearSpring, b.contacts.shearSpring, "contacts/shear_spring");
  ROCKDEM_SAME(a.contacts.rollingSpring, b.contacts.rollingSpring, "contacts/rolling_spring");
  ROCKDEM_SAME(a.bonds.idA, b.bonds.idA, "bonds/id_a");
  ROCKDEM_SAME(a.bonds.idB, b.bonds.idB, "bonds/id_b");
  ROCKDEM_SAME(a.bonds.normalForce, b.bonds.normalForce, "bonds/normal_force");
  ROCKDEM_SAME(a.bonds.shearForce, b.bonds.shearForce, "bonds/shear_force");
  ROCKDEM_SAME(a.bonds.twistingMoment, b.bonds.twistingMoment, "bonds/twisting_moment");
  ROCKDEM_SAME(a.bonds.bendingMoment, b.bonds.bendingMoment, "bonds/bending_moment");
  ROCKDEM_SAME(a.bonds.damage, b.bonds.damage, "bonds/damage");
  ROCKDEM_SAME(a.bonds.failure, b.bonds.failure, "bonds/failure");
  ROCKDEM_SAME(a.bonds.failureTime, b.bonds.failureTime, "bonds/failure_time");
  ROCKDEM_SAME(a.bonds.failurePosition, b.bonds.failurePosition, "bonds/failure_position");
  ROCKDEM_SAME(a.bonds.failureNormal, b.bonds.failureNormal, "bonds/failure_normal");
  ROCKDEM_SAME(a.test.history, b.test.history, "test/history");
#undef ROCKDEM_SAME
  if (a.walls.size() != b.walls.size()) {
    return "walls (count)";
  }
  for (std::size_t w = 0; w < a.walls.size(); ++w) {
    const Wall& x = a.walls[w];
    const Wall& y = b.walls[w];
    if (std::memcmp(&x.position, &y.position, 8) || std::memcmp(&x.velocity, &y.velocity, 8) ||
        std::memcmp(x.force.data(), y.force.data(), 24) || x.active != y.active ||
        std::memcmp(&x.contactStiffness, &y.contactStiffness, 8) ||
        std::memcmp(&x.elasticForce, &y.elasticForce, 8) || x.contacts != y.contacts) {
      return "walls/" + std::to_string(w);
    }
  }
  if (a.test.settings != b.test.settings) {
    return "test/settings";
  }
  if (a.test.stage != b.test.stage || std::memcmp(&a.test.peakStress, &b.test.peakStress, 8) ||
      std::memcmp(&a.test.peakDeviator, &b.test.peakDeviator, 8) || a.test.settledChecks != b.test.settledChecks ||
      a.test.stepsSinceSample != b.test.stepsSinceSample || a.test.initialSpread != b.test.initialSpread) {
    return "test/state";
  }
  if (std::memcmp(&a.clock.time, &b.clock.time, 8) || a.clock.step != b.clock.step ||
      std::memcmp(&a.clock.timestep, &b.clock.timestep, 8)) {
    return "clock";
  }
  if (!(a.random == b.random) || a.nextId != b.nextId) {
    return "random/counters";
  }
  return "";
}

} // namespace statetest
} // namespace dem
