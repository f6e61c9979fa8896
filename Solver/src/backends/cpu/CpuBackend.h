// RockDEM engine: the CPU backend (serial while the work per step is below
// SolverSettings::parallelThreshold particle-equivalents, OpenMP above, decided again at
// every neighbour build; the result never depends on the number of threads).
//
// One step (DESIGN.md "Solver step"): half kick -> drift (periodic wrap) -> wall control
// (dem::controlWalls) and wall motion -> Verlet neighbour list update when any particle
// has moved half the skin (the list of particles near each wall with it, or alone when a
// wall has moved half the skin) -> pair forces (each pair once) -> bond forces ->
// per-particle gather in a fixed order (pairs by partner slot, then its wall contacts,
// evaluated there, then bonds) -> Cundall local damping -> half kick -> wall reaction sums
// in slot order -> clock. Velocity Verlet; velocity-dependent forces use the half-step
// velocity. No floating-point atomics, fixed summation order. It steps the Model's own
// particle arrays in place. SI units throughout.
#pragma once

#include "backends/ContactState.h"
#include "dem/Backend.h"
#include "dem/ContactLaws.h"
#include "dem/Model.h"

#include <cstdint>
#include <string>

namespace dem {

class CpuBackend final : public Backend {
public:
  /// Builds the neighbour list (importing model.contacts by global ids) and the bond lists;
  /// a model that never stepped gets its first forces, a resumed one keeps its stored
  /// forces, springs and wall reactions bit for bit. `timestep` (s) as the driver chose it.
  CpuBackend(Model& model, const ContactModel& contactModel, double timestep);

  std::string path() const override;
  void run(std::int64_t steps) override;
  const ContactState& sync() override { return state_; }
  StabilityReport stability() override;

  /// The contact state, for a backend that starts from the CPU's (the Vulkan backend).
  ContactState& state() { return state_; }

private:
  void rebuildNeighbours(bool importModelHistory);
  void rebuildWallContacts(bool carryHistory);
  bool wallsMoved() const;
  void decideParallel();
  void buildBondLists();
  void computeBondForces(bool incrementState);
  void computeForces(bool incrementHistory, bool closingKick);
  void step();

  Model& model_;
  ContactModel contactModel_;
  double timestep_ = 0.0;
  // The touching pairs run four at a time with AVX2 (TouchingPairsAvx2.cpp) where the
  // processor has it and the environment variable ROCKDEM_CPU_SIMD is not 0 (read when the
  // backend is made); the scalar loop otherwise. The same bits either way.
  bool simd_ = false;
  ContactState state_;
};

} // namespace dem
