// RockDEM engine: the contact lists of a running model in host memory, in the layout
// the CPU backend steps on (and the Vulkan backend mirrors when the driver asks).
//
// Neighbour pairs sorted by (i, j), their history and last forces; per-particle gather
// lists; the sparse particle-wall list; the bond lists. The driver's reductions (Love-Weber
// stress, force balance, elastic energy, exported history) read this structure, so that
// they are written once and give the same bits whichever backend stepped. SI units.
#pragma once

#include "dem/ContactLaws.h"
#include "dem/Model.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace dem {

/// One pair's results, in one 64-byte cache line: the gather reads one line per entry
/// (three rows of three arrays before, which waited on memory in a large pack). The torque
/// of the contact force about i's centre is arm[0] (n x Ft), about j's arm[1] (n x Ft), each
/// product rounded as the pair law rounds it (TouchingPair.h): the same bits.
struct alignas(64) PairResult {
  Vec3 force = Vec3::Zero();         ///< N, force on i (j gets the opposite)
  Vec3 normalCrossFt = Vec3::Zero(); ///< N, the normal (i to j) cross the tangential force
  double arm[2] = { 0.0, 0.0 };      ///< m, from i's (0) and j's (1) centre to the contact point
};
static_assert(sizeof(PairResult) == 64, "one pair's results fill one cache line");

struct ContactState {
  // Neighbour list: particle pairs (slots i < j) within reach, sorted by (i, j).
  std::vector<std::uint32_t> pairI, pairJ;
  std::vector<ContactConstants> pairConstants; // per pair: stiffness and damping factors
  std::vector<Vec3> pairSpring;      // m, tangential history
  std::vector<Vec3> pairRolling;     // N m, rolling history (empty if rolling is off)
  // What the pair loop gives (PairResult: the force, n x Ft and the two arms, one cache
  // line per pair), and the rolling resistance torque on i (N m; j gets the opposite;
  // empty if rolling is off). The torques about the centres are the arms times n x Ft
  // plus (on j minus) the rolling torque: the gather computes them.
  std::vector<PairResult> pairResult;
  std::vector<Vec3> pairRollingTorque;
  std::vector<double> pairNormal;    // N, normal force magnitude (0: adds nothing, the gather skips it)
  // 1: the pair may hold state (a normal force, a spring or a rolling spring) that its
  // end must clear; 0: all of it is zero. Set by every evaluation of a touching pair and
  // by a rebuild, cleared where a pair that does not touch has been cleared: the pair
  // loop reads one byte instead of 32 or 56 for the many pairs that do not touch.
  std::vector<std::uint8_t> pairLive;
  // Per-particle gather lists (CSR): entries of particle i in [start[i], start[i+1]);
  // an entry is 2 * pair + (1 if the particle is j of the pair). 32 bits, as on the
  // device: the gather walks them every step, and half the bytes is half the traffic.
  std::vector<std::uint32_t> adjacencyStart;
  std::vector<std::uint32_t> adjacency;
  // 1: the particle has a touching pair this step (set by the pair loop, cleared by the
  // gather). A particle without one skips its gather list, whose pair entries lie all
  // over memory in a large pack.
  std::vector<std::uint8_t> touching;
  // Wall contacts, sparse: one entry per particle and active wall whose gap was below the
  // skin when the list was built (the particles at positionAtBuild, the walls at
  // wallPositionAtBuild), sorted by (slot, wall). Entries of particle i are
  // [wallStart[i], wallStart[i+1]). The list is rebuilt with the neighbour list, and
  // when a wall has moved half the skin or was switched on or off.
  std::vector<std::uint32_t> wallStart;
  std::vector<std::uint32_t> wallSlot;     // particle slot of each entry
  std::vector<std::uint8_t> wallIndex;     // wall (0..5) of each entry
  std::vector<ContactConstants> wallConstants;
  std::vector<std::uint8_t> wallTouching;  // 1: overlapping at the last evaluation
  std::vector<Vec3> wallSpring;      // m
  std::vector<Vec3> wallRolling;     // N m (empty if rolling is off)
  std::vector<Vec3> wallForce;       // N, force of the wall on the particle
  std::vector<double> wallNormal;    // N
  std::vector<double> wallStiffness; // N/m, normal stiffness of each wall contact (servo gain)
  std::vector<double> wallElastic;   // N, elastic part of each wall contact's normal force
  std::array<double, 6> wallPositionAtBuild{};
  std::array<bool, 6> wallActiveAtBuild{};
  std::vector<Vec3> undampedForce;   // N, net force before local damping (platen reactions)
  // While the backend counts dissipation (Backend::countDissipation): the work Cundall
  // damping took from each particle (J, per slot), and the energy each bond's springs held
  // when it broke (J, per bond; 0 for the others), since counting started.
  std::vector<double> dampingWork;
  std::vector<double> breakEnergy;
  // External forces on the particles (N, per slot; empty: none): the membrane of a
  // cylindrical specimen (dem/Membrane.h), recomputed from the positions every step.
  std::vector<Vec3> externalForce;
  // Bonds (static list, model.bonds order): slots of A and B, per-bond results, and
  // per-particle gather lists (entry 2 * bond + 1 if the particle is B).
  std::vector<std::uint32_t> bondI, bondJ;
  std::vector<Vec3> bondForce;       // N, force on A
  std::vector<Vec3> bondTorqueI;     // N m
  std::vector<Vec3> bondTorqueJ;     // N m
  std::vector<std::size_t> bondAdjacencyStart;
  std::vector<std::size_t> bondAdjacency;
  // Positions at the last neighbour build (for the skin criterion).
  std::vector<Vec3> positionAtBuild;
  double skinDistance = 0.0;         // m
  double smallestRadius = 0.0;       // m
  std::vector<double> inverseMass;   // 1/kg (0 for fixed particles)
  std::vector<double> inverseInertia;
  int threads = 1;       // CPU backend: OpenMP threads offered (used when parallel)
  bool parallel = false; // CPU backend: this list's step runs on `threads` threads
  double work = 0.0;     // CPU backend: work per step at the last neighbour build, in
                         // particle-equivalents (see CpuBackend::decideParallel)
};

} // namespace dem
