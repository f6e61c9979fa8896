#include "dem/Simulation.h"

#include "dem/Bonds.h"
#include "dem/Errors.h"
#include "dem/ParticleStress.h"
#include "dem/SizeClassGrids.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace dem {
namespace {

constexpr double Pi = 3.14159265358979323846;

/// Cundall local damping of one degree of freedom (PHYSICS.md s.1):
/// F - alpha |F| sign(v), with sign(0) = 0. Branch-free: the damping term takes the sign
/// of v by copysign, and vanishes at v = 0.
double cundall(double force, double velocity, double alpha)
{
  const double damping = std::copysign(alpha * std::abs(force), velocity); // N
  return force - (velocity != 0.0 ? damping : 0.0);
}

/// Finds a particle's slot from its global id (ids are stable, slots are storage order).
class SlotLookup {
public:
  explicit SlotLookup(const Particles& p) : sorted_(p.size())
  {
    for (std::size_t i = 0; i < p.size(); ++i) {
      sorted_[i] = { p.id[i], static_cast<std::uint32_t>(i) };
    }
    std::sort(sorted_.begin(), sorted_.end());
  }
  /// The slot of `id`, or -1 when no particle has it.
  long find(std::int64_t id) const
  {
    auto it = std::lower_bound(sorted_.begin(), sorted_.end(), std::make_pair(id, std::uint32_t(0)));
    return (it != sorted_.end() && it->first == id) ? static_cast<long>(it->second) : -1;
  }

private:
  std::vector<std::pair<std::int64_t, std::uint32_t>> sorted_;
};

int availableThreads()
{
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

} // namespace

// ---------------------------------------------------------------------------------------
// Timestep, settings, walls

double contactTimestep(const Model& model, ContactLaw law)
{
  const Particles& p = model.particles;
  if (p.empty()) {
    return std::numeric_limits<double>::infinity();
  }
  const Material& m = model.material;
  if (law == ContactLaw::HertzMindlin) {
    // Rayleigh: dt_R = pi R_min sqrt(rho / G) / (0.1631 nu + 0.8766), G = E / (2(1+nu)).
    const double rmin = *std::min_element(p.radius.begin(), p.radius.end());
    const double G = m.youngsModulus / (2.0 * (1.0 + m.poissonsRatio));
    return Pi * rmin * std::sqrt(m.density / G) / (0.1631 * m.poissonsRatio + 0.8766);
  }
  // Linear springs: per particle sqrt(m / k) and sqrt(I / k_rot) with k summed over a
  // full coordination (12 contacts in 3D, 6 in 2D) of the stiffest (wall) contact.
  const ContactModel cm{ law, m.restitution, 0.0, m.friction, m.rollingFriction, m.youngsModulus,
                         m.poissonsRatio };
  const bool planar = model.domain.section2D;
  const double coordination = planar ? 6.0 : 12.0;
  double dt = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const PairProperties w =
      wallProperties(cm, p.radius[i], p.mass[i], planar, model.domain.slabThickness());
    const double kn = coordination * w.linearNormalStiffness;
    const double kt = coordination * w.linearShearStiffness;
    const double r = p.radius[i];
    dt = std::min(dt, std::sqrt(p.mass[i] / kn));
    dt = std::min(dt, std::sqrt(p.inertia[i] / (kt * r * r)));
  }
  return dt;
}

namespace {
/// Mass-spring limit of the bonds (PHYSICS.md s.2): per particle sqrt(m / sum kn A) and
/// sqrt(I / sum (kn I_b + ks A r^2)) over all its bonds, intact or broken (so that the
/// timestep does not change as bonds break and a resumed run keeps it).
double bondTimestep(const Model& model)
{
  const Particles& p = model.particles;
  const Bonds& b = model.bonds;
  if (b.size() == 0) {
    return std::numeric_limits<double>::infinity();
  }
  const SlotLookup slots(p);
  std::vector<double> translational(p.size(), 0.0);
  std::vector<double> rotational(p.size(), 0.0);
  const bool planar = model.domain.section2D;
  for (std::size_t k = 0; k < b.size(); ++k) {
    const BondSection s = bondSection(b.radius[k], planar, model.domain.slabThickness());
    for (std::int64_t id : { b.idA[k], b.idB[k] }) {
      const long slot = slots.find(id);
      if (slot < 0) {
        continue;
      }
      const std::size_t i = static_cast<std::size_t>(slot);
      const double r = p.radius[i];
      translational[i] += std::max(b.normalStiffness[k], b.shearStiffness[k]) * s.area;
      rotational[i] += b.normalStiffness[k] * s.inertia + b.shearStiffness[k] * s.area * r * r;
    }
  }
  double dt = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (translational[i] > 0.0) {
      dt = std::min(dt, std::sqrt(p.mass[i] / translational[i]));
      dt = std::min(dt, std::sqrt(p.inertia[i] / rotational[i]));
    }
  }
  return dt;
}
} // namespace

double criticalTimestep(const Model& model, ContactLaw law)
{
  return std::min(contactTimestep(model, law), bondTimestep(model));
}

void validate(const SolverSettings& s)
{
  requireInRange("Timestep Safety", s.timestepSafety, 1e-6, 1.0);
  requireNonNegative("Timestep", s.requestedTimestep, "s");
  if (!(s.settlingDamping >= 0.0 && s.settlingDamping < 1.0)) {
    throw InputError("Settling Damping = " + formatValue(s.settlingDamping) +
                     " is out of range: valid range is [0, 1).");
  }
  requirePositive("Verlet Skin", s.skin);
  if (s.threads < 0) {
    throw InputError("Threads = " + std::to_string(s.threads) +
                     " is out of range: valid range is 0 (all cores) or more.");
  }
}

void resetWalls(Model& model)
{
  model.walls.clear();
  const Domain& d = model.domain;
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side < 2; ++side) {
      Wall w;
      w.axis = axis;
      w.side = side;
      w.position = side == 0 ? d.origin[axis] : d.origin[axis] + d.size[axis];
      w.active = !d.periodic[axis] && !(d.section2D && axis == 2);
      model.walls.push_back(w);
    }
  }
}

// ---------------------------------------------------------------------------------------
// Internal state

struct Simulation::Impl {
  // Neighbour list: particle pairs (slots i < j) within reach, sorted by (i, j).
  std::vector<std::uint32_t> pairI, pairJ;
  std::vector<ContactConstants> pairConstants; // per pair: stiffness and damping factors
  std::vector<Vec3> pairSpring;      // m, tangential history
  std::vector<Vec3> pairRolling;     // N m, rolling history (empty if rolling is off)
  std::vector<Vec3> pairForce;       // N, force on i (j gets the opposite)
  std::vector<Vec3> pairTorqueI;     // N m
  std::vector<Vec3> pairTorqueJ;     // N m
  std::vector<double> pairNormal;    // N, normal force magnitude (0: adds nothing, the gather skips it)
  // Per-particle gather lists (CSR): entries of particle i in [start[i], start[i+1]);
  // an entry is 2 * pair + (1 if the particle is j of the pair).
  std::vector<std::size_t> adjacencyStart;
  std::vector<std::size_t> adjacency;
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
  int threads = 1;
  bool parallel = false;
  bool broken = false;
};

namespace {
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

private:
  const Domain& domain_;
  bool plain_;
};

Vec3 separation(const Domain& d, const Vec3& a, const Vec3& b) { return minimumImage(d, a, b); }
} // namespace

Simulation::Simulation(Model& model)
  : impl_(new Impl)
  , model_(model)
{
  validate(model.domain);
  validate(model.material);
  validate(model.solver);
  const SolverSettings& s = model.solver;
  contactModel_ = makeContactModel(model.material, s.contactLaw);
  if (model.walls.size() != 6) {
    resetWalls(model);
  }

  critical_ = dem::criticalTimestep(model, s.contactLaw);
  const double safe = s.timestepSafety * critical_;
  if (s.requestedTimestep > 0.0 && s.requestedTimestep > safe && !s.allowUnsafeTimestep) {
    std::ostringstream msg;
    msg << "Timestep = " << formatValue(s.requestedTimestep) << " s is above the safe value "
        << formatValue(safe) << " s (Timestep Safety " << formatValue(s.timestepSafety)
        << " x critical " << formatValue(critical_) << " s): using " << formatValue(safe) << " s.";
    timestepMessage_ = msg.str();
    timestep_ = safe;
  } else if (s.requestedTimestep > 0.0) {
    timestep_ = s.requestedTimestep;
  } else {
    timestep_ = safe;
  }
  if (!std::isfinite(timestep_)) {
    timestep_ = 0.0; // no particles: nothing to step
  }
  model.clock.timestep = timestep_;

  Impl& im = *impl_;
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
  im.parallel = static_cast<std::int64_t>(n) >= s.parallelThreshold && im.threads > 1;
  if (!im.parallel) {
    im.threads = 1;
  }

  // Import the stored contact history (by global ids) into the neighbour list.
  rebuildNeighbours(true);
  buildBondLists();
  if (model.clock.step == 0) {
    // A model that has never stepped has no forces yet: compute them (no history
    // increment) so that the first half kick sees gravity and the initial contacts.
    computeForces(false, false);
  } else {
    // Resumed: the stored forces, torques, springs and wall reactions are those of the
    // last step and must stay bit for bit. Evaluate the contacts once for the
    // diagnostics only, then put the stored state back.
    const std::vector<Vec3> force = model.particles.force;
    const std::vector<Vec3> torque = model.particles.torque;
    const std::vector<Wall> walls = model.walls;
    const Impl saved = *impl_;
    const Bonds bonds = model.bonds;
    computeForces(false, false);
    model.bonds = bonds;
    model.particles.force = force;
    model.particles.torque = torque;
    model.walls = walls;
    impl_->pairSpring = saved.pairSpring;
    impl_->pairRolling = saved.pairRolling;
    impl_->wallSpring = saved.wallSpring;
    impl_->wallRolling = saved.wallRolling;
  }
  initialAvailableEnergy_ = availableEnergy();
}

Simulation::~Simulation() = default;

std::string Simulation::path() const
{
  return impl_->parallel ? "CPU OpenMP (" + std::to_string(impl_->threads) + " threads)"
                         : std::string("CPU serial");
}

// ---------------------------------------------------------------------------------------
// Neighbour list

void Simulation::rebuildNeighbours(bool importModelHistory)
{
  Impl& im = *impl_;
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
  im.pairForce.assign(pairs, Vec3::Zero());
  im.pairTorqueI.assign(pairs, Vec3::Zero());
  im.pairTorqueJ.assign(pairs, Vec3::Zero());
  im.pairNormal.assign(pairs, 0.0);
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

  // Gather lists: each particle's pairs in order of partner slot (a fixed order).
  im.adjacencyStart.assign(n + 1, 0);
  for (std::size_t k = 0; k < pairs; ++k) {
    ++im.adjacencyStart[im.pairI[k] + 1];
    ++im.adjacencyStart[im.pairJ[k] + 1];
  }
  std::partial_sum(im.adjacencyStart.begin(), im.adjacencyStart.end(), im.adjacencyStart.begin());
  im.adjacency.assign(2 * pairs, 0);
  std::vector<std::size_t> fill(im.adjacencyStart.begin(), im.adjacencyStart.end() - 1);
  // Pairs are sorted by (i, j): visiting them in order appends, for each particle, the
  // partners below it (as j) in increasing i, then the partners above it (as i) in
  // increasing j. Both runs are sorted, and the first precedes the second.
  for (std::size_t k = 0; k < pairs; ++k) {
    im.adjacency[fill[im.pairJ[k]]++] = 2 * k + 1;
  }
  for (std::size_t k = 0; k < pairs; ++k) {
    im.adjacency[fill[im.pairI[k]]++] = 2 * k;
  }
}

void Simulation::rebuildWallContacts(bool carryHistory)
{
  Impl& im = *impl_;
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

bool Simulation::wallsMoved() const
{
  const Impl& im = *impl_;
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

void Simulation::computeForces(bool incrementHistory, bool closingKick)
{
  Impl& im = *impl_;
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

  // 1. Each pair once.
#pragma omp parallel for schedule(static) num_threads(im.threads) if (im.parallel)
  for (long k = 0; k < pairs; ++k) {
    const std::uint32_t i = im.pairI[k];
    const std::uint32_t j = im.pairJ[k];
    const Vec3 branch = separationOf(p.position[i], p.position[j]); // from i to j
    const double distance = branch.norm();
    const double overlap = p.radius[i] + p.radius[j] - distance;
    if (overlap <= 0.0 || distance == 0.0) {
      if (im.pairNormal[k] != 0.0 || !im.pairSpring[k].isZero(0.0) ||
          (rolling && !im.pairRolling[k].isZero(0.0))) {
        // The contact just ended: clear its force and history (once, not every step).
        im.pairForce[k].setZero();
        im.pairTorqueI[k].setZero();
        im.pairTorqueJ[k].setZero();
        im.pairNormal[k] = 0.0;
        im.pairSpring[k].setZero();
        if (rolling) {
          im.pairRolling[k].setZero();
        }
      }
      continue;
    }
    const Vec3 normal = branch / distance;
    const double armI = p.radius[i] - 0.5 * overlap; // m, centre to contact point
    const double armJ = p.radius[j] - 0.5 * overlap;
    // Slip over the step uses the half-step velocities (exact for the displacement
    // increment); the viscous damping uses the full-step velocities, predicted from the
    // last forces, so that restitution does not drift with the number of steps per impact.
    const Vec3 relativeVelocity = p.velocity[i] - p.velocity[j] +
      p.angularVelocity[i].cross(armI * normal) + p.angularVelocity[j].cross(armJ * normal);
    const Vec3 predictedVelocity = relativeVelocity +
      predict * (im.inverseMass[i] * p.force[i] - im.inverseMass[j] * p.force[j]);
    const double approachSpeed = predictedVelocity.dot(normal);
    const NormalResponse response = normalResponse(cm.law, im.pairConstants[k], overlap, approachSpeed);
    const double fn = response.force;
    const Vec3 slip = inPlane(relativeVelocity, normal) * dt;
    const Vec3 ft =
      mindlinCoulombForce(response.tangentialStiffness, cm.friction, fn, normal, slip, im.pairSpring[k]);
    Vec3 torqueI = armI * normal.cross(ft);
    Vec3 torqueJ = armJ * normal.cross(ft);
    if (rolling) {
      const PairProperties pair =
        pairProperties(cm, p.radius[i], massOf(i), p.radius[j], massOf(j), planar, slab);
      const Vec3 roll = inPlane(p.angularVelocity[i] - p.angularVelocity[j], normal) * dt;
      const Vec3 mr = rollingTorque(cm, pair, overlap, fn, normal, roll, im.pairRolling[k]);
      torqueI += mr;
      torqueJ -= mr;
    }
    im.pairForce[k] = -fn * normal + ft;
    im.pairTorqueI[k] = torqueI;
    im.pairTorqueJ[k] = torqueJ;
    im.pairNormal[k] = fn;
    if (fn != 0.0) {
      // Two threads may mark the same particle: both write 1.
#pragma omp atomic write
      im.touching[i] = 1;
#pragma omp atomic write
      im.touching[j] = 1;
    }
  }

  // 2. Bonds, each once (state updated and failure checked only on a real step).
  computeBondForces(incrementHistory);

  // 3. Walls. During a press test the walls are frictionless (the usual choice for
  // servo-controlled faces and platens: a face must be free to follow the specimen's
  // lateral expansion without shear from it). Evaluated in the gather below, by the
  // particle's own thread: wall entry e of particle i adds its force and torque.
  ContactModel wallModel = cm;
  if (model_.test.settings.mode != TestMode::Off) {
    wallModel.friction = 0.0;
    wallModel.rollingFriction = 0.0;
  }
  const bool wallRolling = wallModel.rollingFriction > 0.0;
  auto wallContact = [&](std::size_t e, std::size_t i, Vec3& force, Vec3& torque) {
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
    const Vec3 ft = mindlinCoulombForce(response.tangentialStiffness, wallModel.friction, fn,
                                        normal, slip, im.wallSpring[e]);
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
  const double alpha = model_.solver.settlingDamping;
  const Vec3 gravity = model_.gravity;
  const double half = 0.5 * timestep_;
  const long count = static_cast<long>(n);
  const bool anyBonds = !im.bondI.empty();
#pragma omp parallel for schedule(static) num_threads(im.threads) if (im.parallel)
  for (long li = 0; li < count; ++li) {
    const std::size_t i = static_cast<std::size_t>(li);
    Vec3 force = p.mass[i] * gravity;
    Vec3 torque = Vec3::Zero();
    // Without a touching pair (none has a non-zero normal force) the list adds nothing.
    const std::size_t pairEnd = im.touching[i] ? im.adjacencyStart[i + 1] : im.adjacencyStart[i];
    im.touching[i] = 0;
    for (std::size_t e = im.adjacencyStart[i]; e < pairEnd; ++e) {
      const std::size_t k = im.adjacency[e] >> 1;
      if (im.pairNormal[k] == 0.0) {
        continue; // not touching, or no force: adds nothing (and skipping +0.0 changes no bit)
      }
      if (im.adjacency[e] & 1u) {
        force -= im.pairForce[k];
        torque += im.pairTorqueJ[k];
      } else {
        force += im.pairForce[k];
        torque += im.pairTorqueI[k];
      }
    }
    for (std::size_t e = im.wallStart[i]; e < im.wallStart[i + 1]; ++e) {
      wallContact(e, i, force, torque);
    }
    if (anyBonds) {
      for (std::size_t e = im.bondAdjacencyStart[i]; e < im.bondAdjacencyStart[i + 1]; ++e) {
        const std::size_t b = im.bondAdjacency[e] >> 1;
        if (model_.bonds.broken(b)) {
          continue;
        }
        if (im.bondAdjacency[e] & 1u) {
          force -= im.bondForce[b];
          torque += im.bondTorqueJ[b];
        } else {
          force += im.bondForce[b];
          torque += im.bondTorqueI[b];
        }
      }
    }
    if (planar) {
      force.z() = 0.0;
      torque.x() = 0.0;
      torque.y() = 0.0;
    }
    im.undampedForce[i] = force;
    Vec3 damped = force;
    Vec3 dampedTorque = torque;
    if (alpha > 0.0) {
      for (int c = 0; c < 3; ++c) {
        damped[c] = cundall(force[c], p.velocity[i][c], alpha);
        dampedTorque[c] = cundall(torque[c], p.angularVelocity[i][c], alpha);
      }
    }
    p.force[i] = damped;
    p.torque[i] = dampedTorque;
    if (closingKick && im.inverseMass[i] != 0.0) {
      p.velocity[i] += (half * im.inverseMass[i]) * damped;
      p.angularVelocity[i] += (half * im.inverseInertia[i]) * dampedTorque;
      if (planar) {
        p.velocity[i].z() = 0.0;
        p.angularVelocity[i].x() = 0.0;
        p.angularVelocity[i].y() = 0.0;
      }
    }
  }

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

void Simulation::buildBondLists()
{
  Impl& im = *impl_;
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

void Simulation::computeBondForces(bool incrementState)
{
  Impl& im = *impl_;
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
#pragma omp parallel for schedule(static) num_threads(im.threads) if (im.parallel)
  for (long lk = 0; lk < count; ++lk) {
    const std::size_t k = static_cast<std::size_t>(lk);
    if (b.broken(k)) {
      continue;
    }
    const std::uint32_t i = im.bondI[k];
    const std::uint32_t j = im.bondJ[k];
    const Vec3 branch = separation(d, p.position[i], p.position[j]); // A to B
    const double distance = branch.norm();
    const Vec3 normal = branch / distance;
    // The contact point divides the branch in the ratio of the radii.
    const double armI = distance * p.radius[i] / (p.radius[i] + p.radius[j]);
    const double armJ = distance - armI;
    const BondSection section = bondSection(b.radius[k], planar, slab);
    if (incrementState) {
      const Vec3 relativeVelocity = p.velocity[i] - p.velocity[j] +
        p.angularVelocity[i].cross(armI * normal) + p.angularVelocity[j].cross(armJ * normal);
      const Vec3 relativeSpin = p.angularVelocity[i] - p.angularVelocity[j];
      const double kn = b.normalStiffness[k];
      const double ks = b.shearStiffness[k];
      // dFn = kn A d(separation): positive (tension) when B moves away from A.
      b.normalForce[k] -= kn * section.area * relativeVelocity.dot(normal) * dt;
      // dFs = -ks A (tangential displacement of A relative to B), in the rotated plane.
      b.shearForce[k] = rotateIntoPlane(b.shearForce[k], normal) -
        ks * section.area * inPlane(relativeVelocity, normal) * dt;
      // dMt = -ks J d(theta twist) (3D); dMb = -kn I d(theta bend).
      if (!planar) {
        b.twistingMoment[k] -= ks * section.polar * relativeSpin.dot(normal) * dt;
      }
      b.bendingMoment[k] = rotateIntoPlane(b.bendingMoment[k], normal) -
        kn * section.inertia * inPlane(relativeSpin, normal) * dt;
      const BondStresses stresses = bondStresses(section, b.radius[k], b.normalForce[k],
        b.shearForce[k], b.twistingMoment[k], b.bendingMoment[k]);
      const BondFailure failure =
        bondFailure(stresses, b.tensileStrength[k], b.cohesion[k], b.frictionAngle[k]);
      if (failure != BondFailure::Intact) {
        // Broken for good: record how, when, where and how it was oriented.
        b.markBroken(k, failure, endTime, p.position[i] + armI * normal, normal);
        im.bondForce[k].setZero();
        im.bondTorqueI[k].setZero();
        im.bondTorqueJ[k].setZero();
        continue;
      }
    }
    const Vec3 twist = b.twistingMoment[k] * normal;
    im.bondForce[k] = b.normalForce[k] * normal + b.shearForce[k];
    im.bondTorqueI[k] = armI * normal.cross(b.shearForce[k]) + twist + b.bendingMoment[k];
    im.bondTorqueJ[k] = armJ * normal.cross(b.shearForce[k]) - twist - b.bendingMoment[k];
  }
}

// ---------------------------------------------------------------------------------------
// The virtual press

std::array<double, 3> Simulation::specimenLengths() const
{
  // Between the walls where they are active (or driven, as the tension platen); on the
  // unwalled sides of an unconfined test, the starting extent scaled by the spread of the
  // particle centres (centreSpread: robust to grains that fly off); else the extent.
  const Particles& p = model_.particles;
  const LoadTestState& t = model_.test;
  std::array<double, 3> length{ { 0.0, 0.0, 0.0 } };
  for (int k = 0; k < 3; ++k) {
    const Wall& low = model_.walls[2 * k];
    const Wall& high = model_.walls[2 * k + 1];
    const bool platenAxis = t.settings.mode != TestMode::Off && k == t.settings.axis;
    if (low.active || high.active || platenAxis) {
      length[k] = high.position - low.position;
    } else if (model_.domain.section2D && k == 2) {
      length[k] = model_.domain.slabThickness();
    } else if (t.initialSpread[k] > 0.0) {
      // An unconfined side: the starting extent scaled as the spread of the centres.
      length[k] = t.initialLength[k] * centreSpread(p, k) / t.initialSpread[k];
    } else {
      double lo = std::numeric_limits<double>::max();
      double hi = -lo;
      for (std::size_t i = 0; i < p.size(); ++i) {
        lo = std::min(lo, p.position[i][k] - p.radius[i]);
        hi = std::max(hi, p.position[i][k] + p.radius[i]);
      }
      length[k] = p.empty() ? model_.domain.size[k] : hi - lo;
    }
  }
  return length;
}

void Simulation::controlWalls()
{
  LoadTestState& t = model_.test;
  const LoadTestSettings& s = t.settings;
  if (s.mode == TestMode::Off || t.stage == TestStage::Idle) {
    return;
  }
  const int a = s.axis;
  const double dt = timestep_;
  // Which faces do what: every face servo-controlled while consolidating (and, for an
  // isotropic test, for good: it holds the stress once settled); the side faces of a
  // triaxial test keep the stress through shear and after; the platen advances only
  // during shear and stops when Max Strain is reached.
  const bool servoAll = t.stage == TestStage::Consolidate || s.mode == TestMode::Isotropic;
  const bool servoSides = s.mode == TestMode::Triaxial && t.stage != TestStage::Consolidate;
  const bool platenMoving = t.stage == TestStage::Shear;
  const double platenSpeed = s.strainRate * t.initialLength[a]; // m/s
  const double platenVelocity = s.mode == TestMode::Tension ? platenSpeed : -platenSpeed;
  Particles& p = model_.particles;
  const double rmin = impl_->smallestRadius;
  // The specimen's size (a pass over the particles on an axis without walls): only for
  // the servo.
  std::array<double, 3> length{ { 0.0, 0.0, 0.0 } };
  bool lengthKnown = false;
  // A servo wall never moves more than 0.2 % of the smallest radius per step: fast enough
  // to close a gap of a radius in a few hundred steps, slow enough that the viscous part
  // of the contact forces does not dominate what the servo measures.
  const double maxSpeed = 0.002 * rmin / dt;
  for (Wall& w : model_.walls) {
    const bool servo = w.active && (servoAll || (servoSides && w.axis != a));
    if (servo) {
      if (!lengthKnown) {
        length = specimenLengths();
        lengthKnown = true;
      }
      const int b = (w.axis + 1) % 3;
      const int c = (w.axis + 2) % 3;
      const double area = length[b] * length[c];
      // The servo controls the elastic push: the viscous part of the wall forces follows
      // the wall's own speed, and feeding it back makes the servo chatter.
      const double measured = w.elasticForce / area; // Pa, compression positive
      double outward = -maxSpeed;                    // no contact: close in
      if (w.contactStiffness > 0.0) {
        // u = G (sigma - sigma_target), G = alpha A / (kn_wall Nc dt) (PHYSICS.md s.4).
        const double gain = s.servoAlpha * area / (w.contactStiffness * dt);
        outward = gain * (measured - s.confiningStress);
      }
      outward = std::max(-maxSpeed, std::min(maxSpeed, outward));
      w.velocity = w.side == 0 ? -outward : outward;
    } else if (platenMoving && w.axis == a && w.side == 1) {
      w.velocity = platenVelocity;
    } else {
      w.velocity = 0.0;
    }
  }
  if (s.mode == TestMode::Tension) {
    // The particles attached to the high platen move with it.
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.flags[i] & FlagAttachedHigh) {
        p.velocity[i].setZero();
        p.velocity[i][a] = platenMoving ? platenVelocity : 0.0;
      }
    }
  }
}

TestMeasurements Simulation::measurements() const
{
  const Impl& im = *impl_;
  const Particles& p = model_.particles;
  const Domain& d = model_.domain;
  const LoadTestState& t = model_.test;
  const LoadTestSettings& s = t.settings;
  const bool planar = d.section2D;
  TestMeasurements m;
  const std::array<double, 3> length = specimenLengths();
  const double volume = length[0] * length[1] * length[2];
  for (int k = 0; k < 3; ++k) {
    const double l0 = t.initialLength[k] > 0.0 ? t.initialLength[k] : d.size[k];
    m.strain[k] = (planar && k == 2) ? 0.0 : (l0 - length[k]) / l0;
  }
  const double v0 = t.initialVolume > 0.0 ? t.initialVolume
                                           : d.size.x() * d.size.y() * d.size.z();
  m.volumetricStrain = 1.0 - volume / v0;
  // Face stresses from the wall reactions over the current face areas.
  for (int w = 0; w < 6; ++w) {
    const Wall& wall = model_.walls[w];
    const int b = (wall.axis + 1) % 3;
    const int c = (wall.axis + 2) % 3;
    const double area = length[b] * length[c];
    m.faceStress[w] = wall.active && area > 0.0 ? -wall.force.dot(wall.normal()) / area : 0.0;
  }
  // Love-Weber: sigma = -(1/V) sum over particles and their contacts of (x_c - x_p) (x) f_c.
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (std::size_t k = 0; k < im.pairI.size(); ++k) {
    if (im.pairNormal[k] == 0.0) {
      continue;
    }
    const std::size_t i = im.pairI[k];
    const std::size_t j = im.pairJ[k];
    const Vec3 branch = separation(d, p.position[i], p.position[j]);
    sum += branch * im.pairForce[k].transpose(); // arms add up to the branch
  }
  for (std::size_t k = 0; k < im.bondI.size(); ++k) {
    if (model_.bonds.broken(k)) {
      continue;
    }
    const Vec3 branch = separation(d, p.position[im.bondI[k]], p.position[im.bondJ[k]]);
    sum += branch * im.bondForce[k].transpose();
  }
  for (std::size_t e = 0; e < im.wallSlot.size(); ++e) { // in (slot, wall) order
    if (im.wallTouching[e]) {
      const std::size_t i = im.wallSlot[e];
      const Wall& wall = model_.walls[im.wallIndex[e]];
      const double side = wall.side == 0 ? 1.0 : -1.0;
      const double distance = (p.position[i][wall.axis] - wall.position) * side;
      const Vec3 arm = -wall.normal() * distance; // centre to contact point
      sum += arm * im.wallForce[e].transpose();
    }
  }
  const Eigen::Matrix3d sigma = -(sum + sum.transpose()) / (2.0 * volume);
  m.stressTensor = { { sigma(0, 0), sigma(1, 1), sigma(2, 2), sigma(0, 1), sigma(1, 2), sigma(2, 0) } };
  m.meanStress = planar ? 0.5 * (sigma(0, 0) + sigma(1, 1)) : sigma.trace() / 3.0;

  const int a = s.axis;
  if (s.mode == TestMode::Tension) {
    // The pull on the particles attached to the high platen, over the cross-section.
    double pull = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.flags[i] & FlagAttachedHigh) {
        pull += (im.undampedForce[i] - p.mass[i] * model_.gravity)[a];
      }
    }
    const double area = length[(a + 1) % 3] * length[(a + 2) % 3];
    m.axialStress = area > 0.0 ? pull / area : 0.0; // negative in tension
  } else {
    m.axialStress = 0.5 * (m.faceStress[2 * a] + m.faceStress[2 * a + 1]);
  }
  double lateral = 0.0;
  int sides = 0;
  for (int w = 0; w < 6; ++w) {
    if (model_.walls[w].active && model_.walls[w].axis != a) {
      lateral += m.faceStress[w];
      ++sides;
    }
  }
  m.lateralStress = sides > 0 ? lateral / sides : 0.0;
  m.deviatorStress = m.axialStress - m.lateralStress;

  // Inertial number I = strain rate x mean diameter x sqrt(density / mean stress).
  double meanRadius = 0.0;
  for (double r : p.radius) {
    meanRadius += r;
  }
  meanRadius = p.empty() ? 0.0 : meanRadius / static_cast<double>(p.size());
  const double diameter = 2.0 * meanRadius;
  const double rho = model_.material.density;
  const double pressure = std::abs(m.meanStress);
  if (pressure > 0.0 && s.mode != TestMode::Off) {
    m.inertialNumber = s.strainRate * diameter * std::sqrt(rho / pressure);
  }
  const double reference =
    (s.mode == TestMode::Triaxial || s.mode == TestMode::Isotropic) ? s.confiningStress : pressure;
  if (reference > 0.0 && diameter > 0.0) {
    m.suggestedStrainRate = 1e-4 / (diameter * std::sqrt(rho / reference));
  }
  return m;
}

InteractionForces Simulation::interactionForces() const
{
  const Impl& im = *impl_;
  const Particles& p = model_.particles;
  const Domain& d = model_.domain;
  InteractionForces out;
  for (std::size_t k = 0; k < im.pairI.size(); ++k) {
    if (im.pairNormal[k] != 0.0) {
      const std::uint32_t i = im.pairI[k];
      const std::uint32_t j = im.pairJ[k];
      const Vec3 branch = separation(d, p.position[i], p.position[j]);
      const double distance = branch.norm();
      const double overlap = p.radius[i] + p.radius[j] - distance;
      const Vec3 armI = (p.radius[i] - 0.5 * overlap) / distance * branch; // as computeForces
      out.append(i, j, im.pairForce[k], armI, armI - branch);
    }
  }
  for (std::size_t k = 0; k < im.bondI.size(); ++k) {
    if (!model_.bonds.broken(k)) {
      const std::uint32_t i = im.bondI[k];
      const std::uint32_t j = im.bondJ[k];
      const Vec3 branch = separation(d, p.position[i], p.position[j]);
      const Vec3 armI = p.radius[i] / (p.radius[i] + p.radius[j]) * branch; // as computeBondForces
      out.append(i, j, im.bondForce[k], armI, armI - branch);
    }
  }
  for (std::size_t e = 0; e < im.wallSlot.size(); ++e) {
    if (im.wallTouching[e]) {
      const std::uint32_t i = im.wallSlot[e];
      const Wall& wall = model_.walls[im.wallIndex[e]];
      const double distance = (p.position[i][wall.axis] - wall.position) * (wall.side == 0 ? 1.0 : -1.0);
      out.append(i, WallPartner, im.wallForce[e], -wall.normal() * distance, Vec3::Zero());
    }
  }
  return out;
}

void Simulation::sampleLoadTest()
{
  LoadTestState& t = model_.test;
  const LoadTestSettings& s = t.settings;
  if (s.mode == TestMode::Off || t.stage == TestStage::Done) {
    return;
  }
  if (++t.stepsSinceSample < s.sampleInterval) {
    return;
  }
  t.stepsSinceSample = 0;
  const TestMeasurements m = measurements();
  const Diagnostics d = diagnostics();
  const BondCounts bonds = countBonds(model_.bonds);
  std::array<double, HistoryColumnCount> row{};
  std::size_t c = 0;
  row[c++] = model_.clock.time;
  row[c++] = static_cast<double>(model_.clock.step);
  for (int k = 0; k < 3; ++k) {
    row[c++] = m.strain[k];
  }
  row[c++] = m.volumetricStrain;
  for (double f : m.faceStress) {
    row[c++] = f;
  }
  for (double v : m.stressTensor) {
    row[c++] = v;
  }
  row[c++] = m.axialStress;
  row[c++] = m.lateralStress;
  row[c++] = m.deviatorStress;
  row[c++] = static_cast<double>(bonds.tension);
  row[c++] = static_cast<double>(bonds.shear);
  row[c++] = d.unbalancedForceRatio;
  row[c++] = m.inertialNumber;
  row[c++] = static_cast<double>(t.stage);
  row[c++] = m.meanStress;
  t.history.push_back(row);
  // Peaks: in tension the strength is the largest pull (most negative axial stress).
  const double axialMagnitude = s.mode == TestMode::Tension ? -m.axialStress : m.axialStress;
  if (t.stage == TestStage::Shear) {
    t.peakStress = std::max(t.peakStress, axialMagnitude);
    t.peakDeviator = std::max(t.peakDeviator, m.deviatorStress);
  }

  const int a = s.axis;
  if (t.stage == TestStage::Consolidate) {
    bool settled = true;
    for (int w = 0; w < 6; ++w) {
      if (model_.walls[w].active) {
        settled = settled &&
          std::abs(m.faceStress[w] - s.confiningStress) <= s.settleTolerance * s.confiningStress;
      }
    }
    t.settledChecks = settled && d.unbalancedForceRatio < 0.01 ? t.settledChecks + 1 : 0;
    if (t.settledChecks >= 3) {
      if (s.mode == TestMode::Isotropic) {
        t.stage = TestStage::Done;
      } else {
        // Shear: strains count from here.
        t.stage = TestStage::Shear;
        t.initialLength = specimenLengths();
        t.initialVolume = t.initialLength[0] * t.initialLength[1] * t.initialLength[2];
      }
    }
  } else if (t.stage == TestStage::Shear) {
    const double axialStrain = s.mode == TestMode::Tension ? -m.strain[a] : m.strain[a];
    if (axialStrain >= s.maxStrain) {
      t.stage = TestStage::Done;
    }
  }
}

// ---------------------------------------------------------------------------------------
// Stepping

void Simulation::step()
{
  Impl& im = *impl_;
  Particles& p = model_.particles;
  const Domain& d = model_.domain;
  const double dt = timestep_;
  const double half = 0.5 * dt;
  const bool planar = d.section2D;
  const long count = static_cast<long>(p.size());
  const double limit = 0.5 * im.skinDistance; // m, drift that makes the neighbour list stale
  const double limit2 = limit * limit;
  const MinimumImage separationOf(d);
  const std::array<bool, 3> periodic = d.periodic;
  const bool anyPeriodic = periodic[0] || periodic[1] || periodic[2];

  // Half kick with the forces of the last step, then drift; note whether any particle
  // has moved half the skin since the neighbour list was built.
  bool stale = false;
#pragma omp parallel for schedule(static) num_threads(im.threads) if (im.parallel) reduction(|| : stale)
  for (long li = 0; li < count; ++li) {
    const std::size_t i = static_cast<std::size_t>(li);
    // A fixed particle is kinematic: forces do not change its velocity (inverse mass
    // 0), but it moves with the velocity it was given (at rest unless prescribed).
    p.velocity[i] += (half * im.inverseMass[i]) * p.force[i];
    p.angularVelocity[i] += (half * im.inverseInertia[i]) * p.torque[i];
    if (planar) {
      p.velocity[i].z() = 0.0;
      p.angularVelocity[i].x() = 0.0;
      p.angularVelocity[i].y() = 0.0;
    }
    const Vec3 move = dt * p.velocity[i];
    p.position[i] += move;
    p.displacement[i] += move;
    for (int k = 0; anyPeriodic && k < 3; ++k) {
      if (periodic[k]) {
        const double lo = d.origin[k];
        const double length = d.size[k];
        if (p.position[i][k] < lo) {
          p.position[i][k] += length;
        } else if (p.position[i][k] >= lo + length) {
          p.position[i][k] -= length;
        }
      }
    }
    if (separationOf(im.positionAtBuild[i], p.position[i]).squaredNorm() > limit2) {
      stale = true;
    }
  }
  controlWalls();
  for (Wall& wall : model_.walls) {
    wall.position += wall.velocity * dt;
  }

  if (stale) {
    rebuildNeighbours(false);
  } else if (wallsMoved()) {
    rebuildWallContacts(true);
  }
  // New forces, then the second half kick (in the same pass).
  computeForces(true, true);
  model_.clock.step += 1;
  model_.clock.time += dt;
  sampleLoadTest();
}

void Simulation::advance(std::int64_t steps)
{
  if (impl_->broken) {
    throw InstabilityError("This run stopped after an instability; rebuild the solver.");
  }
  if (steps <= 0 || model_.particles.empty() || timestep_ <= 0.0) {
    return;
  }
  // Last good state: restored if this call goes unstable.
  exportContacts();
  const Particles savedParticles = model_.particles;
  const std::vector<Wall> savedWalls = model_.walls;
  const ContactHistory savedContacts = model_.contacts;
  const Bonds savedBonds = model_.bonds;
  const LoadTestState savedTest = model_.test;
  const Clock savedClock = model_.clock;
  try {
    for (std::int64_t s = 0; s < steps; ++s) {
      step();
      if ((model_.clock.step & 63) == 0) {
        checkStability("during the run");
      }
    }
    checkStability("at the end of the batch");
  } catch (const InstabilityError& e) {
    model_.particles = savedParticles;
    model_.walls = savedWalls;
    model_.contacts = savedContacts;
    model_.bonds = savedBonds;
    model_.test = savedTest;
    model_.clock = savedClock;
    impl_->broken = true;
    std::ostringstream msg;
    msg << e.what() << " The run stopped at step " << savedClock.step << " (t = "
        << formatValue(savedClock.time) << " s), the last good state, which is kept.";
    throw InstabilityError(msg.str());
  }
  exportContacts();
}

double Simulation::availableEnergy() const
{
  // Kinetic + elastic energy now, plus the potential energy each particle could release
  // by falling to the lowest wall (or, without walls along gravity, none).
  const Particles& p = model_.particles;
  const Vec3 g = model_.gravity;
  double potential = 0.0;
  const double gNorm = g.norm();
  if (gNorm > 0.0) {
    int axis = 0;
    g.cwiseAbs().maxCoeff(&axis);
    const bool down = g[axis] < 0.0;
    const Wall& floor = model_.walls[axis * 2 + (down ? 0 : 1)];
    if (floor.active) {
      for (std::size_t i = 0; i < p.size(); ++i) {
        potential += p.mass[i] * gNorm * std::abs(p.position[i][axis] - floor.position);
      }
    }
  }
  const double stored = totalEnergy();
  double gravitational = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    gravitational -= p.mass[i] * g.dot(p.position[i]);
  }
  return potential + (stored - gravitational);
}

void Simulation::checkStability(const char* when) const
{
  const Particles& p = model_.particles;
  const Domain& d = model_.domain;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.position[i].allFinite() || !p.velocity[i].allFinite() ||
        !p.angularVelocity[i].allFinite()) {
      throw InstabilityError(std::string("The run went unstable ") + when + ": particle " +
        std::to_string(p.id[i]) + " has a non-finite position or velocity (timestep " +
        formatValue(timestep_) + " s, critical " + formatValue(critical_) + " s).");
    }
  }
  std::size_t escaped = 0;
  std::size_t first = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const bool walled = model_.walls[2 * k].active;
      if (walled && (p.position[i][k] < model_.walls[2 * k].position ||
                     p.position[i][k] > model_.walls[2 * k + 1].position)) {
        if (escaped++ == 0) {
          first = i;
        }
        break;
      }
    }
  }
  if (escaped > 0) {
    const Vec3& x = p.position[first];
    throw InstabilityError(std::string("The run went unstable ") + when + ": " +
      std::to_string(escaped) + " particle(s) escaped the box (particle " +
      std::to_string(p.id[first]) + " at (" + formatValue(x.x()) + ", " + formatValue(x.y()) +
      ", " + formatValue(x.z()) + ") m).");
  }
  (void)d;
  double kinetic = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    kinetic += 0.5 * p.mass[i] * p.velocity[i].squaredNorm() +
      0.5 * p.inertia[i] * p.angularVelocity[i].squaredNorm();
  }
  // Moving walls and platens do work on the specimen: during a test the energy check
  // has a source, so only non-finite values and escapes are checked then.
  const bool testRunning = model_.test.settings.mode != TestMode::Off;
  const double limit = 2.0 * initialAvailableEnergy_ + 1e-300;
  if (!testRunning && kinetic > limit) {
    throw InstabilityError(std::string("The run went unstable ") + when + ": kinetic energy " +
      formatValue(kinetic) + " J exceeds twice the energy available at the start (" +
      formatValue(initialAvailableEnergy_) + " J) with no source of energy (timestep " +
      formatValue(timestep_) + " s, critical " + formatValue(critical_) + " s).");
  }
}

// ---------------------------------------------------------------------------------------
// Diagnostics

Diagnostics Simulation::diagnostics() const
{
  const Impl& im = *impl_;
  const Particles& p = model_.particles;
  Diagnostics out;
  out.time = model_.clock.time;
  out.step = model_.clock.step;
  double displacement2 = 0.0;
  double net = 0.0;
  double contact = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    out.kineticEnergy += 0.5 * p.mass[i] * p.velocity[i].squaredNorm() +
      0.5 * p.inertia[i] * p.angularVelocity[i].squaredNorm();
    displacement2 += p.displacement[i].squaredNorm();
    if (im.inverseMass[i] > 0.0) {
      // A fixed (kinematic) particle's net force is a support reaction, not imbalance.
      net += im.undampedForce[i].norm();
      contact += contactForceMagnitude(i);
    }
  }
  if (!p.empty()) {
    out.rmsDisplacement = std::sqrt(displacement2 / static_cast<double>(p.size()));
  }
  out.unbalancedForceRatio = contact > 0.0 ? net / contact : 0.0;
  for (double fn : im.pairNormal) {
    out.contacts += fn > 0.0 ? 1 : 0;
  }
  for (std::size_t e = 0; e < im.wallNormal.size(); ++e) {
    out.contacts += im.wallTouching[e] && im.wallNormal[e] > 0.0 ? 1 : 0;
  }
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      if (model_.walls[2 * k].active && (p.position[i][k] < model_.walls[2 * k].position ||
                                         p.position[i][k] > model_.walls[2 * k + 1].position)) {
        ++out.escaped;
        break;
      }
    }
  }
  return out;
}

double Simulation::contactForceMagnitude(std::size_t i) const
{
  // Sum of the magnitudes of the forces on particle i, in the gather's order.
  const Impl& im = *impl_;
  double magnitude = 0.0;
  for (std::size_t e = im.adjacencyStart[i]; e < im.adjacencyStart[i + 1]; ++e) {
    const std::size_t k = im.adjacency[e] >> 1;
    if (im.pairNormal[k] != 0.0) {
      magnitude += im.pairForce[k].norm();
    }
  }
  for (std::size_t e = im.wallStart[i]; e < im.wallStart[i + 1]; ++e) {
    if (im.wallTouching[e]) {
      magnitude += im.wallForce[e].norm();
    }
  }
  for (std::size_t e = im.bondAdjacencyStart[i]; e < im.bondAdjacencyStart[i + 1]; ++e) {
    const std::size_t b = im.bondAdjacency[e] >> 1;
    if (!model_.bonds.broken(b)) {
      magnitude += im.bondForce[b].norm();
    }
  }
  return magnitude;
}

double Simulation::totalEnergy() const
{
  const Impl& im = *impl_;
  const Particles& p = model_.particles;
  const Domain& d = model_.domain;
  const ContactModel& cm = contactModel_;
  double energy = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    energy += 0.5 * p.mass[i] * p.velocity[i].squaredNorm() +
      0.5 * p.inertia[i] * p.angularVelocity[i].squaredNorm() -
      p.mass[i] * model_.gravity.dot(p.position[i]);
  }
  auto elastic = [&](const PairProperties& pair, double overlap, const Vec3& spring) {
    if (overlap <= 0.0) {
      return 0.0;
    }
    const double normal = cm.law == ContactLaw::HertzMindlin
      ? 8.0 / 15.0 * pair.effectiveModulus * std::sqrt(pair.effectiveRadius) * std::pow(overlap, 2.5)
      : 0.5 * pair.linearNormalStiffness * overlap * overlap;
    return normal + 0.5 * tangentialStiffness(cm, pair, overlap) * spring.squaredNorm();
  };
  const double inf = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < im.pairI.size(); ++k) {
    const std::size_t i = im.pairI[k];
    const std::size_t j = im.pairJ[k];
    const double overlap =
      p.radius[i] + p.radius[j] - separation(d, p.position[i], p.position[j]).norm();
    const PairProperties pair = pairProperties(cm, p.radius[i], im.inverseMass[i] > 0 ? p.mass[i] : inf,
      p.radius[j], im.inverseMass[j] > 0 ? p.mass[j] : inf, d.section2D, d.slabThickness());
    energy += elastic(pair, overlap, im.pairSpring[k]);
  }
  // Only the particles in the wall list can touch a wall.
  for (std::size_t e = 0; e < im.wallSlot.size(); ++e) {
    const std::size_t i = im.wallSlot[e];
    const Wall& wall = model_.walls[im.wallIndex[e]];
    if (!wall.active) {
      continue;
    }
    const double side = wall.side == 0 ? 1.0 : -1.0;
    const double overlap = p.radius[i] - (p.position[i][wall.axis] - wall.position) * side;
    const PairProperties pair = wallProperties(cm, p.radius[i], p.mass[i], d.section2D, d.slabThickness());
    energy += elastic(pair, overlap, im.wallSpring[e]);
  }
  return energy;
}

void Simulation::exportContacts()
{
  const Impl& im = *impl_;
  const Particles& p = model_.particles;
  const bool rolling = contactModel_.rollingFriction > 0.0;
  struct Entry {
    std::int64_t a, b;
    Vec3 spring, roll;
  };
  std::vector<Entry> entries;
  for (std::size_t k = 0; k < im.pairI.size(); ++k) {
    const Vec3& s = im.pairSpring[k];
    const Vec3 r = rolling ? im.pairRolling[k] : Vec3::Zero();
    if (s.isZero(0.0) && r.isZero(0.0)) {
      continue;
    }
    const std::int64_t idI = p.id[im.pairI[k]];
    const std::int64_t idJ = p.id[im.pairJ[k]];
    // Stored as A's spring relative to B with idA < idB.
    if (idI < idJ) {
      entries.push_back({ idI, idJ, s, r });
    } else {
      entries.push_back({ idJ, idI, -s, -r });
    }
  }
  for (std::size_t e = 0; e < im.wallSlot.size(); ++e) {
    const Vec3& s = im.wallSpring[e];
    const Vec3 r = rolling ? im.wallRolling[e] : Vec3::Zero();
    if (s.isZero(0.0) && r.isZero(0.0)) {
      continue;
    }
    entries.push_back({ p.id[im.wallSlot[e]], wallPartnerId(im.wallIndex[e]), s, r });
  }
  std::sort(entries.begin(), entries.end(),
    [](const Entry& x, const Entry& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
  ContactHistory& h = model_.contacts;
  h.clear();
  for (const Entry& e : entries) {
    h.idA.push_back(e.a);
    h.idB.push_back(e.b);
    h.shearSpring.push_back(e.spring);
    if (rolling) {
      h.rollingSpring.push_back(e.roll);
    }
  }
}

} // namespace dem
