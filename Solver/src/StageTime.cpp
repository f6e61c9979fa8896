// RockDEM engine: frames of a stepping stage and run-time estimates (dem/StageTime.h).
#include "dem/StageTime.h"

#include "dem/Errors.h"
#include "dem/LoadTest.h"
#include "dem/Model.h"
#include "dem/Simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

namespace dem {

std::int64_t stepsPerFrame(double frameInterval, double timestep)
{
  if (!(frameInterval > 0.0) || !std::isfinite(frameInterval)) {
    throw InputError("Frame Interval = " + formatValue(frameInterval) +
      " s is out of range: it must be a finite number greater than 0 s.");
  }
  if (!(timestep > 0.0)) {
    return 1; // nothing steps (no particles): one step per frame, never taken
  }
  // A small relative tolerance so that an interval written as n x timestep counts as n.
  if (frameInterval < timestep * (1.0 - 1e-9)) {
    throw InputError("Frame Interval = " + formatValue(frameInterval) +
      " s is shorter than one timestep (" + formatValue(timestep) +
      " s): a frame must be at least one step, or the published times would not be times the "
      "model reaches. Use a Frame Interval of at least " + formatValue(timestep) +
      " s, or 0 for frames of Steps Per Batch steps.");
  }
  const double steps = std::round(frameInterval / timestep);
  if (steps > 9.0e18) {
    throw InputError("Frame Interval = " + formatValue(frameInterval) + " s is " +
      formatValue(steps) + " timesteps of " + formatValue(timestep) +
      " s: more steps than a run can count.");
  }
  return std::max<std::int64_t>(1, static_cast<std::int64_t>(steps));
}

TestEstimate estimateRemainingTestSteps(const Model& model, double timestep)
{
  TestEstimate e;
  const LoadTestState& t = model.test;
  const LoadTestSettings& s = t.settings;
  if (s.mode == TestMode::Off || t.stage == TestStage::Idle) {
    e.summary = "no test";
    return e;
  }
  if (t.stage == TestStage::Done) {
    e.summary = "the test has finished";
    return e;
  }
  if (s.mode == TestMode::Isotropic) {
    e.complete = false;
    e.summary = "an isotropic consolidation, which ends when the faces settle at the "
                "Confining Stress (its length cannot be known ahead)";
    return e;
  }
  // Axial strain reached in shear (the last history row; 0 before shearing starts).
  double reached = 0.0;
  if (t.stage == TestStage::Shear && !t.history.empty()) {
    const std::string name = std::string("Strain ") + "XYZ"[std::clamp(s.axis, 0, 2)];
    const auto& columns = historyColumns();
    const auto column = static_cast<std::size_t>(
      std::find(columns.begin(), columns.end(), name) - columns.begin());
    const double strain = t.history.back()[column];
    reached = s.mode == TestMode::Tension ? -strain : strain;
  }
  const double remaining = std::max(0.0, s.maxStrain - reached);
  const double seconds = s.strainRate > 0.0 ? remaining / s.strainRate : 0.0; // model time
  double steps = timestep > 0.0 ? std::ceil(seconds / timestep) : 0.0;
  // The test notices Max Strain when it samples (every Sample Interval steps): it ends at
  // the first sample at or after that step.
  const double interval = static_cast<double>(std::max<std::int64_t>(1, s.sampleInterval));
  const double first = interval - static_cast<double>(t.stepsSinceSample);
  if (steps > first)
  {
    steps = first + std::ceil((steps - first) / interval) * interval;
  }
  else
  {
    steps = first;
  }
  e.steps = static_cast<std::int64_t>(std::min(steps, 9.0e18));
  std::ostringstream line;
  line << "shear from axial strain " << formatValue(reached) << " to Max Strain "
       << formatValue(s.maxStrain) << " at " << formatValue(s.strainRate) << " 1/s: "
       << formatValue(seconds) << " s of model time";
  if (t.stage == TestStage::Consolidate) {
    e.complete = false;
    line << ", after a consolidation to the Confining Stress of unknown length";
  }
  e.summary = line.str();
  return e;
}

bool isSettled(const Diagnostics& d)
{
  return d.contacts > 0 && d.unbalancedForceRatio < 0.01;
}

double measureThroughput(const Model& model, double budgetSeconds)
{
  const std::size_t particles = model.particles.size();
  if (particles == 0) {
    return 0.0;
  }
  try {
    Model copy = model;
    Simulation simulation(copy);
    if (!(simulation.timestep() > 0.0)) {
      return 0.0;
    }
    simulation.advance(1); // the first step rebuilds lists: not typical, not timed
    const auto start = std::chrono::steady_clock::now();
    std::int64_t steps = 0;
    double elapsed = 0.0;
    do {
      simulation.advance(1);
      ++steps;
      elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    } while (elapsed < budgetSeconds && steps < 1000);
    return elapsed > 0.0 ? static_cast<double>(steps) * static_cast<double>(particles) / elapsed : 0.0;
  } catch (const std::exception&) {
    return 0.0; // a model that cannot step reports that when it is run
  }
}

} // namespace dem
