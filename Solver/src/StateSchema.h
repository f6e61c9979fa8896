// RockDEM engine: the schema of the state file, written once (internal header).
//
// visitModel() lists every field of a dem::Model with its dataset path and unit. The
// writer and the reader (StateFileWrite.cpp, StateFileRead.cpp) both walk this one list,
// so they cannot disagree. ADDING A FIELD TO THE MODEL IS ONE LINE HERE (and a row in
// Documentation/StateFile.md; update the recorded struct sizes in
// Testing/Solver/TestStateFile.cpp, which fail on purpose until you do). A reader of
// format version 1 requires every dataset listed here. A field added later is either
// required (bump StateFormatVersion) or optional, so that older files still read:
//   if (io.has("bonds/new_field")) io.column("bonds/new_field", b.newField, nb, "Pa", perBond);
//   else b.newField.assign(nb, 0.0);   // the documented default for older files
// (the writer's has() is always true, so it is always written).
//
// The IO interface (both directions):
//   f64/i64/i32/u8flag(path, value, unit)      scalar datasets
//   enumeration(path, value, maxValue)         an enum stored as its int32 value, 0..maxValue
//   vec3 / doubles3 / flags3 / u64x4           small fixed arrays
//   length(path, n)                            writer: n; reader: the length of the dataset
//   column(path, vector, n, unit, per)         one value (or Vec3 row) per element
//   columnZeroOr(path, vector, n, unit, per)   as column, but may also be empty
//   table(path, rows)                          the test history, rows x HistoryColumnCount
//   has(path)                                  writer: true; reader: the dataset exists
//   IO::Reading                                true in the reader
#pragma once

#include "dem/Bonds.h"
#include "dem/LoadTest.h"
#include "dem/Model.h"
#include "dem/SolverState.h"

#include <array>
#include <cstdint>
#include <vector>

namespace dem {
namespace state {

/// Walls as a structure of arrays (the file stores one dataset per wall field).
struct WallColumns {
  std::vector<std::int32_t> axis, side;
  std::vector<double> position, velocity, contactStiffness, elasticForce;
  std::vector<std::uint8_t> active;
  std::vector<Vec3> force;
  std::vector<std::int64_t> contacts;
};

inline WallColumns toColumns(const std::vector<Wall>& walls)
{
  WallColumns c;
  for (const Wall& w : walls) {
    c.axis.push_back(w.axis);
    c.side.push_back(w.side);
    c.position.push_back(w.position);
    c.velocity.push_back(w.velocity);
    c.active.push_back(w.active ? 1 : 0);
    c.force.push_back(w.force);
    c.contactStiffness.push_back(w.contactStiffness);
    c.elasticForce.push_back(w.elasticForce);
    c.contacts.push_back(w.contacts);
  }
  return c;
}

inline std::vector<Wall> fromColumns(const WallColumns& c)
{
  std::vector<Wall> walls(c.position.size());
  for (std::size_t k = 0; k < walls.size(); ++k) {
    Wall& w = walls[k];
    w.axis = c.axis[k];
    w.side = c.side[k];
    w.position = c.position[k];
    w.velocity = c.velocity[k];
    w.active = c.active[k] != 0;
    w.force = c.force[k];
    w.contactStiffness = c.contactStiffness[k];
    w.elasticForce = c.elasticForce[k];
    w.contacts = c.contacts[k];
  }
  return walls;
}

/// Every field of the model, in file order. `m` is only read by the writer.
template <class IO>
void visitModel(IO& io, Model& m)
{
  // ---- /settings: every model parameter ---------------------------------------------
  io.vec3("settings/domain/origin", m.domain.origin, "m");
  io.vec3("settings/domain/size", m.domain.size, "m");
  io.flags3("settings/domain/periodic", m.domain.periodic);
  io.u8flag("settings/domain/section_2d", m.domain.section2D);
  if (io.has("settings/domain/cylinder_axis")) {
    io.i32("settings/domain/cylinder_axis", m.domain.cylinderAxis, "1");
  } else {
    m.domain.cylinderAxis = -1; // files written before the outline: a box
  }
  io.f64("settings/material/density", m.material.density, "kg/m^3");
  io.f64("settings/material/youngs_modulus", m.material.youngsModulus, "Pa");
  io.f64("settings/material/poissons_ratio", m.material.poissonsRatio, "1");
  io.f64("settings/material/restitution", m.material.restitution, "1");
  io.f64("settings/material/friction", m.material.friction, "1");
  io.f64("settings/material/rolling_friction", m.material.rollingFriction, "1");
  io.vec3("settings/gravity", m.gravity, "m/s^2");
  io.enumeration("settings/solver/contact_law", m.solver.contactLaw, 1);
  io.f64("settings/solver/timestep_safety", m.solver.timestepSafety, "1");
  io.f64("settings/solver/requested_timestep", m.solver.requestedTimestep, "s");
  io.f64("settings/solver/settling_damping", m.solver.settlingDamping, "1");
  io.f64("settings/solver/skin", m.solver.skin, "1");
  io.i32("settings/solver/threads", m.solver.threads, "1");
  io.i64("settings/solver/parallel_threshold", m.solver.parallelThreshold, "1");
  io.u8flag("settings/solver/allow_unsafe_timestep", m.solver.allowUnsafeTimestep);

  // ---- /clock, /random, /counters ------------------------------------------------------
  io.f64("clock/time", m.clock.time, "s");
  io.i64("clock/step", m.clock.step, "1");
  io.f64("clock/timestep", m.clock.timestep, "s");
  std::array<std::uint64_t, 4> randomState = m.random.state();
  io.u64x4("random/state", randomState);
  if (IO::Reading) {
    m.random.setState(randomState);
  }
  io.i64("counters/next_id", m.nextId, "1");

  // ---- /particles: one row per particle ------------------------------------------------
  Particles& p = m.particles;
  const std::size_t n = io.length("particles/id", p.size());
  const char* perParticle = "one per particle";
  io.column("particles/id", p.id, n, "1", perParticle);
  io.column("particles/flags", p.flags, n, "1", perParticle);
  io.column("particles/position", p.position, n, "m", perParticle);
  io.column("particles/velocity", p.velocity, n, "m/s", perParticle);
  io.column("particles/angular_velocity", p.angularVelocity, n, "rad/s", perParticle);
  io.column("particles/displacement", p.displacement, n, "m", perParticle);
  io.column("particles/force", p.force, n, "N", perParticle);
  io.column("particles/torque", p.torque, n, "N m", perParticle);
  io.column("particles/radius", p.radius, n, "m", perParticle);
  io.column("particles/mass", p.mass, n, "kg", perParticle);
  io.column("particles/inertia", p.inertia, n, "kg m^2", perParticle);

  // ---- /contacts: the history of live contacts (slip and rolling springs) --------------
  ContactHistory& c = m.contacts;
  const std::size_t nc = io.length("contacts/id_a", c.size());
  const char* perContact = "one per contact";
  io.column("contacts/id_a", c.idA, nc, "1", perContact);
  io.column("contacts/id_b", c.idB, nc, "1", perContact);
  io.column("contacts/shear_spring", c.shearSpring, nc, "m", perContact);
  io.columnZeroOr("contacts/rolling_spring", c.rollingSpring, nc, "N m", perContact);

  // ---- /bonds: every bond, intact or broken, with its state ----------------------------
  Bonds& b = m.bonds;
  const std::size_t nb = io.length("bonds/id_a", b.size());
  const char* perBond = "one per bond";
  io.column("bonds/id_a", b.idA, nb, "1", perBond);
  io.column("bonds/id_b", b.idB, nb, "1", perBond);
  io.column("bonds/radius", b.radius, nb, "m", perBond);
  io.column("bonds/normal_stiffness", b.normalStiffness, nb, "N/m^3", perBond);
  io.column("bonds/shear_stiffness", b.shearStiffness, nb, "N/m^3", perBond);
  io.column("bonds/tensile_strength", b.tensileStrength, nb, "Pa", perBond);
  io.column("bonds/cohesion", b.cohesion, nb, "Pa", perBond);
  io.column("bonds/friction_angle", b.frictionAngle, nb, "rad", perBond);
  if (io.has("bonds/moment_contribution")) {
    io.column("bonds/moment_contribution", b.momentContribution, nb, "1", perBond);
  } else {
    b.momentContribution.assign(nb, 1.0); // files before the factor: the full moments
  }
  if (io.has("bonds/softening_ratio")) {
    io.column("bonds/softening_ratio", b.softening, nb, "1", perBond);
  } else {
    b.softening.assign(nb, 0.0); // files before tension softening: brittle bonds
  }
  io.column("bonds/normal_force", b.normalForce, nb, "N", perBond);
  io.column("bonds/shear_force", b.shearForce, nb, "N", perBond);
  io.column("bonds/twisting_moment", b.twistingMoment, nb, "N m", perBond);
  io.column("bonds/bending_moment", b.bendingMoment, nb, "N m", perBond);
  if (io.has("bonds/damage")) {
    io.column("bonds/damage", b.damage, nb, "1", perBond);
  } else {
    b.damage.assign(nb, 0.0);
  }
  io.column("bonds/failure", b.failure, nb, "1", perBond);
  io.column("bonds/failure_time", b.failureTime, nb, "s", perBond);
  io.column("bonds/failure_position", b.failurePosition, nb, "m", perBond);
  io.column("bonds/failure_normal", b.failureNormal, nb, "1", perBond);

  // ---- /walls: the six box walls with their servo state (none before the first run) ----
  WallColumns w = toColumns(m.walls);
  const std::size_t nw = io.length("walls/axis", w.axis.size());
  const char* perWall = "one per wall";
  io.column("walls/axis", w.axis, nw, "1", perWall);
  io.column("walls/side", w.side, nw, "1", perWall);
  io.column("walls/position", w.position, nw, "m", perWall);
  io.column("walls/velocity", w.velocity, nw, "m/s", perWall);
  io.column("walls/active", w.active, nw, "1", perWall);
  io.column("walls/force", w.force, nw, "N", perWall);
  io.column("walls/contact_stiffness", w.contactStiffness, nw, "N/m", perWall);
  io.column("walls/elastic_force", w.elasticForce, nw, "N", perWall);
  io.column("walls/contacts", w.contacts, nw, "1", perWall);
  if (IO::Reading) {
    m.walls = fromColumns(w);
  }

  // ---- /test: the load-test state machine and its history ------------------------------
  LoadTestSettings& ts = m.test.settings;
  io.enumeration("test/settings/mode", ts.mode, static_cast<int>(TestMode::Brazilian));
  io.i32("test/settings/axis", ts.axis, "1");
  io.f64("test/settings/confining_stress", ts.confiningStress, "Pa");
  io.f64("test/settings/strain_rate", ts.strainRate, "1/s");
  io.f64("test/settings/max_strain", ts.maxStrain, "1");
  io.f64("test/settings/servo_alpha", ts.servoAlpha, "1");
  io.i64("test/settings/sample_interval", ts.sampleInterval, "1");
  io.f64("test/settings/settle_tolerance", ts.settleTolerance, "1");
  if (io.has("test/settings/grip_length")) {
    io.f64("test/settings/grip_length", ts.gripLength, "1");
  } else {
    ts.gripLength = 1.0; // files written before Grip Length: the grip was one largest diameter
  }
  if (io.has("test/settings/platen_friction")) {
    io.f64("test/settings/platen_friction", ts.platenFriction, "1");
  } else {
    ts.platenFriction = 0.0; // files written before Platen Friction: frictionless platens
  }
  if (io.has("test/settings/consolidation_damping")) {
    io.f64("test/settings/consolidation_damping", ts.consolidationDamping, "1");
  } else {
    // files written before Consolidation Damping: the whole test ran at Settling Damping
    // (read above, /settings/solver)
    ts.consolidationDamping = m.solver.settlingDamping;
  }
  if (io.has("test/settings/confinement")) {
    io.enumeration("test/settings/confinement", ts.confinement, static_cast<int>(Confinement::Membrane));
  } else {
    ts.confinement = Confinement::RigidWalls; // files written before Confinement: rigid faces
  }
  LoadTestState& t = m.test;
  io.enumeration("test/state/stage", t.stage, static_cast<int>(TestStage::Done));
  io.doubles3("test/state/initial_length", t.initialLength, "m");
  io.f64("test/state/initial_volume", t.initialVolume, "m^3");
  io.f64("test/state/peak_stress", t.peakStress, "Pa");
  io.f64("test/state/peak_deviator", t.peakDeviator, "Pa");
  io.i64("test/state/settled_checks", t.settledChecks, "1");
  io.i64("test/state/steps_since_sample", t.stepsSinceSample, "1");
  io.doubles3("test/state/initial_spread", t.initialSpread, "m");
  io.table("test/history", t.history);
}

} // namespace state
} // namespace dem
