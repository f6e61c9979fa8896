// The CPU backend's threads: how the pair loop and the gather share their work
// (balancedRanges, and ChunkClaims, with which a thread done with its range takes the
// chunks left in the others'; CpuBackend.h), and that the result never depends on it: a pack whose
// contacts all sit in its lower slots (where equal shares of the slots gave one thread
// most of the work) ends bit for bit the same on 1, 2, 3 and 4 threads, and however its
// steps are cut into runs (the next step's drift is done in the gather within a run).
#include "backends/cpu/CpuBackend.h"

#include "backends/cpu/WorkerTeam.h"
#include "dem/Model.h"
#include "dem/Simulation.h"
#include "StateFixtures.h" // sameBits, firstDifference
using dem::statetest::firstDifference;
using dem::statetest::sameBits;

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <random>
#include <chrono>
#include <thread>
#include <vector>

using namespace dem;

namespace {

std::uint64_t rangeCost(const std::vector<std::uint32_t>& cost, long first, long last)
{
  std::uint64_t sum = 0;
  for (long c = first; c < last; ++c) {
    sum += cost[static_cast<std::size_t>(c)];
  }
  return sum;
}

/// A column of grains in slot order from the bottom up: the lower 6 layers of 10 x 10 in a
/// jittered lattice 1.96 mm apart (radii 1 mm +- 5 %, so most neighbours overlap), the
/// upper 10 layers 2.6 mm apart (none touch) falling onto them; walls all round, gravity,
/// undamped, random velocities and spins. The contacts (and the work) sit in the first
/// 600 of the 1,600 slots.
Model bottomHeavyColumn(double rollingFriction)
{
  Model m;
  m.domain.origin = Vec3(0.00202, 0.00202, 0.00202);
  m.domain.size = Vec3(0.0196, 0.0196, 0.04);
  m.material.youngsModulus = 1e8;
  m.material.poissonsRatio = 0.25;
  m.material.density = 2650.0;
  m.material.restitution = 0.5;
  m.material.friction = 0.3;
  m.material.rollingFriction = rollingFriction;
  m.gravity = Vec3(0.0, 0.0, -9.81);
  m.solver.settlingDamping = 0.0;
  std::mt19937_64 random(23);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int layer = 0; layer < 16; ++layer) {
    const double z = layer < 6 ? 0.003 + 1.96e-3 * layer : 0.003 + 1.96e-3 * 5 + 2.6e-3 * (layer - 5);
    for (int a = 0; a < 10; ++a) {
      for (int b = 0; b < 10; ++b) {
        const Vec3 x = Vec3(0.003 + 1.96e-3 * a + 2e-5 * unit(random),
                            0.003 + 1.96e-3 * b + 2e-5 * unit(random), z + 2e-5 * unit(random));
        const std::size_t slot = m.particles.size();
        m.particles.append(x, 1e-3 * (1.0 + (layer < 6 ? 0.05 : 0.02) * unit(random)), m.nextId++);
        m.particles.velocity[slot] = 0.05 * Vec3(unit(random), unit(random), unit(random));
        m.particles.angularVelocity[slot] = 20.0 * Vec3(unit(random), unit(random), unit(random));
      }
    }
  }
  updateMassProperties(m);
  return m;
}

} // namespace

TEST(CpuThreads, BalancedRangesSplitTheCostEvenly)
{
  std::vector<long> bounds;
  // Uniform cost: equal ranges.
  const std::vector<std::uint32_t> uniform(100, 7);
  balancedRanges(uniform, 4, bounds);
  EXPECT_EQ(bounds, (std::vector<long>{ 0, 25, 50, 75, 100 }));
  // One part: everything.
  balancedRanges(uniform, 1, bounds);
  EXPECT_EQ(bounds, (std::vector<long>{ 0, 100 }));
  // The work in the first fifth of the chunks (10 times the rest): the ranges cover the
  // chunks in order, without gaps, and each part's cost is within one chunk of its share.
  std::vector<std::uint32_t> skewed(200, 10);
  for (std::size_t c = 0; c < 40; ++c) {
    skewed[c] = 100;
  }
  for (int parts : { 2, 3, 4, 7 }) {
    balancedRanges(skewed, parts, bounds);
    ASSERT_EQ(bounds.size(), static_cast<std::size_t>(parts) + 1);
    EXPECT_EQ(bounds.front(), 0);
    EXPECT_EQ(bounds.back(), 200);
    const std::uint64_t total = rangeCost(skewed, 0, 200);
    for (int p = 0; p < parts; ++p) {
      EXPECT_LE(bounds[p], bounds[p + 1]);
      const double share = static_cast<double>(rangeCost(skewed, bounds[p], bounds[p + 1]));
      EXPECT_NEAR(share, static_cast<double>(total) / parts, 100.0) << parts << " parts, part " << p;
    }
  }
  balancedRanges(skewed, 2, bounds);
  EXPECT_EQ(bounds[1], 28); // 4,000 of the 5,600 in the first 40 chunks: half is 28 chunks in
  // More parts than chunks, and no cost at all: every chunk still in exactly one range.
  balancedRanges(std::vector<std::uint32_t>(3, 1), 5, bounds);
  EXPECT_EQ(bounds.front(), 0);
  EXPECT_EQ(bounds.back(), 3);
  balancedRanges(std::vector<std::uint32_t>(6, 0), 2, bounds);
  EXPECT_EQ(bounds.front(), 0);
  EXPECT_EQ(bounds.back(), 6);
  balancedRanges(std::vector<std::uint32_t>(), 2, bounds);
  EXPECT_EQ(bounds, (std::vector<long>{ 0, 0, 0 }));
}

// Every chunk of a loop goes to exactly one thread, and a thread done with its own range
// takes the chunks left in the others': here rank 0 is slow (it sleeps on each of its
// chunks), and the other ranks claim the rest of its range while it sleeps.
TEST(CpuThreads, ChunkClaimsGiveEachChunkOnceAndLetTheIdleTakeOver)
{
  WorkSplit split;
  dem::WorkerTeam team;
  for (int ranks : { 1, 2, 3, 4 }) {
    const long chunks = 97;
    const ChunkClaims claims = split.split(chunks * 8, 8, 1, ranks);
    ASSERT_EQ(split.ranges.size(), static_cast<std::size_t>(ranks) + 1);
    std::vector<int> claimedBy(static_cast<std::size_t>(chunks), -1);
    std::vector<int> claimCount(static_cast<std::size_t>(chunks), 0);
    team.run(ranks, [&](int rank) {
      int visit = 0;
      for (long c; (c = claims.claim(rank, visit)) >= 0;) {
        claimedBy[static_cast<std::size_t>(c)] = rank; // each chunk written by its one claimant
        claimCount[static_cast<std::size_t>(c)] += 1;
        if (rank == 0 && ranks > 1) {
          std::this_thread::sleep_for(std::chrono::milliseconds(2));
        }
      }
    });
    for (long c = 0; c < chunks; ++c) {
      EXPECT_EQ(claimCount[static_cast<std::size_t>(c)], 1) << ranks << " ranks, chunk " << c;
    }
    if (ranks > 1) {
      // Rank 0's range: it took its first chunk, the others most of the rest.
      const long end0 = split.ranges[1];
      ASSERT_GT(end0, 4);
      EXPECT_EQ(claimedBy[0], 0);
      const long byOthers = std::count_if(claimedBy.begin() + 1, claimedBy.begin() + end0, [](int r) { return r != 0; });
      EXPECT_GT(byOthers, (end0 - 1) / 2) << ranks << " ranks: of rank 0's " << end0 << " chunks";
    }
    // The claims of the next loop start again at the ranges' starts.
    const ChunkClaims again = split.split(chunks * 8, 8, 1, ranks);
    int visit = 0;
    EXPECT_EQ(again.claim(0, visit), 0);
  }
}

// The work of this pack sits in its lower slots; however the threads split it (ranges of
// equal work by the last step's count, which moves as the contacts change), every thread
// count gives the 1-thread bits: positions, velocities, spins, forces,
// torques and the exported contact history. Both pair loops: without rolling resistance
// (the AVX2 kernel where the processor has it) and with it (the scalar loop).
TEST(CpuThreads, BottomHeavyPackSameBitsOnOneToFourThreads)
{
  for (double rolling : { 0.0, 0.1 }) {
    std::vector<Model> runs;
    for (int threads : { 1, 2, 3, 4 }) {
      Model m = bottomHeavyColumn(rolling);
      m.solver.threads = threads;
      m.solver.parallelThreshold = 0;
      Simulation sim(m, SolverDevice::CPU);
      if (threads > 1) {
        EXPECT_EQ(sim.path(), "CPU OpenMP (" + std::to_string(threads) + " threads)");
      }
      sim.advance(300);
      sim.advance(300);
      if (threads == 1) {
        EXPECT_GT(sim.diagnostics().contacts, 300u) << "rolling " << rolling;
      }
      runs.push_back(m);
    }
    for (std::size_t r = 1; r < runs.size(); ++r) {
      SCOPED_TRACE("rolling " + std::to_string(rolling) + ", " + std::to_string(r + 1) + " threads");
      const Particles& a = runs[0].particles;
      const Particles& b = runs[r].particles;
      EXPECT_TRUE(sameBits(a.position, b.position));
      EXPECT_TRUE(sameBits(a.velocity, b.velocity));
      EXPECT_TRUE(sameBits(a.angularVelocity, b.angularVelocity));
      EXPECT_TRUE(sameBits(a.force, b.force));
      EXPECT_TRUE(sameBits(a.torque, b.torque));
      EXPECT_TRUE(sameBits(runs[0].contacts.shearSpring, runs[r].contacts.shearSpring));
      EXPECT_TRUE(sameBits(runs[0].contacts.rollingSpring, runs[r].contacts.rollingSpring));
    }
  }
}

// Within one run of the backend each step's gather also does the next step's kick and
// drift (CpuBackend::run); the last step of a run does not. So how the steps are cut into
// advance() calls (and the driver's runs between its checks) changes no bit: 600 steps in
// one call, and in calls of 1, 7, 50 and 13 steps (of one Simulation, and of a new one for
// each call, which sees only the model), on 1 and 2 threads. The upper grains
// fall at 0.3 m/s more: about 0.5 mm in the 600 steps (dt about 2.8 us), five times the
// half skin (0.095 mm), so the neighbour list is rebuilt along the way, at steps that the
// cuts fall on or next to.
TEST(CpuThreads, BatchesOfAnyLengthGiveTheSameBits)
{
  for (int threads : { 1, 2 }) {
    Model whole = bottomHeavyColumn(0.0);
    for (std::size_t i = 600; i < whole.particles.size(); ++i) {
      whole.particles.velocity[i].z() -= 0.3;
    }
    whole.solver.threads = threads;
    whole.solver.parallelThreshold = 0;
    Model cut = whole;
    Model fresh = whole;
    Simulation a(whole, SolverDevice::CPU);
    Simulation b(cut, SolverDevice::CPU);
    a.advance(600);
    long done = 0;
    const long lengths[] = { 1, 7, 50, 13 };
    for (int k = 0; done < 600; ++k) {
      const long n = std::min(lengths[k % 4], 600 - done);
      b.advance(n);
      // The same cuts with a new Simulation for each call (as a resumed run starts): the
      // model between calls must hold whole steps.
      Simulation c(fresh, SolverDevice::CPU);
      c.advance(n);
      done += n;
    }
    SCOPED_TRACE(std::to_string(threads) + " threads");
    EXPECT_EQ(whole.clock.step, cut.clock.step);
    EXPECT_EQ(firstDifference(whole, cut), "");
    EXPECT_EQ(whole.clock.step, fresh.clock.step);
    EXPECT_EQ(firstDifference(whole, fresh), "");
  }
}
