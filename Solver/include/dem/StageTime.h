// RockDEM engine: the time of a stepping stage, and how long a stage will run.
//
// A stepping stage (DEM Load Test) publishes frames: model times a whole number of
// physics steps apart, so that a published time is always a time the model reached.
// These functions decide the steps of a frame from the Frame Interval and the timestep,
// estimate how many steps a load test needs to finish, and measure how fast the model
// steps on this machine, so a stage can say how long it will take before it starts.
// SI units: s, 1/s; throughput in particle-steps per second.
#pragma once

#include <cstdint>
#include <string>

namespace dem {

struct Diagnostics;
struct Model;

/// Steps in one frame of a stage whose frames are `frameInterval` (s) apart, at
/// `timestep` (s): round(frameInterval / timestep), so frame k is exactly k x that many
/// steps after the start and its model time is k x steps x timestep. Throws InputError
/// naming Frame Interval when it is shorter than one step (published times would then
/// not be times the model reaches) or not a finite positive number.
std::int64_t stepsPerFrame(double frameInterval, double timestep);

/// The most frames a stage publishes (its time steps are a list ParaView holds in
/// memory): more would only be a longer list, not a finer animation.
constexpr std::int64_t MaxFrames = 100000;

/// How far a load test still has to run, in physics steps at `timestep` (s), from the
/// test state in the model: the shear stage runs until the axial strain reaches Max
/// Strain at the Strain Rate (the strain reached so far is the last history row's), and
/// ends at the first history sample (every Sample Interval steps) from there; a
/// consolidation ends when the servo faces have settled, which cannot be known ahead.
struct TestEstimate {
  std::int64_t steps = 0; ///< steps still to run for the parts that can be estimated
  bool complete = true;   ///< false: a consolidation of unknown length comes first (or is all)
  std::string summary;    ///< one line: what the estimate covers
};
TestEstimate estimateRemainingTestSteps(const Model& model, double timestep);

/// Whether a run without a test (Mode Off) has settled: particles touch and the
/// unbalanced force ratio is below 0.01 (equilibrium, PHYSICS.md section 4).
bool isSettled(const Diagnostics& diagnostics);

/// Measured stepping speed of this model on this machine, particle-steps per second: a
/// copy of the model is stepped for about `budgetSeconds` (at least one step); the model
/// itself is not touched. 0 when the model has no particles or the copy cannot step.
double measureThroughput(const Model& model, double budgetSeconds = 0.1);

} // namespace dem
