#include "dem/LoadTest.h"

#include "dem/Bonds.h"
#include "dem/Errors.h"
#include "dem/Membrane.h"
#include "dem/Model.h"
#include "dem/Simulation.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dem {

const char* modeName(TestMode mode)
{
  switch (mode) {
    case TestMode::Off: return "Off";
    case TestMode::Compression: return "Compression";
    case TestMode::Tension: return "Tension";
    case TestMode::Triaxial: return "Triaxial";
    case TestMode::Isotropic: return "Isotropic";
    case TestMode::Brazilian: return "Brazilian";
  }
  return "?";
}

const char* stageName(TestStage stage)
{
  switch (stage) {
    case TestStage::Idle: return "idle";
    case TestStage::Consolidate: return "consolidate";
    case TestStage::Shear: return "shear";
    case TestStage::Done: return "done";
  }
  return "?";
}

const char* confinementName(Confinement confinement)
{
  switch (confinement) {
    case Confinement::RigidWalls: return "Rigid Walls";
    case Confinement::Membrane: return "Membrane";
  }
  return "?";
}

const std::vector<std::string>& historyColumns()
{
  static const std::vector<std::string> columns = {
    "Time (s)", "Step", "Strain X", "Strain Y", "Strain Z", "Volumetric Strain",
    "Stress X- (Pa)", "Stress X+ (Pa)", "Stress Y- (Pa)", "Stress Y+ (Pa)", "Stress Z- (Pa)",
    "Stress Z+ (Pa)", "Sigma XX (Pa)", "Sigma YY (Pa)", "Sigma ZZ (Pa)", "Sigma XY (Pa)",
    "Sigma YZ (Pa)", "Sigma ZX (Pa)", "Axial Stress (Pa)", "Lateral Stress (Pa)",
    "Deviator Stress (Pa)", "Broken In Tension", "Broken In Shear", "Unbalanced Force Ratio",
    "Inertial Number", "Stage", "Mean Stress (Pa)", "Gauge Strain"
  };
  return columns;
}

void validate(const LoadTestSettings& s)
{
  if (s.axis < 0 || s.axis > 2) {
    throw InputError("Axis = " + std::to_string(s.axis) + " is out of range: valid values are X, Y, Z.");
  }
  if (s.mode == TestMode::Triaxial || s.mode == TestMode::Isotropic) {
    requirePositive("Confining Stress", s.confiningStress, "Pa");
  } else {
    requireNonNegative("Confining Stress", s.confiningStress, "Pa");
  }
  requirePositive("Strain Rate", s.strainRate, "1/s");
  requireInOpenRange("Max Strain", s.maxStrain, 0.0, 1.0);
  if (!(s.servoAlpha > 0.0 && s.servoAlpha <= 1.0)) {
    throw InputError("Servo Alpha = " + formatValue(s.servoAlpha) + " is out of range: valid range is (0, 1].");
  }
  if (s.mode == TestMode::Tension) {
    requirePositive("Grip Length", s.gripLength, "largest particle diameters");
  }
  requireInRange("Platen Friction", s.platenFriction, 0.0, 1.0);
  if (!(s.consolidationDamping >= 0.0 && s.consolidationDamping < 1.0)) {
    throw InputError("Consolidation Damping = " + formatValue(s.consolidationDamping) +
                     " is out of range: valid range is [0, 1).");
  }
  if (s.confinement == Confinement::Membrane && s.mode != TestMode::Triaxial && s.mode != TestMode::Isotropic) {
    throw InputError(std::string("Confinement = Membrane is out of range for Mode = ") + modeName(s.mode) +
      ": the membrane confines a Triaxial or Isotropic test (valid values here: Rigid Walls; a " +
      modeName(s.mode) + " test has no confining stress).");
  }
  if (s.confinement != Confinement::RigidWalls && s.confinement != Confinement::Membrane) {
    throw InputError("Confinement = " + std::to_string(static_cast<int>(s.confinement)) +
      " is out of range: valid values are Rigid Walls (0), Membrane (1).");
  }
  if (s.sampleInterval < 1) {
    throw InputError("Sample Interval = " + std::to_string(s.sampleInterval) +
                     " is out of range: it must be 1 or more steps.");
  }
}

bool operator==(const LoadTestSettings& a, const LoadTestSettings& b)
{
  return a.mode == b.mode && a.confinement == b.confinement && a.axis == b.axis && a.confiningStress == b.confiningStress &&
    a.strainRate == b.strainRate && a.maxStrain == b.maxStrain && a.servoAlpha == b.servoAlpha &&
    a.sampleInterval == b.sampleInterval && a.settleTolerance == b.settleTolerance &&
    a.gripLength == b.gripLength && a.platenFriction == b.platenFriction &&
    a.consolidationDamping == b.consolidationDamping;
}

double localDamping(const LoadTestState& test, double settlingDamping)
{
  const TestMode mode = test.settings.mode;
  const bool consolidating = test.stage == TestStage::Consolidate &&
    (mode == TestMode::Triaxial || mode == TestMode::Isotropic);
  return consolidating ? test.settings.consolidationDamping : settlingDamping;
}

bool continuesTest(const LoadTestState& test, const LoadTestSettings& settings)
{
  if (settings.mode == TestMode::Off) {
    return test.settings.mode == TestMode::Off;
  }
  return test.settings == settings &&
    (test.stage == TestStage::Consolidate || test.stage == TestStage::Shear);
}

double brazilianStress(double load, double diameter, double thickness)
{
  constexpr double pi = 3.14159265358979323846;
  return diameter > 0.0 && thickness > 0.0 ? 2.0 * load / (pi * diameter * thickness) : 0.0;
}

std::array<double, 2> brazilianDisc(const Model& model)
{
  const int a = model.test.settings.axis;
  const auto& l0 = model.test.initialLength;
  const double diameter = l0[static_cast<std::size_t>(a)];
  const double thickness = model.domain.section2D
    ? model.domain.slabThickness()
    : std::min(l0[static_cast<std::size_t>((a + 1) % 3)], l0[static_cast<std::size_t>((a + 2) % 3)]);
  return { { diameter, thickness } };
}

double centreSpread(const Particles& particles, int axis)
{
  const std::size_t n = particles.size();
  if (n == 0) {
    return 0.0;
  }
  double mean = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    mean += particles.position[i][axis];
  }
  mean /= static_cast<double>(n);
  double deviation = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    deviation += std::abs(particles.position[i][axis] - mean);
  }
  return deviation / static_cast<double>(n);
}

void validatePlatenSpeed(const Model& model, double timestep)
{
  const LoadTestSettings& s = model.test.settings;
  const Particles& p = model.particles;
  if ((s.mode != TestMode::Compression && s.mode != TestMode::Tension && s.mode != TestMode::Triaxial &&
       s.mode != TestMode::Brazilian) ||
      p.empty() || !(timestep > 0.0) || s.axis < 0 || s.axis > 2 ||
      model.solver.allowUnsafeTimestep) { // test-only: show what an unsafe run does
    return;
  }
  // The starting length along the axis (set by startLoadTest; the box until then).
  const double length = model.test.initialLength[static_cast<std::size_t>(s.axis)] > 0.0
    ? model.test.initialLength[static_cast<std::size_t>(s.axis)]
    : model.domain.size[s.axis];                                             // m
  const double rmin = *std::min_element(p.radius.begin(), p.radius.end()); // m
  const double travel = s.strainRate * length * timestep;                   // m per step
  const double allowed = MaxPlatenTravelPerStep * rmin;                     // m per step
  if (travel > allowed) {
    throw InputError("Strain Rate = " + formatValue(s.strainRate) +
      " 1/s is too fast for this model: the platen would move " + formatValue(travel) +
      " m per step (Strain Rate x starting length " + formatValue(length) + " m x timestep " +
      formatValue(timestep) + " s), more than " + formatValue(100.0 * MaxPlatenTravelPerStep) +
      " % of the smallest radius (" + formatValue(rmin) + " m), and the run would blow up. Valid range is (0, " +
      formatValue(allowed / (length * timestep)) + "] 1/s for this model and timestep.");
  }
}

namespace {
/// Removes the grains beyond the walls the new stage stands up (grains that escaped while
/// those walls were down, in an unconfined test): a grain beyond an active wall could never
/// come back, and the run would stop at once on it (Documentation/Press.md, "Escaped grains").
RemovedParticles removeEscapedGrains(Model& model)
{
  std::vector<std::uint8_t> escaped(model.particles.size(), 0);
  for (std::size_t i = 0; i < escaped.size(); ++i) {
    escaped[i] = beyondActiveWalls(model.walls, model.particles.position[i]) ? 1 : 0;
  }
  return removeParticles(model, escaped);
}
} // namespace

RemovedParticles startLoadTest(Model& model, const LoadTestSettings& settings)
{
  validate(settings);
  validateMembraneSpecimen(model, settings);
  if (settings.mode == TestMode::Tension && !model.particles.empty()) {
    const BondCounts bonds = countBonds(model.bonds);
    if (bonds.installed == bonds.broken) {
      throw InputError(std::string("Mode = Tension needs a cemented model, but this one has ") +
        (bonds.installed == 0 ? "no bonds" : "no intact bonds (all " + std::to_string(bonds.installed) +
         " are broken)") + ": nothing holds the specimen together, so the pull would be zero. Cement it "
        "first (DEM Cement), or use Mode = Compression, Triaxial or Isotropic.");
    }
  }
  if (settings.mode == TestMode::Tension && !model.particles.empty()) {
    // The grips (checked before anything changes): they must leave a gauge length.
    const Particles& q = model.particles;
    const int a = settings.axis;
    double lo = std::numeric_limits<double>::max();
    double hi = -lo;
    double rmax = 0.0;
    for (std::size_t i = 0; i < q.size(); ++i) {
      lo = std::min(lo, q.position[i][a] - q.radius[i]);
      hi = std::max(hi, q.position[i][a] + q.radius[i]);
      rmax = std::max(rmax, q.radius[i]);
    }
    const double grip = settings.gripLength * 2.0 * rmax; // m
    if (2.0 * grip >= hi - lo) {
      throw InputError("Grip Length = " + formatValue(settings.gripLength) + " largest particle diameters (" +
        formatValue(grip) + " m) is out of range: the two grips would cover the whole specimen (" +
        formatValue(hi - lo) + " m long along the axis), leaving no gauge length; valid range is (0, " +
        formatValue(0.5 * (hi - lo) / (2.0 * rmax)) + ") largest particle diameters.");
    }
  }
  LoadTestState& t = model.test;
  Particles& p = model.particles;
  // End any previous test: detach particles, restore the box.
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.flags[i] & (FlagAttachedLow | FlagAttachedHigh)) {
      p.flags[i] &= ~(FlagAttachedLow | FlagAttachedHigh);
      p.velocity[i].setZero();
      p.angularVelocity[i].setZero();
    }
  }
  t = LoadTestState();
  t.settings = settings;
  if (settings.mode == TestMode::Off || model.walls.size() != 6) {
    // Off restores the box; a model that never ran gets its walls here.
    resetWalls(model);
    if (settings.mode == TestMode::Off) {
      return removeEscapedGrains(model);
    }
  }
  // Otherwise the walls stay where the previous stage left them (a consolidated
  // specimen is smaller than the box); they become active again on non-periodic axes.
  for (Wall& w : model.walls) {
    w.velocity = 0.0;
    w.active = !model.domain.periodic[w.axis] && !(model.domain.section2D && w.axis == 2);
  }
  const Domain& d = model.domain;
  for (int k = 0; k < 3; ++k) {
    // The slab axis of a 2D section has no walls, and needs none unless the section is to be
    // squeezed along it: the discs move in the XY plane only, so direct tension (grips),
    // the biaxial test (Triaxial: confined along the other in-plane axis) and the isotropic
    // test (both in-plane axes) are complete in the plane. A periodic axis cannot be
    // confined or gripped.
    const bool slab = d.section2D && k == 2;
    if (k == settings.axis && (d.periodic[k] || slab)) {
      throw InputError(std::string("Axis = ") + "XYZ"[k] + " cannot be loaded: that axis is " +
        (slab ? "the slab axis of a 2D section (load a section along X or Y)" : "periodic") + ".");
    }
    if (d.periodic[k] && settings.mode != TestMode::Compression && settings.mode != TestMode::Brazilian) {
      throw InputError(std::string("Mode = ") + modeName(settings.mode) + " needs walls on axis " +
        "XYZ"[k] + ", but that axis is periodic.");
    }
  }
  const int a = settings.axis;
  for (Wall& w : model.walls) {
    const bool axial = w.axis == a;
    switch (settings.mode) {
      case TestMode::Compression:
      case TestMode::Brazilian:
        w.active = w.active && axial; // unconfined: the four side walls are removed
        break;
      case TestMode::Tension:
        w.active = false; // the particles next to each platen are attached to it instead
        break;
      case TestMode::Triaxial:
      case TestMode::Isotropic:
        if (settings.confinement == Confinement::Membrane) {
          w.active = w.active && axial; // the membrane replaces the four side faces
        }
        break;
      default:
        break;
    }
  }
  const bool unconfined = settings.mode == TestMode::Compression || settings.mode == TestMode::Tension ||
    settings.mode == TestMode::Brazilian;
  if (unconfined && !p.empty()) {
    // The platens start on the specimen: at the extent of the particles along the axis,
    // so that the strain counts from first contact, not from a gap above a settled pack.
    double lo = std::numeric_limits<double>::max();
    double hi = -lo;
    for (std::size_t i = 0; i < p.size(); ++i) {
      lo = std::min(lo, p.position[i][a] - p.radius[i]);
      hi = std::max(hi, p.position[i][a] + p.radius[i]);
    }
    model.walls[2 * a].position = lo;
    model.walls[2 * a + 1].position = hi;
  }
  const RemovedParticles removed = removeEscapedGrains(model);
  for (int k = 0; k < 3; ++k) {
    const Wall& low = model.walls[2 * k];
    const Wall& high = model.walls[2 * k + 1];
    t.initialLength[k] = high.position - low.position;
    const bool unwalledSide = unconfined && k != a && !(d.section2D && k == 2) && !p.empty();
    t.initialSpread[k] = 0.0;
    if (unwalledSide) {
      // Without side walls the specimen's lateral size starts as the particles' extent;
      // it then follows the spread of the centres (Simulation::specimenLengths).
      double lo = std::numeric_limits<double>::max();
      double hi = -lo;
      for (std::size_t i = 0; i < p.size(); ++i) {
        lo = std::min(lo, p.position[i][k] - p.radius[i]);
        hi = std::max(hi, p.position[i][k] + p.radius[i]);
      }
      t.initialLength[k] = hi - lo;
      t.initialSpread[k] = centreSpread(p, k);
    }
  }
  if (settings.mode != TestMode::Off && !p.empty()) {
    t.initialSpread[static_cast<std::size_t>(a)] = centreSpread(p, a); // the Gauge Strain's reference
  }
  t.initialVolume = t.initialLength[0] * t.initialLength[1] * t.initialLength[2];
  if (settings.mode == TestMode::Tension) {
    // The grips: the particles whose surface lies within Grip Length (largest diameters)
    // of each platen are attached to it and move with it.
    const double rmax = p.empty() ? 0.0 : *std::max_element(p.radius.begin(), p.radius.end());
    const double low = model.walls[2 * a].position;
    const double high = model.walls[2 * a + 1].position;
    const double grip = settings.gripLength * 2.0 * rmax; // m
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.position[i][a] - p.radius[i] <= low + grip) {
        p.flags[i] |= FlagAttachedLow;
        p.velocity[i].setZero();
        p.angularVelocity[i].setZero();
      } else if (p.position[i][a] + p.radius[i] >= high - grip) {
        p.flags[i] |= FlagAttachedHigh;
        p.velocity[i].setZero();
        p.velocity[i][a] = settings.strainRate * t.initialLength[a];
        p.angularVelocity[i].setZero();
      }
    }
    model.walls[2 * a + 1].velocity = settings.strainRate * t.initialLength[a];
  }
  t.stage = (settings.mode == TestMode::Triaxial || settings.mode == TestMode::Isotropic)
    ? TestStage::Consolidate
    : TestStage::Shear;
  if (settings.mode == TestMode::Compression || settings.mode == TestMode::Brazilian) {
    model.walls[2 * a + 1].velocity = -settings.strainRate * t.initialLength[a];
  }
  const bool carvedCylinder = (settings.mode == TestMode::Compression || settings.mode == TestMode::Tension) &&
    d.cylinderAxis == a && !d.section2D && !p.empty();
  if (membraneActive(model) || carvedCylinder) {
    // The cylinder's starting diameter: twice the membrane's radius, the mean outer reach
    // of the surface grains (for an unconfined cylinder too: its grains' extent, which the
    // one outermost grain on each side sets, exceeds it by up to a grain diameter). An
    // unconfined side then follows the spread of the centres from there.
    const double diameter = 2.0 * lateralSurface(model, a, 0.0).radius;
    t.initialLength[(a + 1) % 3] = diameter;
    t.initialLength[(a + 2) % 3] = diameter;
    t.initialVolume = t.initialLength[0] * t.initialLength[1] * t.initialLength[2];
  }
  return removed;
}

} // namespace dem
