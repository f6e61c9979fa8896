// RockDEM engine: the CPU backend (serial while the work per step is below
// SolverSettings::parallelThreshold particle-equivalents, on its threads above, decided
// again at every neighbour build; the result never depends on the number of threads).
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
//
// Threads: the loops of a step run on a WorkerTeam (threads kept between loops, waiting
// by a short spin, then asleep). The pair loop, the bond loop and the gather give each thread one range of
// equal work, as the last step counted or timed it (WorkSplit below); a thread done with its range takes
// the chunks still unclaimed in the others' (ChunkClaims below), and within one run() the gather also does
// the next step's half kick and drift of the particles it has just gathered (the last step
// of a run does not, so the model holds whole steps between runs). Neither changes a bit.
#pragma once

#include "backends/ContactState.h"
#include "backends/cpu/WorkerTeam.h"
#include "dem/Backend.h"
#include "dem/ContactLaws.h"
#include "dem/Model.h"

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace dem {

/// Splits the chunks [0, cost.size()) into `parts` contiguous ranges of about equal total
/// cost: part p is [bounds[p], bounds[p + 1]). The CPU backend splits the blocks of its pair
/// loop and the chunks of its gather so, one range per thread, weighed by their work at the
/// previous step, so that the thread holding the contact-rich part of a pack does not do
/// most of the work while the others wait (which thread computes a result never changes a
/// bit of it).
void balancedRanges(const std::vector<std::uint32_t>& cost, int parts, std::vector<long>& bounds);

/// Hands out the chunks of one loop while it runs: thread p claims the chunks of its own
/// range in order, and when its range is done, the chunks still unclaimed in the other
/// ranges (p + 1, p + 2, ... round), so that a thread the machine slows down (a busy core,
/// a virtual processor descheduled for a while) does not hold the others up at the join.
/// Each chunk goes to exactly one thread, and each chunk's results are written once by
/// the thread that claimed it: which thread that is never changes a bit. Copied by value
/// into a loop (two pointers and a count).
class ChunkClaims {
public:
  /// One cursor per range, each on a cache line of its own.
  struct alignas(64) Cursor {
    std::atomic<long> next{ 0 };
  };
  ChunkClaims(Cursor* cursors, const long* ranges, int parts)
    : cursors_(cursors), ranges_(ranges), parts_(parts)
  {
  }
  /// The next chunk for thread `part`, or -1 when every chunk has been claimed. `visit`
  /// holds the thread's place between calls: 0 before its first.
  long claim(int part, int& visit) const
  {
    for (; visit < parts_; ++visit) {
      const int range = (part + visit) % parts_;
      const long chunk = cursors_[range].next.fetch_add(1, std::memory_order_relaxed);
      if (chunk < ranges_[range + 1]) {
        return chunk;
      }
    }
    return -1;
  }

private:
  Cursor* cursors_;
  const long* ranges_;
  int parts_;
};

/// One loop's split among the threads: the cost of each chunk of its items at the chunk's
/// last evaluation (counted or timed, CpuBackend.cpp) and each thread's range of chunks.
struct WorkSplit {
  std::vector<std::uint32_t> cost;
  std::vector<long> ranges; // thread p starts with the chunks [ranges[p], ranges[p + 1])
  /// Sizes `cost` for `count` items in chunks of `chunk` (a chunk not evaluated yet costs
  /// chunk x `unmeasured`), splits it into `parts` ranges (balancedRanges) and returns the
  /// claims of the loop that runs next: each range's cursor at its first chunk.
  ChunkClaims split(long count, long chunk, std::uint32_t unmeasured, int parts);

private:
  std::unique_ptr<ChunkClaims::Cursor[]> cursors_;
  int cursorCount_ = 0;
};

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
  void countDissipation(bool on) override;
  bool evaluateFresh(const std::function<void(const ContactState&)>& read) override;

  /// The contact state, for a backend that starts from the CPU's (the Vulkan backend).
  ContactState& state() { return state_; }

private:
  void rebuildNeighbours(bool importModelHistory);
  void rebuildWallContacts(bool carryHistory);
  bool wallsMoved() const;
  void decideParallel();
  void buildBondLists();
  void computeBondForces(bool incrementState);
  void computeForces(bool incrementHistory, bool closingKick, bool driftNext = false);
  void step(bool last);
  void evaluateKeepingStepState();

  Model& model_;
  ContactModel contactModel_;
  double timestep_ = 0.0;
  // The touching pairs and the intact bonds run four at a time with AVX2
  // (TouchingPairsAvx2.cpp, IntactBondsAvx2.cpp) where the processor has it and the
  // environment variable ROCKDEM_CPU_SIMD is not 0 (read when the backend is made); the
  // scalar loops otherwise. The same bits either way.
  bool simd_ = false;
  ContactState state_;
  // How the pair loop (blocks of kPairBlock pairs, counted in rough instruction units),
  // the gather (chunks of kGatherChunk particles, timed) and the bond loop (chunks of
  // kBondChunk bonds, timed) are split among the threads this step (CpuBackend.cpp).
  WorkSplit pairSplit_, gatherSplit_, bondSplit_;
  // run() did the next step's kick and drift in the last gather (and whether that made the
  // neighbour list stale): the step starts at the wall control.
  bool drifted_ = false;
  bool driftedStale_ = false;
  // countDissipation: the steps add to the contact state's dampingWork and breakEnergy.
  bool countDissipation_ = false;
  // The threads of the step's loops (drift, pairs, bonds, gather), kept between loops
  // (WorkerTeam.h); the neighbour rebuild still uses OpenMP. Each rank's "the list is
  // stale" from its share of the drift.
  WorkerTeam team_;
  std::vector<std::uint8_t> staleByRank_;
  // Per thread, the gather's work space for one chunk of particles (computeForces): the
  // chunk's pair entries that act with the chunk slot of their particle, and the
  // particles' sums of them.
  struct GatherScratch {
    std::vector<std::uint32_t> entry, owner;
    std::vector<Vec3> force, torque;
  };
  std::vector<GatherScratch> gatherScratch_;
  // What an evaluation with no time increment changes and the next step reads
  // (evaluateKeepingStepState), and the rows of the contacts that acted before it
  // (evaluateFresh). Copies held only during the call: kept, they would add about 150
  // and 250 bytes per particle of a contact-rich pack (three acting pairs per particle) to
  // a running solver.
  struct StepStateCopy {
    std::vector<Vec3> force, torque, pairSpring, pairRolling, wallSpring, wallRolling;
    std::vector<std::uint8_t> pairLive;
    std::vector<Wall> walls;
  };
  struct ActingCopy {
    std::vector<Vec3> undampedForce, wallForce, rollingTorque;
    std::vector<double> wallNormal, wallStiffness, wallElastic, pairNormal;
    std::vector<std::uint8_t> wallTouching;
    std::vector<std::uint32_t> pair; // the pairs with a normal force
    std::vector<PairResult> row;
  };
};

} // namespace dem
