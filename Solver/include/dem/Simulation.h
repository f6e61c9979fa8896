// RockDEM engine: the time-stepping solver (the driver, DESIGN.md "Driver and backends").
//
// The driver chooses the timestep, runs the load-test state machine (wall control each
// step, a history row every Sample Interval steps), checks stability and reports
// diagnostics; a backend (dem/Backend.h) owns the particle arrays while it steps them.
// One step (DESIGN.md "Solver step"): half kick -> drift (periodic wrap) -> wall control
// -> Verlet neighbour list update when any particle has moved half the skin (the list of
// particles near each wall with it, or alone when a wall has moved half the skin) -> pair
// forces (each pair once) -> bond forces -> per-particle gather in a fixed order (pairs by
// partner slot, then its wall contacts, evaluated there, then bonds) -> Cundall local
// damping -> half kick. Velocity Verlet; velocity-dependent forces use the half-step
// velocity. The CPU backend runs serially below SolverSettings::parallelThreshold
// particles, OpenMP above; the result never depends on the number of threads (no
// floating-point atomics, fixed summation order). SI units throughout.
#pragma once

#include "dem/Backend.h"
#include "dem/ContactLaws.h"
#include "dem/LoadTest.h"
#include "dem/Model.h"

#include <array>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace dem {

/// The energy check's factor (Simulation::checkStability): a run stops as unstable when its
/// kinetic energy exceeds this many times the energy available to it.
constexpr double EnergyCheckFactor = 2.0;

/// Raised when a run goes unstable (non-finite values, energy gained without a source,
/// particles escaping the box). The model is left at its last good state.
class InstabilityError : public std::runtime_error {
public:
  explicit InstabilityError(const std::string& message) : std::runtime_error(message) {}
};

/// Snapshot of the state of a run, for status lines and the history.
struct Diagnostics {
  double time = 0.0;                 ///< s
  std::int64_t step = 0;
  double kineticEnergy = 0.0;        ///< J, translational + rotational
  double rmsDisplacement = 0.0;      ///< m, RMS of particle displacements since the pack was built
  std::size_t contacts = 0;          ///< touching particle pairs and particle-wall contacts
  double unbalancedForceRatio = 0.0; ///< mean |net force| / mean |contact force| (PHYSICS.md s.4)
  std::size_t escaped = 0;           ///< particles outside the box on an axis with walls
};

/// Critical timestep (s) of a model for a contact law (PHYSICS.md section 2): Rayleigh
/// for Hertz, mass-spring (translation and rotation, a particle with 12 contacts in 3D,
/// 6 in 2D, at the linear stiffness) for the linear law; bonds in parallel shorten it
/// (mass-spring over each particle's bonds, intact or broken). Depends on particles,
/// material and bonds only, so a reloaded model gets the same value.
double criticalTimestep(const Model& model, ContactLaw law);
/// The contact part of criticalTimestep (without bonds).
double contactTimestep(const Model& model, ContactLaw law);

/// Validates the solver settings (InputError naming the parameter).
void validate(const SolverSettings& settings);

/// Puts the six box walls in the model (none on a periodic axis, no Z walls in 2D),
/// at rest on the faces of the box.
void resetWalls(Model& model);

struct InteractionForces;
struct OverlapReport;

/// The interaction forces a Simulation newly made from `model` reports (its
/// interactionForces(): every contact evaluated once with no time increment), evaluated on
/// a copy (the model itself is not changed). Simulation::freshInteractionForces gives the
/// same bits from a running solver.
InteractionForces freshInteractionForces(const Model& model);

/// Where a Simulation steps: the CPU backend, or the GPU (Vulkan) backend when a device
/// can run the model (else the CPU, and path() says why).
enum class SolverDevice { CPU, GPU };

/// Empty when this machine has a Vulkan device that can run the GPU solver (a GPU request
/// then uses it when the model fits in its memory); otherwise why not, in the words a
/// fallback would use ("no Vulkan device", "... has no double precision in shaders ...").
std::string gpuUnavailableReason();

class Simulation {
public:
  /// Validates the model and settings, calibrates the contact damping, chooses the
  /// timestep and builds the neighbour list. Walls are created if the model has none.
  /// SolverDevice::GPU runs the step on a Vulkan device when one can run the model (no
  /// device, no double precision, too little memory: the CPU, see path()). Both give the
  /// same bits on a device that rounds double precision as IEEE 754 (lavapipe does).
  explicit Simulation(Model& model, SolverDevice device = SolverDevice::CPU);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  /// Advances the model by `steps` physics steps. On instability the model is restored
  /// to its state at the start of this call and InstabilityError is thrown; the
  /// Simulation must then not be used again.
  void advance(std::int64_t steps);

  double criticalTimestep() const { return critical_; }
  double timestep() const { return timestep_; }
  /// Non-empty when a requested timestep was overridden (says both values).
  const std::string& timestepMessage() const { return timestepMessage_; }
  /// Which path runs: "CPU serial (why: too few particles for threads, Threads = 1)",
  /// "CPU OpenMP (N threads)", "GPU Vulkan: <device>", or after a fallback
  /// "CPU ...: GPU requested, fell back because <reason>".
  std::string path() const;
  /// Device memory the run holds (zero on the CPU).
  DeviceMemory deviceMemory() const { return backend_->deviceMemory(); }
  /// Why the GPU was requested but not used (empty otherwise).
  const std::string& gpuFallbackReason() const { return gpuFallbackReason_; }
  const ContactModel& contactModel() const { return contactModel_; }

  Diagnostics diagnostics() const;
  /// J, the work the walls, platens (a tension platen's attached grains) and the membrane
  /// have done on the specimen since this Simulation started, as of the last stability
  /// check (every 64 steps and at the end of each advance; the trapezoid rule between them).
  double boundaryWork() const { return boundaryWork_; }
  /// Total mechanical energy, J: kinetic + gravitational potential (relative to the
  /// origin) + elastic energy stored in the normal and tangential contact springs and in
  /// the intact bonds (normal, shear, twisting and bending springs, times 1 - damage).
  double totalEnergy() const;
  /// J, what the steps have dissipated since this Simulation started, while the backend
  /// counts it (the first 32 steps of a load test, the early checks): the work Cundall
  /// damping took from the particles plus the energy the bonds that broke held. Not
  /// counted: the contacts' viscous damping, sliding and rolling friction (so the balance
  /// E0 + W - (K + U + dissipated) is >= 0 for a physical run). 0 outside that window.
  double dissipatedEnergy() const;

  /// Writes the live contact history into model.contacts (done after every advance()).
  void exportContacts();

  /// The press measurements now: strains, face stresses, Love-Weber stress tensor,
  /// axial/lateral/deviator stress, inertial number, suggested strain rate.
  TestMeasurements measurements() const;
  /// The forces measurements() sums (touching contacts, intact bonds, touching wall
  /// contacts), each with the arms from the centres to its contact point, for the
  /// per-particle stress (dem/ParticleStress.h).
  InteractionForces interactionForces() const;
  /// The forces a Simulation newly made from the model's present state reports (its
  /// interactionForces(): every contact evaluated once with no time increment), which
  /// particleStresses(model) sums: a running stage shows the per-particle stresses that
  /// the state, saved and read back, shows, bit for bit. The CPU backend evaluates them on
  /// its own lists and puts its state back; otherwise a Simulation is made from a copy of
  /// the model (and after an instability, whose last good state the model holds). The
  /// steps that follow are those without the call, bit for bit.
  InteractionForces freshInteractionForces();
  /// The overlapping pairs of the present state (dem::measureOverlaps, bit for bit),
  /// measured on the solver's neighbour list, which holds every pair that can touch (by a
  /// search where the list is not sorted by (i, j)).
  OverlapReport overlaps();

private:
  InteractionForces interactionForces(const ContactState& state) const;
  std::int64_t stepsToNextSample() const;
  void sampleLoadTest(std::int64_t steps);
  double contactForceMagnitude(const ContactState& state, std::size_t particle) const;
  void checkStability(const char* when);
  double availableEnergy() const;
  void accumulateWork(const StabilityReport& report);
  std::string timestepAdvice() const;

  Model& model_;
  std::unique_ptr<Backend> backend_;
  ContactModel contactModel_;
  double critical_ = 0.0;
  double timestep_ = 0.0;
  std::string timestepMessage_;
  std::string gpuFallbackReason_;
  double initialAvailableEnergy_ = 0.0; ///< J, for the energy-gain check
  double gravityWorkAtStart_ = 0.0;     ///< J, gravity's work along periodic axes at the start
  double gravityPotentialAtStart_ = 0.0; ///< J, sum of -m g.x over the particles (non-periodic axes)
  // The work the walls, platens (a tension platen's attached grains) and the membrane have
  // done on the specimen since this Simulation started: the trapezoid rule between
  // stability checks (every 64 steps), kept in memory (a resumed run starts again from its
  // own energy). Simulation::checkStability; Documentation/SpeedAccuracy.md "Stability map".
  double boundaryWork_ = 0.0;                 ///< J
  std::int64_t startStep_ = 0;                ///< the clock's step when this Simulation started
  /// The early checks (kinetic + elastic energy 1, 2, 4, ..., 32 steps after the start) run
  /// only when a load test is set at construction. Outside tests the caller may change the
  /// velocities between advances (Compact Elements' FIRE quench steers them towards the
  /// forces, which can raise the mass-weighted kinetic energy), so the balance does not hold
  /// there: the early checks stopped stable compactions and changed the packs they built.
  /// Those runs keep the kinetic-energy check every 64 steps, as before.
  bool earlyChecks_ = false;
  /// The backend counts the dissipation (during the early checks' window).
  bool countingDissipation_ = false;
  std::array<double, 6> lastWallPosition_{};  ///< m, at the last check
  std::array<double, 6> lastWallForce_{};     ///< N, axis component of the particles' push, at the last check
  std::vector<Vec3> lastMembranePosition_;    ///< m, at the last check (membrane and tension runs)
  std::vector<Vec3> lastMembraneForce_;       ///< N, the push of the membrane or tension platen on each particle at the last check
  bool broken_ = false;                 ///< an instability stopped the run
  /// model.contacts holds the backend's contacts: exported, and no step run since.
  bool contactsExported_ = false;
  /// advance()'s last good state (restored if the call goes unstable), kept between calls
  /// so that its copies reuse their buffers.
  struct SavedState {
    Particles particles;
    std::vector<Wall> walls;
    ContactHistory contacts;
    BondStepState bonds;
    LoadTestState test;
  } saved_;
};

} // namespace dem
