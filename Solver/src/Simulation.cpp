#include "dem/Simulation.h"
#include "dem/StrainRateAdvice.h"

#include "SlotLookup.h"
#include "backends/ContactState.h"
#include "backends/cpu/CpuBackend.h"
#include "backends/vulkan/VulkanBackend.h"
#include "dem/BondLaw.h"
#include "dem/Bonds.h"
#include "dem/Errors.h"
#include "dem/ParticleStress.h"
#include "dem/Overlaps.h"
#include "dem/Membrane.h"
#include "dem/WallControl.h"

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

/// Processors this process may run on.
int processorCount()
{
#ifdef _OPENMP
  return omp_get_num_procs();
#else
  return 1;
#endif
}

/// Threads beyond a few per processor only add overhead, and thousands can exhaust the
/// machine (a failed thread start aborts the process): Threads is bounded by 4 x the
/// processors (at least 4, so the thread-independence checks run anywhere).
void validateThreadsForThisMachine(int threads)
{
  const int most = std::max(4, 4 * processorCount());
  if (threads > most) {
    throw InputError("Threads = " + std::to_string(threads) + " is out of range on this machine: valid range is 0 " +
                     "(all " + std::to_string(processorCount()) + " processors) to " + std::to_string(most) +
                     " (4 per processor). Results never depend on the number of threads.");
  }
}

/// Work done by gravity (J) along the periodic axes on the particles that move under forces,
/// measured from their accumulated displacements (which do not wrap). On a periodic axis the
/// height is unbounded, so this work is the energy source of a falling periodic column.
double periodicGravityWork(const Model& model)
{
  const Domain& d = model.domain;
  Vec3 g = Vec3::Zero();
  for (int k = 0; k < 3; ++k) {
    g[k] = d.periodic[k] ? model.gravity[k] : 0.0;
  }
  if (g.isZero(0.0)) {
    return 0.0;
  }
  const Particles& p = model.particles;
  double work = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if ((p.flags[i] & (FlagFixed | FlagAttachedLow | FlagAttachedHigh)) == 0) {
      work += p.mass[i] * g.dot(p.displacement[i]);
    }
  }
  return work;
}

/// Sum of -m g.x over the particles, J, gravity's components along non-periodic axes only
/// (along a periodic axis the positions wrap; periodicGravityWork counts those).
double gravityPotential(const Model& model)
{
  Vec3 g = model.gravity;
  for (int k = 0; k < 3; ++k) {
    g[k] = model.domain.periodic[k] ? 0.0 : g[k];
  }
  const Particles& p = model.particles;
  double potential = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    potential -= p.mass[i] * g.dot(p.position[i]);
  }
  return potential;
}

/// The gravitational potential energy in totalEnergy, J: the sum of -m g.x over the particles.
double gravitationalEnergy(const Model& model)
{
  const Particles& p = model.particles;
  double energy = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    energy -= p.mass[i] * model.gravity.dot(p.position[i]);
  }
  return energy;
}

/// Whether a per-particle driver does work on the specimen: the membrane's pushes, or in a
/// tension test the grains attached to the moving platen.
bool particleDrivers(const Model& model)
{
  return membraneActive(model) || model.test.settings.mode == TestMode::Tension;
}

/// The force (N) each particle's driver exerts on the specimen (zero for the others): the
/// membrane's push on a surface grain; a grain attached to the moving tension platen pushes
/// the specimen back with minus the contact and bond forces it receives.
void drivenForces(const Model& model, const ContactState& im, std::vector<Vec3>& out)
{
  const Particles& p = model.particles;
  out.assign(p.size(), Vec3::Zero());
  if (im.externalForce.size() == p.size()) {
    for (std::size_t i = 0; i < p.size(); ++i) {
      out[i] = im.externalForce[i];
    }
  }
  if (model.test.settings.mode == TestMode::Tension && im.undampedForce.size() == p.size()) {
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.flags[i] & FlagAttachedHigh) {
        out[i] -= im.undampedForce[i] - p.mass[i] * model.gravity;
      }
    }
  }
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

Simulation::Simulation(Model& model, SolverDevice device)
  : model_(model)
{
  validate(model.domain);
  validate(model.material);
  validate(model.solver);
  validateThreadsForThisMachine(model.solver.threads);
  requireDistinctCentres(model.domain, model.particles);
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
  validatePlatenSpeed(model, timestep_);
  model.clock.timestep = timestep_;

  if (device == SolverDevice::GPU && model.test.settings.confinement == Confinement::Membrane &&
      model.test.stage != TestStage::Idle) {
    throw InputError("Confinement = Membrane runs on the CPU backend only (the GPU solver has no membrane "
                     "forces); turn GPU Solver off, or use Confinement = Rigid Walls on the GPU.");
  }
  if (device == SolverDevice::GPU) {
    try {
      backend_.reset(new VulkanBackend(model, contactModel_, timestep_));
    } catch (const vk::Unavailable& e) {
      gpuFallbackReason_ = e.what();
    }
  }
  if (!backend_) {
    backend_.reset(new CpuBackend(model, contactModel_, timestep_));
  }
  initialAvailableEnergy_ = availableEnergy();
  gravityWorkAtStart_ = periodicGravityWork(model);
  gravityPotentialAtStart_ = gravityPotential(model);
  startStep_ = model.clock.step;
  earlyChecks_ = model.test.settings.mode != TestMode::Off;
  if (earlyChecks_) {
    // The early checks' balance counts what the steps dissipate (dissipatedEnergy).
    backend_->countDissipation(true);
    countingDissipation_ = true;
  }
  for (std::size_t w = 0; w < model.walls.size() && w < 6; ++w) {
    lastWallPosition_[w] = model.walls[w].position;
    lastWallForce_[w] = model.walls[w].force[model.walls[w].axis];
  }
  if (particleDrivers(model) && !model.particles.empty()) {
    drivenForces(model, backend_->sync(), lastMembraneForce_);
    lastMembranePosition_ = model.particles.position;
  }
}

Simulation::~Simulation() = default;

std::string gpuUnavailableReason()
{
  try {
    vk::Device::open();
  } catch (const vk::Unavailable& e) {
    return e.what();
  }
  return std::string();
}

std::string Simulation::path() const
{
  if (!gpuFallbackReason_.empty()) {
    return backend_->path() + ": GPU requested, fell back because " + gpuFallbackReason_;
  }
  return backend_->path();
}

// ---------------------------------------------------------------------------------------
// The virtual press

TestMeasurements Simulation::measurements() const
{
  const ContactState& im = backend_->sync();
  const Particles& p = model_.particles;
  const Domain& d = model_.domain;
  const LoadTestState& t = model_.test;
  const LoadTestSettings& s = t.settings;
  const bool planar = d.section2D;
  TestMeasurements m;
  const std::array<double, 3> length = specimenLengths(model_);
  // A membrane cylinder: its cross-section is the membrane's pi R^2. Otherwise the
  // specimen's outline (a box, or a cylinder carved by DEM Specimen: pi/4 of the product
  // of its two lateral lengths across its axis).
  const MembraneSurface membrane = membraneSurface(model_);
  const bool membraneOn = membrane.crossSection > 0.0;
  const double volume = membraneOn ? membrane.crossSection * length[s.axis] : specimenVolume(d, length);
  for (int k = 0; k < 3; ++k) {
    const double l0 = t.initialLength[k] > 0.0 ? t.initialLength[k] : d.size[k];
    m.strain[k] = (planar && k == 2) ? 0.0 : (l0 - length[k]) / l0;
  }
  const auto axis = static_cast<std::size_t>(std::clamp(s.axis, 0, 2));
  if (t.initialSpread[axis] > 0.0 && s.mode != TestMode::Off && !p.empty()) {
    m.gaugeStrain = 1.0 - centreSpread(p, s.axis) / t.initialSpread[axis];
  }
  const double v0 = t.initialVolume > 0.0 ? t.initialVolume
                                           : d.size.x() * d.size.y() * d.size.z();
  m.volumetricStrain = 1.0 - length[0] * length[1] * length[2] / v0; // a cylinder: (D/D0)^2 L/L0 as well
  // Face stresses from the wall reactions over the current face areas.
  for (int w = 0; w < 6; ++w) {
    const Wall& wall = model_.walls[w];
    const double area = membraneOn && wall.axis == s.axis ? membrane.crossSection
                                                          : crossSectionArea(d, length, wall.axis);
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
    const Vec3 branch = minimumImage(d, p.position[i], p.position[j]);
    sum += branch * im.pairResult[k].force.transpose(); // arms add up to the branch
  }
  for (std::size_t k = 0; k < im.bondI.size(); ++k) {
    if (model_.bonds.broken(k)) {
      continue;
    }
    const Vec3 branch = minimumImage(d, p.position[im.bondI[k]], p.position[im.bondJ[k]]);
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
  if (im.externalForce.size() == p.size()) {
    // The membrane pushes each surface grain at its outer surface: the arm runs from the
    // centre outwards by the radius, against the (inward) force.
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double f = im.externalForce[i].norm();
      if (f > 0.0) {
        const Vec3 arm = -(p.radius[i] / f) * im.externalForce[i];
        sum += arm * im.externalForce[i].transpose();
      }
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
    const double area = crossSectionArea(d, length, a);
    m.axialStress = area > 0.0 ? pull / area : 0.0; // negative in tension
  } else if (s.mode == TestMode::Brazilian) {
    // The disc's Brazilian stress 2 P / (pi D t), P the mean push of the two platens.
    const double load = -0.5 * (model_.walls[2 * a].force.dot(model_.walls[2 * a].normal()) +
                                model_.walls[2 * a + 1].force.dot(model_.walls[2 * a + 1].normal()));
    const std::array<double, 2> disc = brazilianDisc(model_);
    m.axialStress = brazilianStress(load, disc[0], disc[1]);
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
  if (membraneOn) {
    // The membrane: its forces summed over the lateral surface, over that surface's area.
    m.lateralStress = membrane.force / membrane.lateralArea;
  }
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
  m.suggestedStrainRate = suggestedStrainRate(model_, pressure);
  return m;
}

InteractionForces Simulation::interactionForces() const { return interactionForces(backend_->sync()); }

InteractionForces Simulation::freshInteractionForces()
{
  // After an instability the model holds the last good state, the backend the state it
  // stopped in: then from a copy of the model.
  InteractionForces out;
  if (!broken_ && backend_->evaluateFresh([&](const ContactState& state) { out = interactionForces(state); })) {
    return out;
  }
  backend_->sync();
  return dem::freshInteractionForces(model_);
}

InteractionForces freshInteractionForces(const Model& model)
{
  Model copy = model; // the Simulation may set up walls and the timestep on its model
  const Simulation fresh(copy);
  return fresh.interactionForces();
}

OverlapReport Simulation::overlaps()
{
  // After an instability the lists are those of the state the run stopped in; a list not
  // sorted by (i, j) would sum in another order: then the search.
  if (!broken_) {
    const ContactState& im = backend_->sync();
    OverlapReport report;
    if (measureOverlaps(model_, im.pairI, im.pairJ, report)) {
      return report;
    }
  }
  return measureOverlaps(model_);
}

InteractionForces Simulation::interactionForces(const ContactState& im) const
{
  const Particles& p = model_.particles;
  const Domain& d = model_.domain;
  InteractionForces out;
  for (std::size_t k = 0; k < im.pairI.size(); ++k) {
    if (im.pairNormal[k] != 0.0) {
      const std::uint32_t i = im.pairI[k];
      const std::uint32_t j = im.pairJ[k];
      const Vec3 branch = minimumImage(d, p.position[i], p.position[j]);
      const double distance = branch.norm();
      const double overlap = p.radius[i] + p.radius[j] - distance;
      const Vec3 armI = (p.radius[i] - 0.5 * overlap) / distance * branch; // as the CPU backend's contact loop
      out.append(i, j, im.pairResult[k].force, armI, armI - branch);
    }
  }
  for (std::size_t k = 0; k < im.bondI.size(); ++k) {
    if (!model_.bonds.broken(k)) {
      const std::uint32_t i = im.bondI[k];
      const std::uint32_t j = im.bondJ[k];
      const Vec3 branch = minimumImage(d, p.position[i], p.position[j]);
      const Vec3 armI = p.radius[i] / (p.radius[i] + p.radius[j]) * branch; // as the CPU backend's bond loop
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

std::int64_t Simulation::stepsToNextSample() const
{
  const LoadTestState& t = model_.test;
  const LoadTestSettings& s = t.settings;
  if (s.mode == TestMode::Off || t.stage == TestStage::Done) {
    return std::numeric_limits<std::int64_t>::max();
  }
  return std::max<std::int64_t>(1, s.sampleInterval - t.stepsSinceSample);
}

void Simulation::sampleLoadTest(std::int64_t steps)
{
  LoadTestState& t = model_.test;
  const LoadTestSettings& s = t.settings;
  if (s.mode == TestMode::Off || t.stage == TestStage::Done) {
    return;
  }
  t.stepsSinceSample += steps;
  if (t.stepsSinceSample < s.sampleInterval) {
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
  row[c++] = m.gaugeStrain;
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
        t.initialLength = specimenLengths(model_);
        t.initialVolume = t.initialLength[0] * t.initialLength[1] * t.initialLength[2];
        if (t.initialSpread[static_cast<std::size_t>(a)] > 0.0) { // the Gauge Strain's reference
          t.initialSpread[static_cast<std::size_t>(a)] = centreSpread(model_.particles, a);
        }
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

void Simulation::advance(std::int64_t steps)
{
  if (broken_) {
    throw InstabilityError("This run stopped after an instability; rebuild the solver.");
  }
  if (steps <= 0 || model_.particles.empty() || timestep_ <= 0.0) {
    return;
  }
  // Last good state: restored if this call goes unstable. The model's contacts are the
  // backend's unless a step ran since the last export; the copies go into kept buffers
  // (the same sizes from one call to the next: no allocation, no fresh pages to fault in).
  if (!contactsExported_) {
    exportContacts();
  }
  saved_.particles = model_.particles;
  saved_.walls = model_.walls;
  saved_.contacts = model_.contacts;
  saved_.bonds.save(model_.bonds); // what stepping changes (the rest stays as it is)
  saved_.test = model_.test;
  const Clock savedClock = model_.clock;
  try {
    std::int64_t done = 0;
    while (done < steps) {
      // The backend runs up to the next history row or stability check (every 64 steps),
      // where the driver looks at the state; the test's stage stays as it is until then.
      // A timestep above the stability limit shows in its first steps (the unstable mode grows
      // from the first step; a cemented specimen can break its bonds and calm down again within
      // 50): the first checks of a Simulation come 1, 2, 4, ..., 32 steps after its start.
      std::int64_t chunk = std::min<std::int64_t>(steps - done, 64 - (model_.clock.step & 63));
      chunk = std::min(chunk, stepsToNextSample());
      const std::int64_t since = model_.clock.step - startStep_;
      if (earlyChecks_ && since >= 0 && since < 32) {
        std::int64_t next = 1;
        while (next <= since) {
          next *= 2;
        }
        chunk = std::min(chunk, next - since);
      }
      contactsExported_ = false;
      backend_->run(chunk);
      done += chunk;
      sampleLoadTest(chunk);
      const std::int64_t after = model_.clock.step - startStep_;
      if ((model_.clock.step & 63) == 0 || (earlyChecks_ && after > 0 && after <= 32 && (after & (after - 1)) == 0)) {
        checkStability("during the run");
      }
      if (countingDissipation_ && after >= 32) {
        backend_->countDissipation(false); // the early checks are done
        countingDissipation_ = false;
      }
    }
    checkStability("at the end of the batch");
  } catch (const InstabilityError& e) {
    model_.particles = saved_.particles;
    model_.walls = saved_.walls;
    model_.contacts = saved_.contacts;
    saved_.bonds.restore(model_.bonds);
    model_.test = saved_.test;
    model_.clock = savedClock;
    broken_ = true;
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
  return potential + (totalEnergy() - gravitationalEnergy(model_));
}

void Simulation::accumulateWork(const StabilityReport& report)
{
  // Work on the specimen since the last check, trapezoid rule: a wall pushes the particles
  // with minus its reaction F (axis component), so moving by dx it does -(F0 + F1) / 2 dx.
  for (std::size_t w = 0; w < 6; ++w) {
    const double dx = report.wallPosition[w] - lastWallPosition_[w];
    boundaryWork_ -= 0.5 * (lastWallForce_[w] + report.wallForce[w]) * dx;
    lastWallPosition_[w] = report.wallPosition[w];
    lastWallForce_[w] = report.wallForce[w];
  }
  if (particleDrivers(model_)) {
    // The membrane and the tension platen act on single grains: the same rule per grain.
    // (The membrane runs on the CPU only; a tension test on the GPU downloads its state here.)
    std::vector<Vec3> force;
    drivenForces(model_, backend_->sync(), force);
    const Particles& p = model_.particles;
    if (lastMembranePosition_.size() == p.size() && lastMembraneForce_.size() == p.size()) {
      for (std::size_t i = 0; i < p.size(); ++i) {
        if (!force[i].isZero(0.0) || !lastMembraneForce_[i].isZero(0.0)) {
          boundaryWork_ += 0.5 * (lastMembraneForce_[i] + force[i]).dot(p.position[i] - lastMembranePosition_[i]);
        }
      }
    }
    lastMembranePosition_ = p.position; // (a driver that starts here counts from here)
    lastMembraneForce_.swap(force);
  }
}

std::string Simulation::timestepAdvice() const
{
  const double safety = critical_ > 0.0 ? timestep_ / critical_ : 0.0;
  return "The timestep " + formatValue(timestep_) + " s is " + formatValue(safety) + " x the critical timestep " +
    formatValue(critical_) + " s (Timestep Safety " + formatValue(safety) +
    "): lower Timestep Safety (default 0.1, at most 1; cemented specimens went unstable from " +
    formatValue(CementedUnstableTimestepSafety) +
    " x the critical timestep, Documentation/SpeedAccuracy.md \"Stability map\").";
}

void Simulation::checkStability(const char* when)
{
  const StabilityReport report = backend_->stability();
  if (report.firstNonFinite >= 0 || report.escaped > 0) {
    backend_->sync(); // the message names the particle
  }
  const Particles& p = model_.particles;
  if (report.firstNonFinite >= 0) {
    const std::size_t i = static_cast<std::size_t>(report.firstNonFinite);
    throw InstabilityError(std::string("The run went unstable ") + when + ": particle " +
      std::to_string(p.id[i]) + " has a non-finite position or velocity (timestep " +
      formatValue(timestep_) + " s, critical " + formatValue(critical_) + " s).");
  }
  if (report.escaped > 0) {
    const Vec3& x = p.position[static_cast<std::size_t>(report.firstEscaped)];
    throw InstabilityError(std::string("The run went unstable ") + when + ": " +
      std::to_string(report.escaped) + " particle(s) escaped the box (particle " +
      std::to_string(p.id[static_cast<std::size_t>(report.firstEscaped)]) + " at (" +
      formatValue(x.x()) + ", " + formatValue(x.y()) + ", " + formatValue(x.z()) + ") m).");
  }
  // The energy check (Documentation/SpeedAccuracy.md, "The energy check"): with no
  // dissipation, kinetic + stored energy now = the energy at the start + the work the
  // walls, platens and membrane did + the work gravity did; damping, friction and breaking
  // bonds only remove energy. So the kinetic energy can never exceed that sum, and more
  // than EnergyCheckFactor times it is energy the integrator made: an instability.
  accumulateWork(report);
  // In the first checks of a Simulation (1, 2, 4, ..., 32 steps after its start: a timestep
  // above the stability limit shows there) the elastic energy counts too: the same bound
  // holds for kinetic + elastic energy, and it is sharper (a cemented specimen can turn its
  // instability into broken bonds with little kinetic energy left). It needs the contact
  // state, so only there (a GPU run downloads it six times per Simulation).
  const std::int64_t since = model_.clock.step - startStep_;
  const bool early = earlyChecks_ && since > 0 && since <= 32 && (since & (since - 1)) == 0;
  double measured = report.kineticEnergy;
  double dissipated = 0.0;
  if (early) {
    // ... and what damping and breaking bonds took out since the start: K + U + D + B is
    // bounded too, and much sharper where damping hides the burst (a cemented specimen at 2
    // x the critical timestep with stiff bonds: K + U 1.19 x the sources, K + U + D + B 2.9
    // x; SpeedAccuracy.md, "The energy check").
    dissipated = dissipatedEnergy();
    measured = totalEnergy() - gravitationalEnergy(model_) + dissipated;
  }
  const double sources = initialAvailableEnergy_ + std::max(0.0, boundaryWork_);
  if (measured <= EnergyCheckFactor * sources + 1e-300) {
    return;
  }
  // Gravity's work since the start. The positions live in the backend: bring them to the
  // Model first (only here, when the check would otherwise fail, so a GPU run does not
  // download them every check). Along a periodic axis a falling column has no floor, so the
  // displacements count; along the others the positions (the floor potential in
  // initialAvailableEnergy_ already covers a fall onto the floor where it started).
  backend_->sync();
  const double gravityWork = std::max(0.0, periodicGravityWork(model_) - gravityWorkAtStart_) +
    std::max(0.0, gravityPotentialAtStart_ - gravityPotential(model_));
  const double limit = EnergyCheckFactor * (sources + gravityWork) + 1e-300;
  if (measured > limit) {
    throw InstabilityError(std::string("The run went unstable ") + when + ": " +
      (early ? "kinetic + elastic + dissipated energy " + formatValue(measured) + " J (of which " + formatValue(dissipated) +
       " J taken by damping and broken bonds)" : "kinetic energy " + formatValue(measured) + " J") + " exceeds " +
      formatValue(EnergyCheckFactor) +
      " x the energy available (" + formatValue(initialAvailableEnergy_) + " J stored and kinetic at the start + " +
      formatValue(std::max(0.0, boundaryWork_)) + " J of work by the walls, platens and membrane + " +
      formatValue(gravityWork) + " J of work by gravity), which no physics can give. " + timestepAdvice());
  }
}

// ---------------------------------------------------------------------------------------
// Diagnostics

Diagnostics Simulation::diagnostics() const
{
  const ContactState& im = backend_->sync();
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
      contact += contactForceMagnitude(im, i);
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
    out.escaped += beyondActiveWalls(model_.walls, p.position[i]) ? 1 : 0;
  }
  return out;
}

double Simulation::contactForceMagnitude(const ContactState& im, std::size_t i) const
{
  // Sum of the magnitudes of the forces on particle i, in the gather's order.
  double magnitude = 0.0;
  for (std::size_t e = im.adjacencyStart[i]; e < im.adjacencyStart[i + 1]; ++e) {
    const std::size_t k = im.adjacency[e] >> 1;
    if (im.pairNormal[k] != 0.0) {
      magnitude += im.pairResult[k].force.norm();
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
  const ContactState& im = backend_->sync();
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
      p.radius[i] + p.radius[j] - minimumImage(d, p.position[i], p.position[j]).norm();
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
  // The intact bonds' springs (bondStoredEnergy); a softened bond applies (1 - D) of its
  // elastic forces.
  const Bonds& b = model_.bonds;
  for (std::size_t k = 0; k < b.size(); ++k) {
    if (b.broken(k)) {
      continue;
    }
    const BondSection sec = bondSection(b.radius[k], d.section2D, d.slabThickness());
    energy += b.intactShare(k) * bondStoredEnergy(sec, b.normalStiffness[k], b.shearStiffness[k], b.normalForce[k],
                                                  b.shearForce[k], b.twistingMoment[k], b.bendingMoment[k]);
  }
  return energy;
}

double Simulation::dissipatedEnergy() const
{
  if (!countingDissipation_) {
    return 0.0;
  }
  // In slot and bond order, on the host: the same sum whichever backend stepped.
  const ContactState& im = backend_->sync();
  double dissipated = 0.0;
  for (const double w : im.dampingWork) {
    dissipated += w;
  }
  for (const double e : im.breakEnergy) {
    dissipated += e;
  }
  return dissipated;
}

void Simulation::exportContacts()
{
  const ContactState& im = backend_->sync();
  const Particles& p = model_.particles;
  const bool rolling = contactModel_.rollingFriction > 0.0;
  struct Entry {
    std::int64_t a, b;
    Vec3 spring, roll;
  };
  const auto before = [](const Entry& x, const Entry& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; };
  // The keys (idA, idB) are unique, so any sort gives the same rows. The pairs come in
  // slot order, which is id order when the ids rise with the slots (the common case: then
  // no sort); the wall entries are sorted on their own and merged in.
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
  if (!std::is_sorted(entries.begin(), entries.end(), before)) {
    std::sort(entries.begin(), entries.end(), before);
  }
  const std::size_t pairEntries = entries.size();
  for (std::size_t e = 0; e < im.wallSlot.size(); ++e) {
    const Vec3& s = im.wallSpring[e];
    const Vec3 r = rolling ? im.wallRolling[e] : Vec3::Zero();
    if (s.isZero(0.0) && r.isZero(0.0)) {
      continue;
    }
    entries.push_back({ p.id[im.wallSlot[e]], wallPartnerId(im.wallIndex[e]), s, r });
  }
  if (entries.size() > pairEntries) {
    const auto middle = entries.begin() + static_cast<std::ptrdiff_t>(pairEntries);
    std::sort(middle, entries.end(), before);
    std::inplace_merge(entries.begin(), middle, entries.end(), before);
  }
  ContactHistory& h = model_.contacts;
  h.clear();
  h.idA.reserve(entries.size());
  h.idB.reserve(entries.size());
  h.shearSpring.reserve(entries.size());
  if (rolling) {
    h.rollingSpring.reserve(entries.size());
  }
  for (const Entry& e : entries) {
    h.idA.push_back(e.a);
    h.idB.push_back(e.b);
    h.shearSpring.push_back(e.spring);
    if (rolling) {
      h.rollingSpring.push_back(e.roll);
    }
  }
  contactsExported_ = true;
}

} // namespace dem
