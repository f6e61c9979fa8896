// RockDEM engine: the seam between the driver (dem::Simulation) and the code that steps
// the particles (DESIGN.md "Driver and backends").
//
// The driver chooses the timestep, runs the load-test state machine and its history rows,
// checks stability and reports diagnostics; it never touches a contact. A backend owns the
// particle arrays while it runs and does everything a step does: half kick and drift,
// wall control (the servo law, dem/WallControl.h), wall motion, neighbour update, contact,
// bond and wall forces, Cundall damping, the closing half kick and the walls' reaction
// sums, then advances the clock. Backends: cpu (serial or OpenMP, backends/cpu/) and
// vulkan (the whole step on a GPU, backends/vulkan/). Every backend gives the same bits.
// This is also where a distributed (MPI) backend will plug in. SI units.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace dem {

struct ContactState;

/// The quantities the driver's stability check needs (Simulation::checkStability).
struct StabilityReport {
  long firstNonFinite = -1;   ///< slot of the first particle with a non-finite position or velocity, or -1
  std::size_t escaped = 0;    ///< particles outside the walls on an axis with walls
  long firstEscaped = -1;     ///< slot of the first of them, or -1
  double kineticEnergy = 0.0; ///< J, translational + rotational
  /// The walls (X-, X+, Y-, Y+, Z-, Z+) after the last step, for the work they do on the
  /// specimen (Simulation::checkStability): position along the axis (m) and the axis
  /// component of the reaction, the force the particles exert on the wall (N).
  std::array<double, 6> wallPosition{};
  std::array<double, 6> wallForce{};
};

/// Device memory a backend holds (none for the CPU backend, whose arrays are host memory).
struct DeviceMemory {
  std::uint64_t total = 0;        ///< bytes
  double perParticle = 0.0;       ///< bytes of the per-particle arrays (and grids), per particle
  double perBond = 0.0;           ///< bytes of the per-bond arrays, per bond
  double perPair = 0.0;           ///< bytes per neighbour-pair slot (pairs, gather lists, history)
  std::uint64_t pairSlots = 0;    ///< neighbour pairs the device lists hold room for now
};

class Backend {
public:
  virtual ~Backend() = default;

  /// Which path runs: "CPU serial", "CPU OpenMP (N threads)", "GPU Vulkan: <device>".
  virtual std::string path() const = 0;

  /// Advances the model by `steps` steps (the clock included). The load test's stage and
  /// settings stay as they are during the call (they change only at a history row, which
  /// the driver takes between calls).
  virtual void run(std::int64_t steps) = 0;

  /// Brings the Model (particles, walls, bonds, clock) and the contact state up to date
  /// with the last step, and returns the contact state.
  virtual const ContactState& sync() = 0;

  /// Non-finite values, escaped particles and kinetic energy after the last step.
  virtual StabilityReport stability() = 0;

  /// Starts (on: from zero) or stops counting what the steps dissipate, for the energy
  /// check's balance: each particle's Cundall damping work and each breaking bond's stored
  /// energy, in the contact state's dampingWork and breakEnergy (sync() brings them). Off
  /// by default: it costs a write per particle per step.
  virtual void countDissipation(bool on) = 0;

  /// Evaluates the contact, bond and wall forces of the present state once, with no time
  /// increment, as a backend newly made from the model evaluates them at its start; passes
  /// the contact state so evaluated to `read`; then puts back everything the evaluation
  /// changed, so that the next step and the diagnostics see the state of the last step.
  /// False, without calling `read`, where the backend cannot (the driver then makes a
  /// backend from a copy of the model: Simulation::freshInteractionForces).
  virtual bool evaluateFresh(const std::function<void(const ContactState&)>& read)
  {
    (void)read;
    return false;
  }

  /// What the backend holds in device memory (zero for the CPU).
  virtual DeviceMemory deviceMemory() const { return {}; }
};

} // namespace dem
