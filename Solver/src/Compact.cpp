// RockDEM engine: Compact Elements, radius expansion with relaxation (see dem/Pack.h).
// SI units: m, Pa.
#include "dem/Pack.h"

#include "dem/Errors.h"
#include "dem/Simulation.h"
#include "dem/SizeClassGrids.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace dem {

namespace {

/// Radius growth of the first stage, and its bounds (relative). A stage that relaxes at
/// once grows the next one by half as much again; one that runs out of steps halves it.
/// Larger stages pack denser: the overlaps a 5 % stage opens push the grains into
/// rearranging, where 2 % stages let them settle into the first jammed state (10,000
/// spheres, walled: porosity 0.377 against 0.383; 10,000 discs 0.166 against 0.173;
/// Benchmarks-Pack.md), and 10 % stages overshoot (0.382).
constexpr double kFirstStageGrowth = 0.05;
constexpr double kMaxStageGrowth = 0.05;
constexpr double kMinStageGrowth = 0.001;
/// A growth stage relaxes until the unbalanced force ratio is below this multiple of the
/// Equilibrium Ratio (0.05 at the default 0.01), or the stress has gone, for at most
/// kStageSteps steps (kFinalSteps when the stage ratio is stricter than the default one).
constexpr double kStageRatioOverEquilibrium = 5.0;
constexpr double kDefaultStageRatio = 0.05;
constexpr std::int64_t kStageSteps = 1000;
/// The final relaxation and each shrinking step: at most this many steps.
constexpr std::int64_t kFinalSteps = 20000;
/// Relaxation of a pack found past the working limit before it is shrunk back.
constexpr std::int64_t kHoldSteps = 1000;
/// Steps between equilibrium checks.
constexpr std::int64_t kCheckSteps = 50;
/// Linear springs: a relaxation counts as equilibrium only once the mean stress, too, has
/// changed by less than this share over kCheckSteps. At the default ceiling a linear pack
/// overlaps 1e-5 to 1e-4 of the radius and sits at the jamming point itself, where it
/// creeps: its stress fell e-fold every 1,000-3,000 steps at an unbalanced force ratio of
/// 0.007-0.016, below 0.01 now and then (200 grains), and a creeping pack read as relaxed at
/// 140 x the ceiling, then had no stress at all 1e-5 smaller in radius.
constexpr double kSteadyStress = 0.01;
/// Steps between quenches.
constexpr std::int64_t kQuenchSteps = 5;
/// FIRE's mixing factor (its alpha at the start, kept fixed).
constexpr double kFireMixing = 0.1;
/// Timestep Safety while compacting: the overlaps stay below a few per cent of the radius,
/// where a Hertz contact is far softer than the Rayleigh limit assumes.
constexpr double kCompactTimestepSafety = 0.5;
/// The same with linear springs: their critical timestep (Simulation.cpp, contactTimestep)
/// is already the bound for a full coordination of wall-stiff springs, sqrt(m / (12 kn_wall))
/// = 1 / omega_max at most, half of the explicit scheme's limit 2 / omega_max, and the smaller
/// rotational bound it takes does not apply to a frictionless pack with its spins zeroed. At
/// 0.5, a linear pack relaxed 4-8 x more slowly per step than a Hertz one (omega dt 0.1
/// against 0.4-0.9 at the same overlaps) and ran out of steps before its stress had settled.
constexpr double kCompactLinearTimestepSafety = 1.0;
/// The exponent n of the relaxed mean stress of a pack compressed past jamming, sigma ~
/// (s - sJ)^n in the radius factor s: its contact forces grow as overlap^n (Hertz 3/2,
/// linear springs 1; PHYSICS.md section 1, Documentation/Physics-Contacts.md).
double stressExponent(ContactLaw law) { return law == ContactLaw::Linear ? 1.0 : 1.5; }
/// Halving the timestep after an instability stops below this safety (the error then stands).
constexpr double kSmallestTimestepSafety = 0.01;
/// Shrinking to the ceiling aims at this fraction of it, and accepts [kLowestShare, 1] of it.
constexpr double kAimShare = 0.8;
constexpr double kLowestShare = 0.5;
constexpr int kShrinkIterations = 8;
/// Stepping down: at most this many steps, each shrinking the radii by at least this
/// much; overlaps are brought below this share of the bar.
constexpr int kStepDownIterations = 40;
constexpr double kSmallestStepDown = 1.0e-4;
constexpr double kOverlapMargin = 0.8;
/// A relaxed stress below this share of the ceiling counts as no stress (unjammed).
constexpr double kStressFloorShare = 0.01;
/// Growth stops once a stage's stress passes this multiple of the ceiling (jammed).
constexpr double kWorkingLimit = 10.0;
/// A pack that relaxes below the ceiling where growth stopped grows on with this share of
/// the last stage growth.
constexpr double kLateGrowthShare = 0.25;

/// Solid volume over the box volume (2D: disc areas over the section), the measure
/// compaction works on: a compacted pack fills the whole box.
double boxSolidFraction(const Model& model)
{
  double solid = 0.0;
  for (double r : model.particles.radius) {
    solid += particleVolume(model.domain, r);
  }
  const Vec3& s = model.domain.size;
  return solid / (s.x() * s.y() * s.z());
}

/// Scales every movable radius by `factor` from the reference radii. Masses follow with
/// density scaling: every grain gets the mass that gives it the contact frequency of the
/// smallest at the same overlap strain (a Hertz contact stiffness grows as r at equal
/// strain, so m proportional to r), so that the large
/// grains relax as fast as the small ones. Equilibrium does not depend on masses; the
/// true masses come back at the end (updateMassProperties).
void setScale(Model& model, const std::vector<double>& reference, double factor)
{
  Particles& p = model.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!(p.flags[i] & FlagFixed)) {
      p.radius[i] = reference[i] * factor;
    }
  }
  updateMassProperties(model);
  const auto smallest = std::min_element(p.radius.begin(), p.radius.end());
  const std::size_t k = static_cast<std::size_t>(smallest - p.radius.begin());
  const double m0 = p.mass[k];
  const double r0 = p.radius[k];
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double r = p.radius[i];
    p.mass[i] = m0 * (r / r0);
    p.inertia[i] = p.mass[i] * p.inertia[k] / m0 * (r * r) / (r0 * r0);
  }
}

/// Drains kinetic energy without slowing the descent: the velocity update of FIRE
/// (Bitzek et al. 2006, PRL 97:170201) at a fixed timestep. While the forces do positive
/// work on the grains (power F.v > 0), the velocities turn towards the forces,
/// v <- (1 - a) v + a |v| F/|F| (norms over all grains); as soon as the power turns
/// negative, every grain stops. Rotation plays no part in a frictionless pack: spins
/// are zeroed.
void quench(Particles& p)
{
  double power = 0.0;
  double vv = 0.0;
  double ff = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    power += p.force[i].dot(p.velocity[i]);
    vv += p.velocity[i].squaredNorm();
    ff += p.force[i].squaredNorm();
  }
  if (!(power > 0.0) || !(ff > 0.0)) {
    for (std::size_t i = 0; i < p.size(); ++i) {
      p.velocity[i].setZero();
      p.angularVelocity[i].setZero();
    }
    return;
  }
  const double steer = kFireMixing * std::sqrt(vv / ff);
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.velocity[i] = (1.0 - kFireMixing) * p.velocity[i] + steer * p.force[i];
    p.angularVelocity[i].setZero();
  }
}

/// State of a relaxation: mean stress (Pa, compression positive), unbalanced force
/// ratio and steps taken.
struct Relaxed {
  double meanStress = 0.0;
  double unbalancedForceRatio = 0.0;
  std::int64_t steps = 0;
  bool equilibrium = false;
};

/// Cycles the frictionless model until it is in equilibrium: the unbalanced force ratio
/// below `ratio`, or the mean stress below `stressFloor` (a pack looser than jamming
/// relaxes to no stress at all, where the ratio means nothing), or `maxSteps` steps.
/// With linear springs the ratio must be met with the mean stress steady, within
/// kSteadyStress of its value kCheckSteps earlier (see kSteadyStress).
Relaxed relax(Model& model, double ratio, double stressFloor, std::int64_t maxSteps)
{
  Relaxed out;
  const bool steady = model.solver.contactLaw == ContactLaw::Linear;
  double previousStress = -1.0;
  model.clock.step = 0;
  model.clock.time = 0.0;
  model.contacts.clear();
  Particles& p = model.particles;
  auto sim = std::make_unique<Simulation>(model);
  while (out.steps < maxSteps) {
    try {
      for (std::int64_t s = 0; s < kCheckSteps; s += kQuenchSteps) {
        sim->advance(kQuenchSteps);
        quench(p);
      }
    } catch (const InstabilityError&) {
      // Overlaps past what the timestep can follow (a stage grew too far past jamming):
      // the model is back at its last good state; go on with half the timestep.
      if (model.solver.timestepSafety < kSmallestTimestepSafety) {
        throw;
      }
      model.solver.timestepSafety *= 0.5;
      model.clock.step = 0;
      model.clock.time = 0.0;
      model.contacts.clear();
      for (std::size_t i = 0; i < p.size(); ++i) {
        p.velocity[i].setZero();
        p.angularVelocity[i].setZero();
      }
      sim = std::make_unique<Simulation>(model);
      continue;
    }
    out.steps += kCheckSteps;
    out.unbalancedForceRatio = sim->diagnostics().unbalancedForceRatio;
    out.meanStress = sim->measurements().meanStress;
    const bool settled =
      !steady || std::abs(out.meanStress - previousStress) <= kSteadyStress * std::abs(out.meanStress);
    previousStress = out.meanStress;
    if ((out.unbalancedForceRatio < ratio && settled) || out.meanStress < stressFloor) {
      out.equilibrium = true;
      break;
    }
  }
  return out;
}

/// Overlaps of a model: the largest over the smaller radius (pairs) or the radius (walls of
/// the box on its non-periodic moving axes), and the mean overlap strain over the
/// overlapping pairs, overlap / (rA + rB).
struct OverlapStatistics {
  double largest = 0.0;
  double meanStrain = 0.0;
  std::size_t pairs = 0;
};

OverlapStatistics overlapStatistics(const Model& model)
{
  OverlapStatistics out;
  const Particles& p = model.particles;
  const Domain& d = model.domain;
  if (p.empty()) {
    return out;
  }
  const auto [smallest, largest] = std::minmax_element(p.radius.begin(), p.radius.end());
  SizeClassGrids grids(d, *smallest, *largest, std::max(SizeClassGrids::kDefaultMaxCellsPerClass, p.size()));
  grids.insertAll(p);
  double strain = 0.0;
  std::vector<std::size_t> keys;
  for (std::size_t i = 0; i < p.size(); ++i) {
    grids.neighboursWithin(p.position[i], p.radius[i], 0.0, i, keys);
    for (std::size_t j : keys) {
      if (j < i) {
        continue; // each pair once
      }
      const double sum = p.radius[i] + p.radius[j];
      const double overlap = sum - grids.separation(p.position[i], p.position[j]).norm();
      out.largest = std::max(out.largest, overlap / std::min(p.radius[i], p.radius[j]));
      if (overlap > 0.0) {
        strain += overlap / sum;
        ++out.pairs;
      }
    }
    for (int a = 0; a < d.dimension(); ++a) {
      if (!d.periodic[a]) {
        const double gap = std::min(p.position[i][a] - d.origin[a], d.upper()[a] - p.position[i][a]);
        out.largest = std::max(out.largest, (p.radius[i] - gap) / p.radius[i]);
      }
    }
  }
  out.meanStrain = out.pairs ? strain / static_cast<double>(out.pairs) : 0.0;
  return out;
}

} // namespace

void validate(const CompactParameters& params)
{
  requireInOpenRange("Target Porosity", params.targetPorosity, 0.0, 1.0);
  requireNonNegative("Maximum Locked-In Stress", params.stressCeiling, "Pa");
  requireInRange("Equilibrium Ratio", params.equilibriumRatio, 1e-6, 0.5);
}

double defaultStressCeiling(const Material& material)
{
  return kDefaultCeilingOverModulus * material.youngsModulus;
}

double largestOverlap(const Model& model)
{
  return overlapStatistics(model).largest;
}

CompactReport compactElements(Model& model, const CompactParameters& params)
{
  validate(params);
  validate(model.domain);
  validate(model.material);
  validate(model.particles);
  if (model.bonds.size() > 0) {
    throw InputError("Compact Elements works on an uncemented pack, but this model has " +
                     std::to_string(model.bonds.size()) + " bonds: compact before cementing.");
  }
  CompactReport report;
  report.particles = model.particles.size();
  report.targetPorosity = params.targetPorosity;
  report.porosityBefore = currentPorosity(model);
  report.stressCeiling =
    params.stressCeiling > 0.0 ? params.stressCeiling : defaultStressCeiling(model.material);
  if (model.particles.empty()) {
    report.porosity = report.porosityBefore;
    return report;
  }

  // The relaxation steps the particles in a space-filling order (neighbours in space near
  // each other in memory: 40 % less CPU time on a 20k pack than in placement order,
  // Documentation/Benchmarks-Pack.md); the users' order comes back at the end, whatever
  // happens.
  struct SpatialOrder {
    Particles& particles;
    std::vector<std::size_t> order;
    void restore()
    {
      std::vector<std::size_t> back(order.size());
      for (std::size_t s = 0; s < order.size(); ++s) {
        back[order[s]] = s;
      }
      permuteParticles(particles, back);
      order.clear();
    }
    ~SpatialOrder()
    {
      if (!order.empty()) {
        restore();
      }
    }
  } spatial{ model.particles, spatialOrder(model) };
  permuteParticles(model.particles, spatial.order);

  // The relaxation runs frictionless, without gravity, in the closed box, from rest.
  const Material material = model.material;
  const Vec3 gravity = model.gravity;
  const SolverSettings solver = model.solver;
  const LoadTestState test = model.test;
  const Clock clock = model.clock;
  const std::vector<Wall> walls = model.walls;
  model.material.friction = 0.0;
  model.material.rollingFriction = 0.0;
  model.gravity.setZero();
  model.solver.settlingDamping = kCompactDamping;
  model.solver.timestepSafety =
    model.solver.contactLaw == ContactLaw::Linear ? kCompactLinearTimestepSafety : kCompactTimestepSafety;
  model.solver.requestedTimestep = 0.0;
  model.test = LoadTestState();
  resetWalls(model);

  const ContactLaw law = model.solver.contactLaw;
  const double dimension = model.domain.dimension();
  const std::vector<double> reference = model.particles.radius;
  const double startFraction = boxSolidFraction(model);
  // The radius factor that puts the solid fraction of the box at the target.
  const double targetScale = std::pow((1.0 - params.targetPorosity) / startFraction, 1.0 / dimension);
  const double ceiling = report.stressCeiling;
  const double floor = kStressFloorShare * ceiling;

  // 1. Growth, stage by stage, up to the target or until the pack is jammed: its stress,
  // relaxed as far as a stage relaxes, past the working limit (kWorkingLimit x ceiling).
  // 2. Equilibrium where growth stopped; if the stress relaxes below the ceiling there,
  // the pack was not jammed yet: grow on, more gently.
  const double stageRatio = kStageRatioOverEquilibrium * params.equilibriumRatio;
  const std::int64_t stageSteps = stageRatio < kDefaultStageRatio ? kFinalSteps : kStageSteps;
  double scale = 1.0;
  double growth = kFirstStageGrowth;
  setScale(model, reference, scale);
  Relaxed state = relax(model, stageRatio, floor, stageSteps);
  report.steps += state.steps;
  for (;;) {
    while (scale < targetScale && state.meanStress <= kWorkingLimit * ceiling) {
      scale = std::min(targetScale, scale * (1.0 + growth));
      setScale(model, reference, scale);
      state = relax(model, stageRatio, floor, stageSteps);
      report.steps += state.steps;
      ++report.stages;
      if (state.steps <= kCheckSteps) {
        growth = std::min(kMaxStageGrowth, 1.5 * growth);
      } else if (!state.equilibrium) {
        growth = std::max(kMinStageGrowth, 0.5 * growth);
      }
    }
    // A Hertz pack past the working limit is held for kHoldSteps only (it is jammed; the
    // shrinking relaxes it). A linear one is relaxed in full: at equal overlaps its springs
    // carry 25-60 x the force of a Hertz contact at 0.3-1.5 % of the radius (kn = pi r E / 2),
    // so the residue of an unrelaxed growth stage passes the working limit long before the
    // pack jams; held 1,000 steps it still read 265 x the ceiling, and the shrinking that
    // started from that reading never came back up to jamming (200-2,000 grains ended at
    // porosity 0.41-0.46 with almost no stress, or a grain pushed past a wall).
    const bool overcompressed = state.meanStress > kWorkingLimit * ceiling;
    const bool hold = overcompressed && law != ContactLaw::Linear;
    state = relax(model, params.equilibriumRatio, floor, hold ? kHoldSteps : kFinalSteps);
    report.steps += state.steps;
    if (state.meanStress > ceiling || scale >= targetScale) {
      break;
    }
    growth = std::max(kMinStageGrowth, kLateGrowthShare * growth);
  }

  // 3. Jammed above the ceiling: shrink the radii back to it. A pack compressed past
  // jamming carries sigma ~ (s - sJ)^n, n = 3/2 for Hertz contacts and 1 for linear springs
  // (stressExponent); the mean overlap strain estimates s - sJ, and two relaxed points then
  // give the secant in sigma^(1/n). The factors tried stay inside the bracket the relaxed
  // points give: below the smallest one found above the ceiling, above the largest one found
  // below the window (bisection where the secant would leave it).
  if (state.meanStress > ceiling) {
    report.jammed = true;
    const double power = 1.0 / stressExponent(law);
    double sHigh = scale;
    double yHigh = std::pow(state.meanStress, power);
    double jammingScale = scale * (1.0 - overlapStatistics(model).meanStrain);
    double above = scale; // smallest factor found above the ceiling
    double below = 0.0;   // largest factor found below kLowestShare x the ceiling (0: none yet)
    const double aim = std::pow(kAimShare * ceiling, power);
    // A linear pack that creeps below the window is a point below it (bisection needs no
    // more): its relaxation stops there instead of creeping on to the floor (up to 20,000
    // steps).
    const double shrinkFloor = law == ContactLaw::Linear ? kLowestShare * ceiling : floor;
    bool bisect = false;
    for (int k = 0; k < kShrinkIterations; ++k) {
      // sigma^(1/n) is linear in s between jamming (0) and (sHigh, yHigh).
      double next = jammingScale + (sHigh - jammingScale) * aim / yHigh;
      if (bisect || !(next < above && next > below)) {
        next = below > 0.0 ? 0.5 * (below + above) : 0.5 * (std::max(jammingScale, 0.0) + above);
      }
      scale = next;
      setScale(model, reference, scale);
      state = relax(model, params.equilibriumRatio, shrinkFloor, kFinalSteps);
      report.steps += state.steps;
      ++report.stages;
      if (state.meanStress <= ceiling && state.meanStress >= kLowestShare * ceiling) {
        break;
      }
      if (state.meanStress > ceiling) {
        above = std::min(above, scale);
      } else {
        below = std::max(below, scale);
      }
      // A relaxation that stopped at the stress floor found no stress (relax): the pack is
      // below jamming there, whatever stress was left when it stopped. (Read as a stress,
      // it made the secant extrapolate up, 20 x the bracket: the radii grew past the box,
      // and a grain's centre lay beyond a wall before the first step, InstabilityError.)
      const double y =
        state.meanStress < shrinkFloor ? 0.0 : std::pow(std::max(state.meanStress, 0.0), power);
      if (state.meanStress > ceiling || y > 0.0) {
        // A new point of the line through it and the previous one.
        const double slope = (yHigh - y) / (sHigh - scale);
        if (slope > 0.0) {
          jammingScale = scale - y / slope;
        }
        sHigh = scale;
        yHigh = y;
        bisect = false;
      } else {
        // Below jamming (no stress): jamming lies between here and the last point. The
        // secant from there would creep up from this point in steps of aim / yHigh of the
        // bracket (1e-3 for a linear pack 1,000 x past its ceiling): bisect instead.
        jammingScale = scale;
        bisect = true;
      }
    }
  }
  // 4. Within the ceiling, but overlaps past the bar (a ceiling set high): and in any case
  // until the ceiling holds, step down by a quarter of the mean overlap strain.
  for (int k = 0; k < kStepDownIterations &&
                  (state.meanStress > ceiling || overlapStatistics(model).largest > kOverlapMargin * kOverlapBar);
       ++k) {
    scale *= 1.0 - std::max(kSmallestStepDown, 0.25 * overlapStatistics(model).meanStrain);
    setScale(model, reference, scale);
    state = relax(model, params.equilibriumRatio, floor, kFinalSteps);
    report.steps += state.steps;
    ++report.stages;
  }

  report.lockedInStress = state.meanStress;
  report.unbalancedForceRatio = state.unbalancedForceRatio;

  // A fresh pack in the users' order: at rest, never stepped, their material and settings back.
  spatial.restore();
  model.material = material;
  model.gravity = gravity;
  model.solver = solver;
  model.test = test;
  model.clock = clock;
  model.walls = walls;
  model.contacts.clear();
  Particles& p = model.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.displacement[i].setZero();
    p.velocity[i].setZero();
    p.angularVelocity[i].setZero();
    p.force[i].setZero();
    p.torque[i].setZero();
  }
  updateMassProperties(model);
  report.porosity = currentPorosity(model);
  report.largestOverlap = largestOverlap(model);
  // The target is a solid fraction of the box (growth stops there); Current Porosity counts
  // the volume overlapping pairs share once, so it lies above by that shared volume.
  report.targetReached = 1.0 - boxSolidFraction(model) <= params.targetPorosity + 1e-9;
  return report;
}

} // namespace dem
