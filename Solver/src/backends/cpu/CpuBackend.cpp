#include "backends/cpu/CpuBackend.h"

#include "SlotLookup.h"
#include "dem/BondLaw.h"
#include "dem/Bonds.h"
#include "dem/Errors.h"
#include "dem/Membrane.h"
#include "dem/SizeClassGrids.h"
#include "dem/WallControl.h"
#include "backends/cpu/IntactBond.h"
#include "backends/cpu/TouchingPair.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <numeric>
#include <string>
#include <type_traits>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace dem {
namespace {

int availableThreads()
{
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

/// The start of part `part` of `count` items split into `parts` contiguous parts of
/// (nearly) equal size; part p is [evenShare(count, p, parts), evenShare(count, p + 1, parts)).
long evenShare(long count, int part, int parts)
{
  return static_cast<long>(static_cast<std::int64_t>(count) * part / parts);
}

/// dem::minimumImage for the hot loops: a box without periodic axes (and not a 2D section)
/// takes the plain difference, decided once.
class MinimumImage {
public:
  explicit MinimumImage(const Domain& d)
    : domain_(d)
    , plain_(!d.periodic[0] && !d.periodic[1] && !d.periodic[2] && !d.section2D)
  {
  }
  Vec3 operator()(const Vec3& a, const Vec3& b) const
  {
    return plain_ ? Vec3(b - a) : minimumImage(domain_, a, b);
  }
  /// True when the separation is the plain difference b - a.
  bool plain() const { return plain_; }

private:
  const Domain& domain_;
  bool plain_;
};

Vec3 separation(const Domain& d, const Vec3& a, const Vec3& b) { return minimumImage(d, a, b); }

/// The opening half kick of velocity Verlet and the drift of particle i, with the periodic
/// wrap: true when it has moved half the skin (limit2 is its square) since the neighbour
/// list was built. It reads and writes particle i's state only. (All by value or raw
/// pointer, as the hot loops read the arrays: CpuBackend::computeForces.)
[[gnu::always_inline]] inline bool kickAndDrift(std::size_t i, Vec3* position, Vec3* velocity, Vec3* spin,
  Vec3* displacement, const Vec3* force, const Vec3* torque, const Vec3* positionAtBuild,
  const double* inverseMass, const double* inverseInertia, double dt, double half, bool planar,
  bool anyPeriodic, const Domain& d, const MinimumImage& separationOf, double limit2)
{
  // A fixed particle is kinematic: forces do not change its velocity (inverse mass
  // 0), but it moves with the velocity it was given (at rest unless prescribed).
  velocity[i] += (half * inverseMass[i]) * force[i];
  spin[i] += (half * inverseInertia[i]) * torque[i];
  if (planar) {
    velocity[i].z() = 0.0;
    spin[i].x() = 0.0;
    spin[i].y() = 0.0;
  }
  const Vec3 move = dt * velocity[i];
  position[i] += move;
  displacement[i] += move;
  for (int k = 0; anyPeriodic && k < 3; ++k) {
    if (d.periodic[k]) {
      const double lo = d.origin[k];
      const double length = d.size[k];
      if (position[i][k] < lo) {
        position[i][k] += length;
      } else if (position[i][k] >= lo + length) {
        position[i][k] -= length;
      }
    }
  }
  return separationOf(positionAtBuild[i], position[i]).squaredNorm() > limit2;
}

// kApart: the squared-distance rejection of pairs that do not touch (TouchingPair.h).

/// a when c, else b, without a branch.
inline const Vec3* chooseRow(bool c, const Vec3* a, const Vec3* b)
{
  const std::uintptr_t m = std::uintptr_t{ 0 } - static_cast<std::uintptr_t>(c);
  return reinterpret_cast<const Vec3*>((reinterpret_cast<std::uintptr_t>(a) & m) |
                                       (reinterpret_cast<std::uintptr_t>(b) & ~m));
}

/// -v when flip, else v (the sign bits flipped, without a branch).
inline Vec3 withSignFlipped(const Vec3& v, bool flip)
{
  const std::uint64_t sign = static_cast<std::uint64_t>(flip) << 63;
  Vec3 out;
  for (int c = 0; c < 3; ++c) {
    std::uint64_t bits;
    std::memcpy(&bits, &v[c], sizeof bits);
    bits ^= sign;
    std::memcpy(&out[c], &bits, sizeof bits);
  }
  return out;
}

/// Adds particle i's share of a bond's force and torques to its sums, without a branch on
/// the entry (whether it acts and which end i is are data, and a branch on them was
/// mispredicted about one entry in three): i of the bond adds the force and torque I,
/// j minus the force and torque J, and an entry that does not act (`live` false) adds
/// -0.0, which leaves every sum as it is (x + -0.0 is x for every x, -0.0 included), as
/// skipping it did; minus the force is the force with its sign bit flipped (x - y is
/// x + (-y)). The same bits as the branches.
[[gnu::always_inline]] inline void addEntry(bool live, bool asJ, const Vec3* force, const Vec3* torqueI,
                                            const Vec3* torqueJ, Vec3& sumForce, Vec3& sumTorque)
{
  // The rows are read whether the entry acts or not, so that their loads need not wait for
  // the load of `live` (two cache misses one after the other, on a large pack), and then
  // replaced by -0.0 where it does not act.
  const Vec3& f = *force;
  const Vec3& t = *chooseRow(asJ, torqueJ, torqueI);
  const std::uint64_t keep = std::uint64_t{ 0 } - static_cast<std::uint64_t>(live);
  const std::uint64_t sign = static_cast<std::uint64_t>(asJ) << 63;
  constexpr std::uint64_t negativeZero = std::uint64_t{ 1 } << 63;
  for (int c = 0; c < 3; ++c) {
    std::uint64_t fBits, tBits;
    std::memcpy(&fBits, &f[c], sizeof fBits);
    std::memcpy(&tBits, &t[c], sizeof tBits);
    fBits = ((fBits ^ sign) & keep) | (negativeZero & ~keep);
    tBits = (tBits & keep) | (negativeZero & ~keep);
    double fc, tc;
    std::memcpy(&fc, &fBits, sizeof fc);
    std::memcpy(&tc, &tBits, sizeof tc);
    sumForce[c] += fc;
    sumTorque[c] += tc;
  }
}

/// A pair's entry that acts (one cache line, dem::PairResult): i adds the force and
/// arm[0] (n x Ft), j minus the force and arm[1] (n x Ft); with rolling resistance
/// (`rolling` not null) the rolling torque is added to the product on i and subtracted on j
/// before the sum, as the pair law did: the same bits as the torques it stored before the
/// row held the arms.
[[gnu::always_inline]] inline void addPairEntry(bool asJ, const PairResult& row, const Vec3* rolling,
                                                Vec3& sumForce, Vec3& sumTorque)
{
  const double arm = row.arm[asJ ? 1 : 0]; // an indexed load: a branch was mispredicted
  Vec3 torque = arm * row.normalCrossFt;
  if (rolling != nullptr) {
    torque += withSignFlipped(*rolling, asJ);
  }
  sumForce += withSignFlipped(row.force, asJ);
  sumTorque += torque;
}

/// Pairs per block of the pair loop: the AVX2 path lists a block's touching pairs (on the
/// stack) and evaluates them at the block's end, while its arrays are still in cache.
constexpr long kPairBlock = 256;

/// Particles per chunk of the gather (the unit of its cost count and of its partition).
constexpr long kGatherChunk = 256;

/// Bonds per chunk of the bond loop (the unit of its timing and of its partition).
constexpr long kBondChunk = 512;

// The work of a block of pairs, counted as the loop runs, in rough relative units fitted to
// the two threads' times on the settled 100k pack (where the contacts sit in the lower
// slots): a pair's test 2 and a touching pair 9 more (with AVX2 about 40 and 160
// instructions). Only the ratios matter, and only for speed (balancedRanges).
constexpr std::uint32_t kPairCost = 2;
constexpr std::uint32_t kTouchingPairCost = 9;
// The work of a chunk of the gather is the time it took (ns) at its last evaluation,
// averaged with the one before so that one interrupted chunk does not swing the split. A
// count weighted by hand (a particle 4, an entry 3, a wall entry 4) left the two threads of
// a cemented specimen's gather 60 % apart (its platens' Hertz contacts, its bonds' memory
// traffic); timing the pair blocks as well gained nothing measurable. Timing decides only
// who computes what, never a bit of a result. Before a chunk has run: 50 ns per particle.
constexpr std::uint32_t kUnmeasuredParticleCost = 50;
// The bond loop's chunks are timed the same way: equal counts of bonds left the threads
// unequal work where the bonds of one half of a specimen have broken (a broken bond costs
// a byte's test). Before a chunk has run: 50 ns per bond.
constexpr std::uint32_t kUnmeasuredBondCost = 50;

/// An array of Vec3 (or of constants of three doubles) as plain doubles, for the AVX2
/// kernels, which include no Eigen.
template <class T> auto doubles(T* array)
{
  using Double = std::conditional_t<std::is_const_v<T>, const double, double>;
  static_assert(sizeof(std::remove_const_t<T>) % sizeof(double) == 0, "rows of doubles");
  return reinterpret_cast<Double*>(array);
}

/// The time since `start` (ns) averaged with the last cost, at least 1.
std::uint32_t measuredCost(std::chrono::steady_clock::time_point start, std::uint32_t last)
{
  const std::int64_t took =
    std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start).count();
  return static_cast<std::uint32_t>(std::clamp<std::int64_t>((took + last) / 2, 1, std::int64_t{ 1 } << 30));
}
} // namespace

void balancedRanges(const std::vector<std::uint32_t>& cost, int parts, std::vector<long>& bounds)
{
  const long chunks = static_cast<long>(cost.size());
  parts = std::max(parts, 1);
  bounds.assign(static_cast<std::size_t>(parts) + 1, chunks);
  bounds[0] = 0;
  std::uint64_t total = 0;
  for (const std::uint32_t c : cost) {
    total += c;
  }
  // Part p ends at the first chunk boundary where the running cost reaches p / parts of
  // the total (integers: the same ranges on every machine).
  std::uint64_t sum = 0;
  long c = 0;
  for (int part = 1; part < parts; ++part) {
    const std::uint64_t target = total * static_cast<std::uint64_t>(part) / static_cast<std::uint64_t>(parts);
    while (c < chunks && sum + cost[static_cast<std::size_t>(c)] / 2 < target) {
      sum += cost[static_cast<std::size_t>(c)];
      ++c;
    }
    bounds[static_cast<std::size_t>(part)] = c;
  }
}

ChunkClaims WorkSplit::split(long count, long chunk, std::uint32_t unmeasured, int parts)
{
  cost.resize(static_cast<std::size_t>((count + chunk - 1) / chunk), static_cast<std::uint32_t>(chunk) * unmeasured);
  balancedRanges(cost, parts, ranges);
  parts = std::max(parts, 1);
  if (cursorCount_ < parts) {
    cursors_ = std::make_unique<ChunkClaims::Cursor[]>(static_cast<std::size_t>(parts));
    cursorCount_ = parts;
  }
  for (int part = 0; part < parts; ++part) {
    cursors_[part].next.store(ranges[static_cast<std::size_t>(part)], std::memory_order_relaxed);
  }
  return ChunkClaims(cursors_.get(), ranges.data(), parts);
}

#if ROCKDEM_AVX2_KERNEL
bool touchingPairsAvx2Enabled()
{
  static const bool cpuHasAvx2 = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") != 0;
  }();
  const char* setting = std::getenv("ROCKDEM_CPU_SIMD");
  return cpuHasAvx2 && !(setting != nullptr && std::string(setting) == "0");
}
#else
bool touchingPairsAvx2Enabled() { return false; } // not an x86-64 build: the scalar loop
#endif

CpuBackend::CpuBackend(Model& model, const ContactModel& contactModel, double timestep)
  : model_(model)
  , contactModel_(contactModel)
  , timestep_(timestep)
  , simd_(touchingPairsAvx2Enabled())
{
  const SolverSettings& s = model.solver;
  ContactState& im = state_;
  const Particles& p = model.particles;
  const std::size_t n = p.size();
  im.inverseMass.resize(n);
  im.inverseInertia.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const bool fixed = (p.flags[i] & (FlagFixed | FlagAttachedLow | FlagAttachedHigh)) != 0;
    im.inverseMass[i] = fixed ? 0.0 : 1.0 / p.mass[i];
    im.inverseInertia[i] = fixed ? 0.0 : 1.0 / p.inertia[i];
  }
  im.undampedForce.assign(n, Vec3::Zero());
  im.touching.assign(n, 0);
  const double rmin = n ? *std::min_element(p.radius.begin(), p.radius.end()) : 0.0;
  im.skinDistance = s.skin * rmin;
  im.smallestRadius = rmin;
  im.threads = s.threads > 0 ? s.threads : availableThreads();
  decideParallel(); // on the particles alone for the first build

  // Import the stored contact history (by global ids) into the neighbour list.
  rebuildNeighbours(true);
  buildBondLists();
  decideParallel(); // with the pairs and bonds
  membraneSurface(model, &state_.externalForce); // the membrane's forces at these positions
  if (model.clock.step == 0) {
    // A model that has never stepped has no forces yet: compute them (no history
    // increment) so that the first half kick sees gravity and the initial contacts.
    computeForces(false, false);
  } else {
    // Resumed: the stored forces, torques, springs and wall reactions are those of the
    // last step and must stay bit for bit. Evaluate the contacts once for the
    // diagnostics only, keeping the stored state.
    evaluateKeepingStepState();
  }
}

namespace {
/// Calls f(array, its copy) for each array of the step state that an evaluation with no
/// time increment changes and the next step reads (the list, once, for the copy and the
/// restore): the net forces and torques, the wall reactions, the springs (the Coulomb limit
/// at the evaluated normal force) and which pairs hold state. Not the bonds (no
/// increment, no failure test) and not the positions and velocities.
template <class Copy, class F> void forEachStepStateArray(Model& m, ContactState& im, Copy& c, F f)
{
  f(m.particles.force, c.force);
  f(m.particles.torque, c.torque);
  f(m.walls, c.walls);
  f(im.pairSpring, c.pairSpring);
  f(im.pairRolling, c.pairRolling);
  f(im.pairLive, c.pairLive);
  f(im.wallSpring, c.wallSpring);
  f(im.wallRolling, c.wallRolling);
}

/// The same for the contacts' results that the evaluation rewrites whole (the pairs' rows
/// are copied for the pairs that act only: evaluateFresh).
template <class Copy, class F> void forEachResultArray(ContactState& im, Copy& c, F f)
{
  f(im.undampedForce, c.undampedForce);
  f(im.wallForce, c.wallForce);
  f(im.wallNormal, c.wallNormal);
  f(im.wallStiffness, c.wallStiffness);
  f(im.wallElastic, c.wallElastic);
  f(im.wallTouching, c.wallTouching);
}

constexpr auto copyInto = [](const auto& array, auto& copy) { copy = array; };
constexpr auto putBack = [](auto& array, auto& copy) { array.swap(copy); };
} // namespace

void CpuBackend::evaluateKeepingStepState()
{
  StepStateCopy copy;
  forEachStepStateArray(model_, state_, copy, copyInto);
  const bool drifted = drifted_;
  const bool driftedStale = driftedStale_;
  computeForces(false, false);
  forEachStepStateArray(model_, state_, copy, putBack);
  drifted_ = drifted;
  driftedStale_ = driftedStale;
}

bool CpuBackend::evaluateFresh(const std::function<void(const ContactState&)>& read)
{
  // Besides the step state, the evaluation rewrites the results of the contacts: those
  // of the pairs that acted at the last step are copied (a pair's row is read only while
  // it has a normal force), the wall entries' and the particles' undamped forces whole.
  ContactState& im = state_;
  ActingCopy a;
  const bool rolling = !im.pairRollingTorque.empty();
  for (std::size_t k = 0; k < im.pairNormal.size(); ++k) {
    if (im.pairNormal[k] != 0.0) {
      a.pair.push_back(static_cast<std::uint32_t>(k));
      a.row.push_back(im.pairResult[k]);
      a.pairNormal.push_back(im.pairNormal[k]);
      if (rolling) {
        a.rollingTorque.push_back(im.pairRollingTorque[k]);
      }
    }
  }
  forEachResultArray(im, a, copyInto);
  evaluateKeepingStepState();
  read(im);
  std::fill(im.pairNormal.begin(), im.pairNormal.end(), 0.0);
  for (std::size_t q = 0; q < a.pair.size(); ++q) {
    const std::uint32_t k = a.pair[q];
    im.pairResult[k] = a.row[q];
    im.pairNormal[k] = a.pairNormal[q];
    if (rolling) {
      im.pairRollingTorque[k] = a.rollingTorque[q];
    }
  }
  forEachResultArray(im, a, putBack);
  return true;
}

std::string CpuBackend::path() const
{
  if (state_.parallel) {
    return "CPU OpenMP (" + std::to_string(state_.threads) + " threads)";
  }
  // Serial: say why, since Threads may have asked for more.
  const SolverSettings& s = model_.solver;
  if (state_.work < static_cast<double>(s.parallelThreshold)) {
    // Kept short: the DEM Test dock shows it (particles + 5 pairs + 6 bonds, decideParallel).
    return "CPU serial (work " + std::to_string(std::llround(state_.work)) +
      ", below the parallel threshold of " + std::to_string(s.parallelThreshold) +
      (s.threads == 1 ? ")" : "; threads are used from there on)");
  }
  return s.threads == 1 ? std::string("CPU serial (Threads = 1)")
                        : std::string("CPU serial (OpenMP offers 1 thread)");
}

void CpuBackend::run(std::int64_t steps)
{
  // Within one run(), each step's gather also does the next step's opening half kick and
  // drift of each chunk of particles right after gathering it (the same operations on the
  // same values: a particle's kick and drift read only its own state, which its gather has
  // just finished; the thread that gathered a chunk moves it while it is in that thread's
  // cache, and one pass and one fork/join per step are saved). The last step of a run does
  // not, so between runs the state is that of whole steps.
  for (std::int64_t s = 0; s < steps; ++s) {
    step(s + 1 == steps);
  }
}

void CpuBackend::countDissipation(bool on)
{
  countDissipation_ = on;
  if (on) {
    state_.dampingWork.assign(model_.particles.size(), 0.0);
    state_.breakEnergy.assign(model_.bonds.size(), 0.0);
  }
}

StabilityReport CpuBackend::stability()
{
  const Particles& p = model_.particles;
  StabilityReport r;
  for (std::size_t w = 0; w < model_.walls.size() && w < 6; ++w) {
    r.wallPosition[w] = model_.walls[w].position;
    r.wallForce[w] = model_.walls[w].force[model_.walls[w].axis];
  }
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.position[i].allFinite() || !p.velocity[i].allFinite() ||
        !p.angularVelocity[i].allFinite()) {
      r.firstNonFinite = static_cast<long>(i);
      return r;
    }
  }
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (beyondActiveWalls(model_.walls, p.position[i]) && r.escaped++ == 0) {
      r.firstEscaped = static_cast<long>(i);
    }
  }
  if (r.escaped > 0) {
    return r;
  }
  for (std::size_t i = 0; i < p.size(); ++i) {
    r.kineticEnergy += 0.5 * p.mass[i] * p.velocity[i].squaredNorm() +
      0.5 * p.inertia[i] * p.angularVelocity[i].squaredNorm();
  }
  return r;
}

// ---------------------------------------------------------------------------------------
// Neighbour list

void CpuBackend::rebuildNeighbours(bool importModelHistory)
{
  ContactState& im = state_;
  const Particles& p = model_.particles;
  const Domain& d = model_.domain;
  const std::size_t n = p.size();
  const bool rolling = contactModel_.rollingFriction > 0.0;

  // Keep the old list's history to carry it over (both lists are sorted by (i, j)).
  std::vector<std::uint32_t> oldI, oldJ;
  std::vector<Vec3> oldSpring, oldRolling;
  oldI.swap(im.pairI);
  oldJ.swap(im.pairJ);
  oldSpring.swap(im.pairSpring);
  oldRolling.swap(im.pairRolling);

  if (n > 0) {
    const auto [rmin, rmax] = std::minmax_element(p.radius.begin(), p.radius.end());
    SizeClassGrids grids(d, *rmin, *rmax);
    grids.insertAll(p);
    // The queries run in parallel over fixed blocks of slots; each block's pairs are
    // appended in block order, so the list, sorted by (i, j), does not depend on the
    // number of threads.
    const std::size_t blocks = im.parallel ? 8 * static_cast<std::size_t>(im.threads) : 1;
    std::vector<std::vector<std::uint32_t>> blockI(blocks), blockJ(blocks);
    const long blockCount = static_cast<long>(blocks);
#pragma omp parallel for schedule(dynamic, 1) num_threads(im.threads) if (im.parallel)
    for (long b = 0; b < blockCount; ++b) {
      std::vector<std::size_t> keys;
      const std::size_t first = n * static_cast<std::size_t>(b) / blocks;
      const std::size_t last = n * static_cast<std::size_t>(b + 1) / blocks;
      for (std::size_t i = first; i < last; ++i) {
        grids.neighboursWithin(p.position[i], p.radius[i], im.skinDistance, i, keys);
        std::sort(keys.begin(), keys.end());
        for (std::size_t j : keys) {
          if (j > i) {
            blockI[b].push_back(static_cast<std::uint32_t>(i));
            blockJ[b].push_back(static_cast<std::uint32_t>(j));
          }
        }
      }
    }
    for (std::size_t b = 0; b < blocks; ++b) {
      im.pairI.insert(im.pairI.end(), blockI[b].begin(), blockI[b].end());
      im.pairJ.insert(im.pairJ.end(), blockJ[b].begin(), blockJ[b].end());
    }
  }
  const std::size_t pairs = im.pairI.size();
  // The contact law's constants of each pair (they depend on radii and masses only).
  const double infinite = std::numeric_limits<double>::infinity();
  auto massOf = [&](std::size_t i) { return im.inverseMass[i] > 0.0 ? p.mass[i] : infinite; };
  const bool planar = d.section2D;
  const double slab = d.slabThickness();
  im.pairConstants.resize(pairs);
  const long pairCount = static_cast<long>(pairs);
#pragma omp parallel for schedule(static) num_threads(im.threads) if (im.parallel)
  for (long k = 0; k < pairCount; ++k) {
    const std::uint32_t i = im.pairI[k];
    const std::uint32_t j = im.pairJ[k];
    im.pairConstants[k] = contactConstants(contactModel_,
      pairProperties(contactModel_, p.radius[i], massOf(i), p.radius[j], massOf(j), planar, slab));
  }
  im.pairSpring.assign(pairs, Vec3::Zero());
  im.pairRolling.assign(rolling ? pairs : 0, Vec3::Zero());
  im.pairResult.assign(pairs, PairResult{});
  im.pairRollingTorque.assign(rolling ? pairs : 0, Vec3::Zero());
  im.pairNormal.assign(pairs, 0.0);
  im.pairLive.assign(pairs, 1); // the first evaluation clears the flag where there is no state
  im.positionAtBuild = p.position;
  rebuildWallContacts(!importModelHistory);

  if (importModelHistory) {
    // Stored history is keyed by global ids: map ids to slots, then find each pair.
    const SlotLookup slots(p);
    auto findSlot = [&](std::int64_t id) { return slots.find(id); };
    const ContactHistory& h = model_.contacts;
    for (std::size_t c = 0; c < h.size(); ++c) {
      const long a = findSlot(h.idA[c]);
      if (a < 0) {
        continue;
      }
      if (h.idB[c] < 0) {
        // A wall contact: its entry, if the particle is near that wall. One that is not
        // cannot touch before the list is next rebuilt, and its history would be
        // cleared at the first step anyway.
        const std::size_t w = static_cast<std::size_t>(-h.idB[c] - 1);
        for (std::size_t e = im.wallStart[a]; e < im.wallStart[a + 1]; ++e) {
          if (im.wallIndex[e] == w) {
            im.wallSpring[e] = h.shearSpring[c];
            im.wallTouching[e] = 1; // cleared at the next evaluation if it no longer touches
            if (rolling && c < h.rollingSpring.size()) {
              im.wallRolling[e] = h.rollingSpring[c];
            }
          }
        }
        continue;
      }
      const long b = findSlot(h.idB[c]);
      if (b < 0) {
        continue;
      }
      // The stored spring is A's displacement relative to B; the list orders by slot.
      const std::uint32_t i = static_cast<std::uint32_t>(std::min(a, b));
      const std::uint32_t j = static_cast<std::uint32_t>(std::max(a, b));
      const double orientation = (a == static_cast<long>(i)) ? 1.0 : -1.0;
      std::size_t lo = std::lower_bound(im.pairI.begin(), im.pairI.end(), i) - im.pairI.begin();
      for (std::size_t k = lo; k < pairs && im.pairI[k] == i; ++k) {
        if (im.pairJ[k] == j) {
          im.pairSpring[k] = orientation * h.shearSpring[c];
          if (rolling && c < h.rollingSpring.size()) {
            im.pairRolling[k] = orientation * h.rollingSpring[c];
          }
          break;
        }
      }
    }
  } else {
    // Merge-join with the previous list to carry the history over.
    std::size_t k = 0;
    for (std::size_t o = 0; o < oldI.size(); ++o) {
      while (k < pairs && (im.pairI[k] < oldI[o] || (im.pairI[k] == oldI[o] && im.pairJ[k] < oldJ[o]))) {
        ++k;
      }
      if (k < pairs && im.pairI[k] == oldI[o] && im.pairJ[k] == oldJ[o]) {
        im.pairSpring[k] = oldSpring[o];
        if (rolling) {
          im.pairRolling[k] = oldRolling[o];
        }
      }
    }
  }

  if (2 * pairs > std::numeric_limits<std::uint32_t>::max()) {
    throw InputError("The neighbour list has " + std::to_string(pairs) +
                     " pairs; the solver's gather lists hold at most 2^31.");
  }
  // Gather lists: each particle's pairs in order of partner slot (a fixed order).
  im.adjacencyStart.assign(n + 1, 0);
  for (std::size_t k = 0; k < pairs; ++k) {
    ++im.adjacencyStart[im.pairI[k] + 1];
    ++im.adjacencyStart[im.pairJ[k] + 1];
  }
  std::partial_sum(im.adjacencyStart.begin(), im.adjacencyStart.end(), im.adjacencyStart.begin());
  im.adjacency.assign(2 * pairs, 0);
  std::vector<std::uint32_t> fill(im.adjacencyStart.begin(), im.adjacencyStart.end() - 1);
  // Pairs are sorted by (i, j): visiting them in order appends, for each particle, the
  // partners below it (as j) in increasing i, then the partners above it (as i) in
  // increasing j. Both runs are sorted, and the first precedes the second.
  for (std::size_t k = 0; k < pairs; ++k) {
    im.adjacency[fill[im.pairJ[k]]++] = static_cast<std::uint32_t>(2 * k + 1);
  }
  for (std::size_t k = 0; k < pairs; ++k) {
    im.adjacency[fill[im.pairI[k]]++] = static_cast<std::uint32_t>(2 * k);
  }
  decideParallel(); // for the steps on this list
}

void CpuBackend::rebuildWallContacts(bool carryHistory)
{
  ContactState& im = state_;
  const Particles& p = model_.particles;
  const Domain& d = model_.domain;
  const std::size_t n = p.size();
  const bool rolling = contactModel_.rollingFriction > 0.0;
  const double infinite = std::numeric_limits<double>::infinity();

  std::vector<std::uint32_t> oldSlot, oldStart;
  std::vector<std::uint8_t> oldIndex, oldTouching;
  std::vector<Vec3> oldSpring, oldRolling;
  if (carryHistory) {
    oldSlot.swap(im.wallSlot);
    oldStart.swap(im.wallStart);
    oldIndex.swap(im.wallIndex);
    oldTouching.swap(im.wallTouching);
    oldSpring.swap(im.wallSpring);
    oldRolling.swap(im.wallRolling);
  }
  im.wallSlot.clear();
  im.wallIndex.clear();
  im.wallStart.assign(n + 1, 0);
  // A particle is a candidate for a wall when its gap was below the skin at the build.
  // Until the next build, the particle moves by at most half the skin (from
  // positionAtBuild) and the wall by at most half the skin: together, never more than
  // the gap, so no contact is missed.
  for (std::size_t i = 0; i < n; ++i) {
    im.wallStart[i] = static_cast<std::uint32_t>(im.wallSlot.size());
    for (int w = 0; w < 6; ++w) {
      const Wall& wall = model_.walls[w];
      const double side = wall.side == 0 ? 1.0 : -1.0;
      const double gap = (im.positionAtBuild[i][wall.axis] - wall.position) * side - p.radius[i];
      if (wall.active && gap < im.skinDistance) {
        im.wallSlot.push_back(static_cast<std::uint32_t>(i));
        im.wallIndex.push_back(static_cast<std::uint8_t>(w));
      }
    }
  }
  const std::size_t entries = im.wallSlot.size();
  im.wallStart[n] = static_cast<std::uint32_t>(entries);
  for (int w = 0; w < 6; ++w) {
    im.wallPositionAtBuild[w] = model_.walls[w].position;
    im.wallActiveAtBuild[w] = model_.walls[w].active;
  }
  im.wallConstants.resize(entries);
  for (std::size_t e = 0; e < entries; ++e) {
    const std::uint32_t i = im.wallSlot[e];
    const double mass = im.inverseMass[i] > 0.0 ? p.mass[i] : infinite;
    im.wallConstants[e] = contactConstants(contactModel_,
      wallProperties(contactModel_, p.radius[i], mass, d.section2D, d.slabThickness()));
  }
  im.wallTouching.assign(entries, 0);
  im.wallSpring.assign(entries, Vec3::Zero());
  im.wallRolling.assign(rolling ? entries : 0, Vec3::Zero());
  im.wallForce.assign(entries, Vec3::Zero());
  im.wallNormal.assign(entries, 0.0);
  im.wallStiffness.assign(entries, 0.0);
  im.wallElastic.assign(entries, 0.0);
  if (!carryHistory) {
    return;
  }
  // Carry the history over: both lists are sorted by (slot, wall). A contact touching now
  // is in the new list (its gap is negative).
  std::size_t e = 0;
  for (std::size_t o = 0; o < oldSlot.size(); ++o) {
    if (!oldTouching[o] && oldSpring[o].isZero(0.0) && !(rolling && !oldRolling[o].isZero(0.0))) {
      continue;
    }
    while (e < entries && (im.wallSlot[e] < oldSlot[o] ||
                           (im.wallSlot[e] == oldSlot[o] && im.wallIndex[e] < oldIndex[o]))) {
      ++e;
    }
    if (e < entries && im.wallSlot[e] == oldSlot[o] && im.wallIndex[e] == oldIndex[o]) {
      im.wallTouching[e] = oldTouching[o];
      im.wallSpring[e] = oldSpring[o];
      if (rolling) {
        im.wallRolling[e] = oldRolling[o];
      }
    }
  }
}

// The work of one step in particle-equivalents: each particle (drift, gather, walls,
// damping, kicks) counts 1, each neighbour pair kPairWork and each bond kBondWork. These
// are not the serial costs alone (a contact costs about 1.7 loose particles): they also
// carry the larger parallel overhead of a loose pack (memory-bound passes, little work per
// fork/join), so that with the default SolverSettings::parallelThreshold one rule separates
// the packs where two threads won from those where they lost, loose, dense and cemented
// (Documentation/Benchmarks-Solver.md section 1, "Serial or parallel").
constexpr double kPairWork = 5.0;
constexpr double kBondWork = 6.0;

void CpuBackend::decideParallel()
{
  ContactState& im = state_;
  im.work = static_cast<double>(model_.particles.size()) +
    kPairWork * static_cast<double>(im.pairI.size()) + kBondWork * static_cast<double>(im.bondI.size());
  // Which loop runs on which thread never changes a bit of the result (fixed partition
  // of the writes, fixed summation order), so the switch may change at any build.
  im.parallel = im.threads > 1 && im.work >= static_cast<double>(model_.solver.parallelThreshold);
}

bool CpuBackend::wallsMoved() const
{
  const ContactState& im = state_;
  const double limit = 0.5 * im.skinDistance;
  for (int w = 0; w < 6; ++w) {
    const Wall& wall = model_.walls[w];
    if (wall.active != im.wallActiveAtBuild[w] ||
        (wall.active && !(std::abs(wall.position - im.wallPositionAtBuild[w]) <= limit))) {
      return true;
    }
  }
  return false;
}

// ---------------------------------------------------------------------------------------
// Forces

void CpuBackend::computeForces(bool incrementHistory, bool closingKick, bool driftNext)
{
  ContactState& im = state_;
  Particles& p = model_.particles;
  const Domain& d = model_.domain;
  const ContactModel& cm = contactModel_;
  const bool planar = d.section2D;
  const double slab = d.slabThickness();
  const double dt = incrementHistory ? timestep_ : 0.0;
  const double predict = 0.5 * dt; // s, half kick from the half-step to the full-step velocity
  const bool rolling = cm.rollingFriction > 0.0;
  const std::size_t n = p.size();
  const long pairs = static_cast<long>(im.pairI.size());
  const double infinite = std::numeric_limits<double>::infinity();
  auto massOf = [&](std::size_t i) { return im.inverseMass[i] > 0.0 ? p.mass[i] : infinite; };

  const MinimumImage separationOf(d);

  // 1. Each pair once. The hot loops read the arrays through raw pointers: through the
  // vectors' operator[], the arrays' addresses were reloaded after every store.
  const Vec3* const position = p.position.data();
  const Vec3* const velocity = p.velocity.data();
  const Vec3* const spin = p.angularVelocity.data();
  const Vec3* const lastForce = p.force.data();
  const double* const radius = p.radius.data();
  const double* const inverseMass = im.inverseMass.data();
  const std::uint32_t* const pairI = im.pairI.data();
  const std::uint32_t* const pairJ = im.pairJ.data();
  const ContactConstants* const pairConstants = im.pairConstants.data();
  Vec3* const pairSpring = im.pairSpring.data();
  Vec3* const pairRolling = im.pairRolling.data();
  PairResult* const pairResult = im.pairResult.data();
  Vec3* const pairRollingTorque = im.pairRollingTorque.data();
  double* const pairNormal = im.pairNormal.data();
  std::uint8_t* const pairLive = im.pairLive.data();
  std::uint8_t* const touching = im.touching.data();
  // In blocks of kPairBlock pairs. With AVX2 (and no rolling resistance, no periodic axis)
  // a block's pairs are tested four at a time and its touching pairs evaluated four at a
  // time; otherwise one by one. Both run the same test and dem::touchingPairForce, with
  // the same bits.
  const bool hertz = cm.law == ContactLaw::HertzMindlin;
  [[maybe_unused]] const bool simd = simd_ && !rolling && separationOf.plain();
  static_assert(sizeof(Vec3) == 3 * sizeof(double) && sizeof(ContactConstants) == 3 * sizeof(double) &&
                  sizeof(PairResult) == 8 * sizeof(double) && offsetof(PairResult, normalCrossFt) == 24 &&
                  offsetof(PairResult, arm) == 48,
                "the AVX2 kernel reads and writes these arrays as plain doubles");
  [[maybe_unused]] const TouchingPairArrays arrays{ doubles(position), doubles(velocity), doubles(spin),
    doubles(lastForce), radius, inverseMass, pairI, pairJ, doubles(pairConstants),
    doubles(pairSpring), reinterpret_cast<double*>(pairResult),
    pairNormal, pairLive, touching, hertz, cm.friction, dt, predict };
  // A pair that does not touch (any longer): clear its force and history once, where it
  // may hold some (pairLive 1); a pair without state has nothing to clear: one byte read
  // instead of its normal force and springs. (Captured by value: a reference to the
  // pointers would make the parallel loops read every array's address through memory.)
  auto endContact = [=](std::size_t k) {
    if (pairNormal[k] != 0.0 || !pairSpring[k].isZero(0.0) ||
        (rolling && !pairRolling[k].isZero(0.0))) {
      pairResult[k] = PairResult{};
      pairNormal[k] = 0.0;
      pairSpring[k].setZero();
      if (rolling) {
        pairRolling[k].setZero();
        pairRollingTorque[k].setZero();
      }
    }
    pairLive[k] = 0;
  };
  // Each thread starts with one contiguous range of blocks, of about equal work as the blocks'
  // work at the last step weighs it (a block new since a rebuild counts its pairs as not
  // touching): equal shares of the pairs gave the thread holding the contact-rich part of
  // a pack most of the work (WorkSplit). A thread done with its range takes the blocks
  // still unclaimed in the others' (ChunkClaims).
  const int parts = im.parallel ? im.threads : 1;
  const ChunkClaims pairClaims = pairSplit_.split(pairs, kPairBlock, kPairCost, parts);
  std::uint32_t* const blockCost = pairSplit_.cost.data();
  // The loops capture by value (the arrays' addresses, the constants) and the two large
  // objects they use by reference (WorkerTeam::run).
  team_.run(parts, [=, &im, &p](int part) __attribute__((always_inline)) {
  int visit = 0;
  for (long b; (b = pairClaims.claim(part, visit)) >= 0;) {
    const long blockEnd = std::min(pairs, (b + 1) * kPairBlock);
#if ROCKDEM_AVX2_KERNEL
    if (simd) {
      // The block's pairs tested four at a time; those that touch evaluated four at a time.
      std::uint32_t list[kPairBlock + kScanSlack], ended[kPairBlock + kScanSlack];
      std::size_t endedCount = 0;
      const std::size_t listed = scanPairsAvx2(arrays, static_cast<std::size_t>(b * kPairBlock),
                                               static_cast<std::size_t>(blockEnd), list, ended, endedCount);
      for (std::size_t e = 0; e < endedCount; ++e) {
        endContact(ended[e]);
      }
      touchingPairsAvx2(arrays, list, listed);
      blockCost[b] = static_cast<std::uint32_t>((blockEnd - b * kPairBlock) * kPairCost + listed * kTouchingPairCost);
      continue;
    }
#endif
    std::uint32_t evaluated = 0;
    for (long k = b * kPairBlock; k < blockEnd; ++k) {
      const std::uint32_t i = pairI[k];
      const std::uint32_t j = pairJ[k];
      const Vec3 branch = separationOf(position[i], position[j]); // from i to j
      const double reach = radius[i] + radius[j];
      const double distance2 = branch.squaredNorm();
      // Most neighbour pairs of a settled pack do not touch (88 % at 100k): those far
      // enough apart are rejected on the squared distance, before the square root (bit for
      // bit: see kApart). The others take the distance and the overlap as before.
      const bool apart = distance2 > kApart * (reach * reach);
      const double distance = apart ? 0.0 : std::sqrt(distance2); // = branch.norm()
      const double overlap = reach - distance;
      if (apart || overlap <= 0.0 || distance == 0.0) {
        if (pairLive[k]) {
          endContact(static_cast<std::size_t>(k));
        }
        continue;
      }
      const ContactConstants& c = pairConstants[k];
      const TouchingPairInput<Vec3> in{ branch, distance, overlap, radius[i], radius[j],
        velocity[i], velocity[j], spin[i], spin[j], lastForce[i], lastForce[j],
        inverseMass[i], inverseMass[j], c.normalStiffness, c.normalDamping, c.tangentialStiffness };
      const TouchingPairResult<Vec3> r =
        touchingPairForce(in, hertz, cm.friction, dt, predict, pairSpring[k]);
      ++evaluated;
      const double fn = r.normalForce;
      if (rolling) {
        const Vec3& normal = r.normal;
        const PairProperties pair =
          pairProperties(cm, radius[i], massOf(i), radius[j], massOf(j), planar, slab);
        const Vec3 roll = inPlane(spin[i] - spin[j], normal) * dt;
        pairRollingTorque[k] = rollingTorque(cm, pair, overlap, fn, normal, roll, pairRolling[k]);
      }
      PairResult& row = pairResult[k];
      row.force = r.force;
      row.normalCrossFt = r.normalCrossFt;
      row.arm[0] = r.armI;
      row.arm[1] = r.armJ;
      pairNormal[k] = fn;
      pairLive[k] = 1;
      if (fn != 0.0) {
        // Two threads may mark the same particle: both write 1.
        __atomic_store_n(&touching[i], std::uint8_t{ 1 }, __ATOMIC_RELAXED);
        __atomic_store_n(&touching[j], std::uint8_t{ 1 }, __ATOMIC_RELAXED);
      }
    }
    blockCost[b] = static_cast<std::uint32_t>((blockEnd - b * kPairBlock) * kPairCost + evaluated * kTouchingPairCost);
  }
  });

  // 2. Bonds, each once (state updated and failure checked only on a real step).
  computeBondForces(incrementHistory);

  // 3. Walls. During a press test the side walls are frictionless (a servo-controlled
  // face must be free to follow the specimen's lateral expansion without shear from it)
  // and the two platens (the walls on the test axis) have the test's Platen Friction.
  // Evaluated in the gather below, by the particle's own thread: wall entry e of
  // particle i adds its force and torque.
  ContactModel wallModel = cm;
  const bool pressTest = model_.test.settings.mode != TestMode::Off;
  if (pressTest) {
    wallModel.friction = 0.0;
    wallModel.rollingFriction = 0.0;
  }
  const bool wallRolling = wallModel.rollingFriction > 0.0;
  auto wallContact = [&](std::size_t e, std::size_t i, Vec3& force, Vec3& torque) __attribute__((always_inline)) {
    const Wall& wall = model_.walls[im.wallIndex[e]];
    const double side = wall.side == 0 ? 1.0 : -1.0;
    const double distance = (p.position[i][wall.axis] - wall.position) * side;
    const double overlap = wall.active ? p.radius[i] - distance : 0.0;
    if (overlap <= 0.0) {
      if (im.wallTouching[e] || !im.wallSpring[e].isZero(0.0)) {
        // The contact just ended: clear its force and history once.
        im.wallTouching[e] = 0;
        im.wallForce[e].setZero();
        im.wallNormal[e] = 0.0;
        im.wallStiffness[e] = 0.0;
        im.wallElastic[e] = 0.0;
        im.wallSpring[e].setZero();
        if (rolling) {
          im.wallRolling[e].setZero();
        }
      }
      return;
    }
    const Vec3 normal = -wall.normal(); // from the centre towards the wall
    const double arm = p.radius[i] - overlap;
    Vec3 wallVelocity = Vec3::Zero();
    wallVelocity[wall.axis] = wall.velocity;
    const Vec3 relativeVelocity =
      p.velocity[i] - wallVelocity + p.angularVelocity[i].cross(arm * normal);
    const double approachSpeed =
      (relativeVelocity + predict * im.inverseMass[i] * p.force[i]).dot(normal);
    const NormalResponse response =
      normalResponse(cm.law, im.wallConstants[e], overlap, approachSpeed);
    const double fn = response.force;
    const Vec3 slip = inPlane(relativeVelocity, normal) * dt;
    const double mu = pressTest && wall.axis == model_.test.settings.axis
      ? model_.test.settings.platenFriction : wallModel.friction;
    const Vec3 ft = mindlinCoulombForce(response.tangentialStiffness, mu, fn, normal, slip,
                                        im.wallSpring[e]);
    Vec3 contactTorque = arm * normal.cross(ft);
    if (wallRolling) {
      const PairProperties pair = wallProperties(wallModel, p.radius[i], massOf(i), planar, slab);
      const Vec3 roll = inPlane(p.angularVelocity[i], normal) * dt;
      contactTorque += rollingTorque(wallModel, pair, overlap, fn, normal, roll, im.wallRolling[e]);
    } else if (rolling) {
      im.wallRolling[e].setZero(); // rolling resistance off against frictionless walls
    }
    im.wallTouching[e] = 1;
    im.wallForce[e] = -fn * normal + ft;
    im.wallNormal[e] = fn;
    im.wallStiffness[e] = response.stiffness;
    im.wallElastic[e] = response.elasticForce; // no viscous part
    force += im.wallForce[e];
    torque += contactTorque;
  };

  // 4. Gather per particle in a fixed order (pairs by partner slot, then walls, then
  // bonds); Cundall damping on the unbalanced force; on a real step, the closing half
  // kick of the velocity Verlet step.
  const double alpha = localDamping(model_.test, model_.solver.settlingDamping);
  const Vec3 gravity = model_.gravity;
  const double half = 0.5 * timestep_;
  const long count = static_cast<long>(n);
  const bool anyBonds = !im.bondI.empty();
  const bool anyExternal = im.externalForce.size() == n; // the membrane's pushes
  const double* const mass = p.mass.data();
  const std::uint32_t* const adjacencyStart = im.adjacencyStart.data();
  const std::uint32_t* const adjacency = im.adjacency.data();
  const std::size_t* const bondAdjacencyStart = im.bondAdjacencyStart.data();
  const std::size_t* const bondAdjacency = im.bondAdjacency.data();
  const Vec3* const bondForce = im.bondForce.data();
  const Vec3* const bondTorqueI = im.bondTorqueI.data();
  const Vec3* const bondTorqueJ = im.bondTorqueJ.data();
  const std::uint8_t* const bondFailure = model_.bonds.failure.data();
  const std::uint8_t intact = static_cast<std::uint8_t>(BondFailure::Intact);
  // Each thread starts with one contiguous range of chunks of about equal work, as the pair loop
  // takes its blocks (and, with driftNext, moves the particles it gathered).
  const ChunkClaims gatherClaims = gatherSplit_.split(count, kGatherChunk, kUnmeasuredParticleCost, parts);
  std::uint32_t* const chunkCost = gatherSplit_.cost.data();
  // The particle arrays the gather writes, through raw pointers (as in the pair loop).
  Vec3* const movePosition = p.position.data();
  Vec3* const moveVelocity = p.velocity.data();
  Vec3* const moveSpin = p.angularVelocity.data();
  Vec3* const moveDisplacement = p.displacement.data();
  Vec3* const netForce = p.force.data();
  Vec3* const netTorque = p.torque.data();
  Vec3* const undampedForce = im.undampedForce.data();
  const Vec3* const externalForce = im.externalForce.data();
  const std::uint32_t* const wallStart = im.wallStart.data();
  const Vec3* const positionAtBuild = im.positionAtBuild.data();
  const double* const inverseInertia = im.inverseInertia.data();
  const double stepDt = timestep_;
  // On a real step while counting dissipation: each particle's Cundall damping work.
  double* const dampingWork = countDissipation_ && closingKick ? im.dampingWork.data() : nullptr;
  // With driftNext, the next step's kick and drift (step(), run()).
  bool stale = false; // the drift made the neighbour list stale
  const bool anyPeriodic = d.periodic[0] || d.periodic[1] || d.periodic[2];
  const double skinLimit = 0.5 * im.skinDistance; // m, drift that makes the neighbour list stale
  const double limit2 = skinLimit * skinLimit;
  staleByRank_.assign(static_cast<std::size_t>(parts), 0);
  std::uint8_t* const staleByRank = staleByRank_.data();
  if (gatherScratch_.size() < static_cast<std::size_t>(parts)) {
    gatherScratch_.resize(static_cast<std::size_t>(parts));
  }
  GatherScratch* const gatherScratch = gatherScratch_.data();
  team_.run(parts, [=, &im, &p](int part) __attribute__((always_inline)) {
  bool rankStale = false; // this rank's drift made the list stale
  int visit = 0;
  for (long chunk; (chunk = gatherClaims.claim(part, visit)) >= 0;) {
    const long chunkBegin = chunk * kGatherChunk;
    const long chunkEnd = std::min(count, chunkBegin + kGatherChunk);
    const std::chrono::steady_clock::time_point chunkStart = std::chrono::steady_clock::now();
    // The chunk's pair entries that act (actingEntry), each with its particle's slot in the
    // chunk (actingOwner), in the gather's order. A pair without normal force (not touching,
    // or no force) adds nothing, and most pairs of a pack do not touch (88 % of a settled
    // pack's): the entries are sorted out first, one independent load of a normal force
    // each and no branch on each, and then only the rows of those that act are read
    // (skipping an entry gives the bits of adding -0.0 for it: x + -0.0 is x). A particle
    // without a touching pair skips its list. The sums start from the weight, as before.
    GatherScratch& scratch = gatherScratch[part];
    const std::size_t chunkEntries = adjacencyStart[chunkEnd] - adjacencyStart[chunkBegin];
    if (scratch.entry.size() < chunkEntries) {
      scratch.entry.resize(chunkEntries);
      scratch.owner.resize(chunkEntries);
    }
    if (scratch.force.empty()) {
      scratch.force.resize(kGatherChunk);
      scratch.torque.resize(kGatherChunk);
    }
    std::uint32_t* const actingEntry = scratch.entry.data();
    std::uint32_t* const actingOwner = scratch.owner.data();
    Vec3* const chunkForce = scratch.force.data();
    Vec3* const chunkTorque = scratch.torque.data();
    std::uint32_t acting = 0;
    for (long li = chunkBegin; li < chunkEnd; ++li) {
      const std::size_t i = static_cast<std::size_t>(li);
      chunkForce[li - chunkBegin] = mass[i] * gravity;
      chunkTorque[li - chunkBegin].setZero();
      const std::uint32_t pairEnd = touching[i] ? adjacencyStart[i + 1] : adjacencyStart[i];
      touching[i] = 0;
      for (std::uint32_t e = adjacencyStart[i]; e < pairEnd; ++e) {
        const std::uint32_t entry = adjacency[e];
        actingEntry[acting] = entry;
        actingOwner[acting] = static_cast<std::uint32_t>(li - chunkBegin);
        acting += pairNormal[entry >> 1] != 0.0 ? 1u : 0u;
      }
    }
    // One loop over the chunk's acting entries (a loop per particle ended in a mispredicted
    // branch per particle), each added to its particle's sums in the list's order.
    for (std::uint32_t a = 0; a < acting; ++a) {
      const std::uint32_t k = actingEntry[a] >> 1;
      addPairEntry((actingEntry[a] & 1u) != 0, pairResult[k], rolling ? pairRollingTorque + k : nullptr,
                   chunkForce[actingOwner[a]], chunkTorque[actingOwner[a]]);
    }
    for (long li = chunkBegin; li < chunkEnd; ++li) {
      const std::size_t i = static_cast<std::size_t>(li);
      Vec3 force = chunkForce[li - chunkBegin];
      Vec3 torque = chunkTorque[li - chunkBegin];
      for (std::size_t e = wallStart[i]; e < wallStart[i + 1]; ++e) {
        wallContact(e, i, force, torque);
      }
      if (anyBonds) {
        // A broken bond adds nothing (without a branch, as the pairs: bonds break at random).
        for (std::size_t e = bondAdjacencyStart[i]; e < bondAdjacencyStart[i + 1]; ++e) {
          const std::size_t b = bondAdjacency[e] >> 1;
          addEntry(bondFailure[b] == intact, (bondAdjacency[e] & 1u) != 0, bondForce + b, bondTorqueI + b,
                   bondTorqueJ + b, force, torque);
        }
      }
      if (anyExternal) {
        force += externalForce[i];
      }
      if (planar) {
        force.z() = 0.0;
        torque.x() = 0.0;
        torque.y() = 0.0;
      }
      undampedForce[i] = force;
      Vec3 damped = force;
      Vec3 dampedTorque = torque;
      if (alpha > 0.0) {
        for (int c = 0; c < 3; ++c) {
          damped[c] = cundallDamping(force[c], moveVelocity[i][c], alpha);
          dampedTorque[c] = cundallDamping(torque[c], moveSpin[i][c], alpha);
        }
      }
      netForce[i] = damped;
      netTorque[i] = dampedTorque;
      if (dampingWork != nullptr && alpha > 0.0) {
        dampingWork[i] += cundallDampingWork(force, damped, moveVelocity[i], torque, dampedTorque, moveSpin[i], stepDt);
      }
      if (closingKick && inverseMass[i] != 0.0) {
        moveVelocity[i] += (half * inverseMass[i]) * damped;
        moveSpin[i] += (half * inverseInertia[i]) * dampedTorque;
        if (planar) {
          moveVelocity[i].z() = 0.0;
          moveSpin[i].x() = 0.0;
          moveSpin[i].y() = 0.0;
        }
      }
    }
    if (driftNext) {
      // The chunk's kick and drift, while it is in this thread's cache (a loop of its own:
      // inside the gather's it took 13 % more instructions, for want of registers).
      for (long li = chunkBegin; li < chunkEnd; ++li) {
        if (kickAndDrift(static_cast<std::size_t>(li), movePosition, moveVelocity, moveSpin, moveDisplacement,
                         netForce, netTorque, positionAtBuild, inverseMass, inverseInertia, stepDt, half, planar,
                         anyPeriodic, d, separationOf, limit2)) {
          rankStale = true;
        }
      }
    }
    chunkCost[chunk] = measuredCost(chunkStart, chunkCost[chunk]);
  }
  staleByRank[part] = rankStale ? 1 : 0;
  });
  for (int part = 0; part < parts; ++part) {
    stale = stale || staleByRank[part] != 0;
  }
  drifted_ = driftNext;
  driftedStale_ = driftNext && stale;

  // 5. Wall reactions: one pass over the wall entries in (slot, wall) order, so each
  // wall's sum runs in slot order (deterministic).
  std::array<Vec3, 6> reaction;
  reaction.fill(Vec3::Zero());
  std::array<double, 6> stiffness{};
  std::array<double, 6> elastic{};
  std::array<std::int64_t, 6> contacts{};
  for (std::size_t e = 0; e < im.wallSlot.size(); ++e) {
    if (im.wallTouching[e]) {
      const int w = im.wallIndex[e];
      reaction[w] -= im.wallForce[e];
      stiffness[w] += im.wallStiffness[e];
      elastic[w] += im.wallElastic[e];
      ++contacts[w];
    }
  }
  for (int w = 0; w < 6; ++w) {
    model_.walls[w].elasticForce = elastic[w];
    model_.walls[w].force = reaction[w];
    model_.walls[w].contactStiffness = stiffness[w];
    model_.walls[w].contacts = contacts[w];
  }
}

// ---------------------------------------------------------------------------------------
// Bonds

void CpuBackend::buildBondLists()
{
  ContactState& im = state_;
  const Particles& p = model_.particles;
  const Bonds& b = model_.bonds;
  const std::size_t n = p.size();
  const SlotLookup slots(p);
  auto findSlot = [&](std::int64_t id) {
    const long slot = slots.find(id);
    if (slot < 0) {
      throw InputError("A bond refers to particle " + std::to_string(id) +
                       ", which is not in the model.");
    }
    return static_cast<std::uint32_t>(slot);
  };
  im.bondI.resize(b.size());
  im.bondJ.resize(b.size());
  for (std::size_t k = 0; k < b.size(); ++k) {
    im.bondI[k] = findSlot(b.idA[k]);
    im.bondJ[k] = findSlot(b.idB[k]);
  }
  im.bondForce.assign(b.size(), Vec3::Zero());
  im.bondTorqueI.assign(b.size(), Vec3::Zero());
  im.bondTorqueJ.assign(b.size(), Vec3::Zero());
  // Gather lists in bond order (a fixed order).
  im.bondAdjacencyStart.assign(n + 1, 0);
  for (std::size_t k = 0; k < b.size(); ++k) {
    ++im.bondAdjacencyStart[im.bondI[k] + 1];
    ++im.bondAdjacencyStart[im.bondJ[k] + 1];
  }
  std::partial_sum(im.bondAdjacencyStart.begin(), im.bondAdjacencyStart.end(),
                   im.bondAdjacencyStart.begin());
  im.bondAdjacency.assign(2 * b.size(), 0);
  std::vector<std::size_t> fill(im.bondAdjacencyStart.begin(), im.bondAdjacencyStart.end() - 1);
  for (std::size_t k = 0; k < b.size(); ++k) {
    im.bondAdjacency[fill[im.bondI[k]]++] = 2 * k;
    im.bondAdjacency[fill[im.bondJ[k]]++] = 2 * k + 1;
  }
}

void CpuBackend::computeBondForces(bool incrementState)
{
  ContactState& im = state_;
  Particles& p = model_.particles;
  Bonds& b = model_.bonds;
  const Domain& d = model_.domain;
  const bool planar = d.section2D;
  const double slab = d.slabThickness();
  const double dt = timestep_;
  const double endTime = model_.clock.time + dt;
  const long count = static_cast<long>(b.size());
  if (count == 0) {
    return;
  }
  const int parts = im.parallel ? im.threads : 1;
  // Each thread starts with one contiguous range of chunks of about equal time at the last
  // step, then takes the chunks still unclaimed in the others' (ChunkClaims).
  const ChunkClaims bondClaims = bondSplit_.split(count, kBondChunk, kUnmeasuredBondCost, parts);
  std::uint32_t* const chunkCost = bondSplit_.cost.data();
  // Four bonds at a time with AVX2 on a real step without periodic axes (IntactBond.h);
  // the scalar loop steps the rest: softening or damaged bonds, groups in which one breaks.
  [[maybe_unused]] const bool simd =
    simd_ && incrementState && !d.periodic[0] && !d.periodic[1] && !d.periodic[2];
  [[maybe_unused]] const IntactBondArrays arrays{ doubles(p.position.data()), doubles(p.velocity.data()),
    doubles(p.angularVelocity.data()), p.radius.data(), im.bondI.data(), im.bondJ.data(), b.failure.data(),
    b.radius.data(), b.normalStiffness.data(), b.shearStiffness.data(), b.tensileStrength.data(),
    b.cohesion.data(), b.frictionAngle.data(), b.momentContribution.data(), b.softening.data(), b.damage.data(),
    b.normalForce.data(), doubles(b.shearForce.data()), b.twistingMoment.data(), doubles(b.bendingMoment.data()),
    doubles(im.bondForce.data()), doubles(im.bondTorqueI.data()), doubles(im.bondTorqueJ.data()), planar, slab, dt };
  team_.run(parts, [=, &im, &p, &b](int part) __attribute__((flatten)) {
  // tan(friction angle) of the last bond whose shear failure this rank tested (NaN: none).
  double lastAngle = std::numeric_limits<double>::quiet_NaN();
  double lastTan = 0.0;
  // One bond's step (the AVX2 kernel's, one lane at a time): state, failure, loads.
  auto stepBond = [&](std::size_t k) __attribute__((always_inline)) {
    if (b.broken(k)) {
      return;
    }
    const std::uint32_t i = im.bondI[k];
    const std::uint32_t j = im.bondJ[k];
    const BondAxis<Vec3> axis = bondAxis(separation(d, p.position[i], p.position[j]), p.radius[i], p.radius[j]);
    const BondSection section = bondSection(b.radius[k], planar, slab);
    if (incrementState) {
      advanceBond(axis, section, b.normalStiffness[k], b.shearStiffness[k], planar, p.velocity[i], p.velocity[j],
                  p.angularVelocity[i], p.angularVelocity[j], dt, b.normalForce[k], b.shearForce[k],
                  b.twistingMoment[k], b.bendingMoment[k]);
      const BondStresses stresses = bondStresses(section, b.radius[k], b.normalForce[k],
        b.shearForce[k], b.twistingMoment[k], b.bendingMoment[k], b.momentContribution[k]);
      if (!(b.frictionAngle[k] == lastAngle)) { // most bonds of a rock share one angle
        lastAngle = b.frictionAngle[k];
        lastTan = std::tan(lastAngle);
      }
      const BondFailure failure = softenedBondFailureWithTan(stresses, b.tensileStrength[k], b.cohesion[k],
                                                             lastTan, b.softening[k], b.damage[k]);
      if (failure != BondFailure::Intact) {
        if (countDissipation_) {
          // the energy its springs held, which breaking takes out of the model
          im.breakEnergy[k] = b.intactShare(k) * bondStoredEnergy(section, b.normalStiffness[k], b.shearStiffness[k],
            b.normalForce[k], b.shearForce[k], b.twistingMoment[k], b.bendingMoment[k]);
        }
        // Broken for good: record how, when, where and how it was oriented.
        b.markBroken(k, failure, endTime, p.position[i] + axis.armI * axis.normal, axis.normal);
        im.bondForce[k].setZero();
        im.bondTorqueI[k].setZero();
        im.bondTorqueJ[k].setZero();
        return;
      }
    }
    const BondLoads<Vec3> loads =
      bondLoads(axis, b.normalForce[k], b.shearForce[k], b.twistingMoment[k], b.bendingMoment[k]);
    im.bondForce[k] = loads.force;
    im.bondTorqueI[k] = loads.torqueI;
    im.bondTorqueJ[k] = loads.torqueJ;
    if (b.damage[k] > 0.0) { // tension softening: the bond applies (1 - D) of its elastic state
      const double share = b.intactShare(k);
      im.bondForce[k] *= share;
      im.bondTorqueI[k] *= share;
      im.bondTorqueJ[k] *= share;
    }
  };
  int visit = 0;
  for (long chunk; (chunk = bondClaims.claim(part, visit)) >= 0;) {
    const std::chrono::steady_clock::time_point chunkStart = std::chrono::steady_clock::now();
    const long chunkEnd = std::min(count, (chunk + 1) * kBondChunk);
#if ROCKDEM_AVX2_KERNEL
    if (simd) {
      std::uint32_t rest[kBondChunk + kBondScanSlack];
      const std::size_t restCount = intactBondsAvx2(arrays, static_cast<std::size_t>(chunk * kBondChunk),
                                                    static_cast<std::size_t>(chunkEnd), rest);
      for (std::size_t r = 0; r < restCount; ++r) {
        stepBond(rest[r]);
      }
      chunkCost[chunk] = measuredCost(chunkStart, chunkCost[chunk]);
      continue;
    }
#endif
    for (long k = chunk * kBondChunk; k < chunkEnd; ++k) {
      stepBond(static_cast<std::size_t>(k));
    }
    chunkCost[chunk] = measuredCost(chunkStart, chunkCost[chunk]);
  }
  });
}

// ---------------------------------------------------------------------------------------
// Stepping

void CpuBackend::step(bool last)
{
  ContactState& im = state_;
  Particles& p = model_.particles;
  const Domain& d = model_.domain;
  const double dt = timestep_;
  const double half = 0.5 * dt;
  const bool planar = d.section2D;
  const long count = static_cast<long>(p.size());
  const double limit = 0.5 * im.skinDistance; // m, drift that makes the neighbour list stale
  const double limit2 = limit * limit;
  const MinimumImage separationOf(d);
  const bool anyPeriodic = d.periodic[0] || d.periodic[1] || d.periodic[2];

  // Half kick with the forces of the last step, then drift; note whether any particle
  // has moved half the skin since the neighbour list was built. Done already where the
  // last step's gather did it (run()).
  bool stale = driftedStale_;
  Vec3* const position = p.position.data(); // raw pointers, as in computeForces
  Vec3* const velocity = p.velocity.data();
  Vec3* const spin = p.angularVelocity.data();
  Vec3* const displacement = p.displacement.data();
  const Vec3* const force = p.force.data();
  const Vec3* const torque = p.torque.data();
  const Vec3* const positionAtBuild = im.positionAtBuild.data();
  const double* const inverseMass = im.inverseMass.data();
  const double* const inverseInertia = im.inverseInertia.data();
  if (!drifted_) {
    const int parts = im.parallel ? im.threads : 1;
    staleByRank_.assign(static_cast<std::size_t>(parts), 0);
    std::uint8_t* const staleByRank = staleByRank_.data();
    team_.run(parts, [&](int part) {
      bool rankStale = false;
      for (long li = evenShare(count, part, parts); li < evenShare(count, part + 1, parts); ++li) {
        if (kickAndDrift(static_cast<std::size_t>(li), position, velocity, spin, displacement, force, torque,
                         positionAtBuild, inverseMass, inverseInertia, dt, half, planar, anyPeriodic, d,
                         separationOf, limit2)) {
          rankStale = true;
        }
      }
      staleByRank[part] = rankStale ? 1 : 0;
    });
    for (int part = 0; part < parts; ++part) {
      stale = stale || staleByRank[part] != 0;
    }
  }
  drifted_ = false;
  driftedStale_ = false;
  controlWalls(model_, timestep_, im.smallestRadius);
  for (Wall& wall : model_.walls) {
    wall.position += wall.velocity * dt;
  }
  membraneSurface(model_, &im.externalForce); // the membrane's forces at the new positions

  if (stale) {
    rebuildNeighbours(false);
  } else if (wallsMoved()) {
    rebuildWallContacts(true);
  }
  // New forces, then the second half kick (in the same pass), and unless this is the
  // run's last step, the next step's half kick and drift.
  computeForces(true, true, !last);
  model_.clock.step += 1;
  model_.clock.time += dt;
}

} // namespace dem
