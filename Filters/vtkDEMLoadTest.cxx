#include "vtkDEMLoadTest.h"

#include "vtkDEMCheckpoint.h"
#include "vtkDEMModelConversion.h"
#include "vtkDEMPipelineTime.h"

#include "dem/Bonds.h"
#include "dem/Errors.h"
#include "dem/LoadTest.h"
#include "dem/Model.h"
#include "dem/Overlaps.h"
#include "dem/Pack.h"
#include "dem/Simulation.h"
#include "dem/StageTime.h"
#include "dem/StateFile.h"
#include "dem/ResolutionAdvice.h"
#include "dem/StrainRateAdvice.h"

#include <vtkDoubleArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkTable.h>
#include <vtkTimeStamp.h>

#include <dlfcn.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstring>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <map>
#include <memory>
#include <sstream>

vtkStandardNewMacro(vtkDEMLoadTest);

namespace
{
/// In-memory checkpoints are kept within this budget; beyond it every other one goes.
constexpr double CheckpointBudgetBytes = 1024.0 * 1024.0 * 1024.0;

double ModelBytes(const dem::Model& m)
{
  // Particles, contact history, bonds (ids, 7 doubles, 4 vectors, a byte) and history rows.
  return static_cast<double>(m.particles.size() * dem::Particles::bytesPerParticle() +
    m.contacts.size() * (2 * sizeof(std::int64_t) + 2 * sizeof(dem::Vec3)) +
    m.bonds.size() * (2 * sizeof(std::int64_t) + 7 * sizeof(double) + 4 * sizeof(dem::Vec3) + 1) +
    m.test.history.size() * dem::HistoryColumnCount * sizeof(double));
}

/// Derived plot columns of the History table (port 1): name, source column, scale.
struct PlotColumn
{
  const char* name;
  const char* source; ///< nullptr: the strain on the test axis
  double scale;
};
const PlotColumn PlotColumns[] = {
  { "Axial Strain (%)", nullptr, 100.0 },
  { "Volumetric Strain (%)", "Volumetric Strain", 100.0 },
  { "Axial Stress (MPa)", "Axial Stress (Pa)", 1e-6 },
  { "Lateral Stress (MPa)", "Lateral Stress (Pa)", 1e-6 },
  { "Deviator Stress (MPa)", "Deviator Stress (Pa)", 1e-6 },
};

std::size_t ColumnIndex(const std::string& name)
{
  const auto& names = dem::historyColumns();
  for (std::size_t k = 0; k < names.size(); ++k)
  {
    if (names[k] == name)
    {
      return k;
    }
  }
  throw std::logic_error("history column '" + name + "' not found");
}

/// The history as a table: the engine's columns, then the derived plot columns.
void HistoryToTable(const dem::LoadTestState& test, int axis, vtkTable* table)
{
  table->Initialize();
  const auto& names = dem::historyColumns();
  const vtkIdType rows = static_cast<vtkIdType>(test.history.size());
  for (std::size_t c = 0; c < names.size(); ++c)
  {
    vtkNew<vtkDoubleArray> column;
    column->SetName(names[c].c_str());
    column->SetNumberOfTuples(rows);
    for (vtkIdType r = 0; r < rows; ++r)
    {
      column->SetValue(r, test.history[static_cast<std::size_t>(r)][c]);
    }
    table->AddColumn(column);
  }
  const std::size_t axialStrain = ColumnIndex(std::string("Strain ") + "XYZ"[axis]);
  for (const PlotColumn& plot : PlotColumns)
  {
    const std::size_t source = plot.source ? ColumnIndex(plot.source) : axialStrain;
    vtkNew<vtkDoubleArray> column;
    column->SetName(plot.name);
    column->SetNumberOfTuples(rows);
    for (vtkIdType r = 0; r < rows; ++r)
    {
      column->SetValue(r, plot.scale * test.history[static_cast<std::size_t>(r)][source]);
    }
    table->AddColumn(column);
  }
}

/// Ctrl-C (SIGINT) while a stage steps stops it at the next batch (at the last whole
/// frame) instead of killing the program with the run half done: pvpython and pvbatch end
/// on SIGINT (their handler is a crash handler), and a run of unknown length must be
/// stoppable. The handler is installed only while the stage steps; afterwards the stage
/// stays stopped until a property changes, so a script's loop over frames ends too, and a
/// second Ctrl-C ends the program as before. In a Python that handles SIGINT itself (a
/// plain python importing paraview) Python is told, so it raises KeyboardInterrupt.
std::atomic<bool> Interrupted{ false };
extern "C" void OnInterrupt(int)
{
  Interrupted = true;
}
class InterruptGuard
{
public:
  InterruptGuard()
  {
    Interrupted = false;
    this->Previous = std::signal(SIGINT, OnInterrupt);
  }
  ~InterruptGuard()
  {
    std::signal(SIGINT, this->Previous);
    Dl_info owner;
    if (Interrupted && this->Previous != SIG_DFL && this->Previous != SIG_IGN &&
      this->Previous != SIG_ERR && dladdr(reinterpret_cast<void*>(this->Previous), &owner) &&
      owner.dli_fname && std::strstr(owner.dli_fname, "python"))
    {
      // Python's own handler was in place: tell Python (found at run time, the filters do
      // not depend on Python), which raises KeyboardInterrupt.
      using SetInterrupt = void (*)();
      if (auto notify = reinterpret_cast<SetInterrupt>(dlsym(RTLD_DEFAULT, "PyErr_SetInterrupt")))
      {
        notify();
      }
    }
  }
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

private:
  void (*Previous)(int) = SIG_DFL;
};

/// "3.2 years", "4.5 min", "12 s": a run time for a message.
std::string Duration(double seconds)
{
  std::ostringstream out;
  out << std::setprecision(2) << std::fixed;
  if (!(seconds >= 0.0) || !std::isfinite(seconds))
  {
    return "an unknown time";
  }
  if (seconds < 120.0)
  {
    out << std::setprecision(1) << seconds << " s";
  }
  else if (seconds < 7200.0)
  {
    out << std::setprecision(1) << seconds / 60.0 << " min";
  }
  else if (seconds < 3.0 * 86400.0)
  {
    out << std::setprecision(1) << seconds / 3600.0 << " h";
  }
  else if (seconds < 3.0 * 365.25 * 86400.0)
  {
    out << std::setprecision(0) << seconds / 86400.0 << " days";
  }
  else
  {
    out << std::setprecision(1) << seconds / (365.25 * 86400.0) << " years";
  }
  return out.str();
}

/// A run longer than this is announced as a warning (Output Messages pops up).
constexpr double LongRunSeconds = 600.0;

/// Writes the table as CSV (quoted header, full precision) with the engine's atomic
/// writer (dem::writeFileAtomically): a crash never leaves a half-written file, and a
/// failure says why (the system's reason).
void WriteTableCSV(vtkTable* table, const std::string& path)
{
  std::ostringstream out;
  const vtkIdType columns = table->GetNumberOfColumns();
  for (vtkIdType c = 0; c < columns; ++c)
  {
    out << (c ? "," : "") << '"' << table->GetColumnName(c) << '"';
  }
  out << "\n" << std::setprecision(17);
  for (vtkIdType r = 0; r < table->GetNumberOfRows(); ++r)
  {
    for (vtkIdType c = 0; c < columns; ++c)
    {
      out << (c ? "," : "") << vtkDoubleArray::SafeDownCast(table->GetColumn(c))->GetValue(r);
    }
    out << "\n";
  }
  const std::string text = out.str();
  try
  {
    dem::writeFileAtomically(path, text.data(), text.size());
  }
  catch (const std::exception& e)
  {
    throw std::runtime_error(std::string("History File: ") + e.what());
  }
}
}

struct vtkDEMLoadTest::vtkInternals
{
  bool Valid = false;
  bool Failed = false;
  vtkMTimeType BuildTime = 0;     ///< this filter's MTime when the cache was built
  vtkMTimeType InputTime = 0;     ///< the input data's MTime when the cache was built
  dem::Model Model;
  std::unique_ptr<dem::Simulation> Simulation;
  int Frame = 0;
  std::int64_t StepsPerFrame = 1;
  double Timestep = 0.0;          ///< s, of the run (frames are StepsPerFrame of these)
  int Published = 0;              ///< Number Of Frames 0: the last frame published so far
  int FinishFrame = -1;           ///< the frame where the test finished (or settled); -1: not yet
  int Revision = 0;               ///< changes of the published times
  bool TimesChanged = false;      ///< RequestData published new times: see ComputePipelineMTime
  vtkTimeStamp TimesTime;         ///< when the next pass learnt that the times changed
  std::map<int, dem::Model> Checkpoints;
  std::string GravityNote;
  int SavedFrame = -1;     ///< frame last written to SavedPath (-1: none since the rebuild)
  std::string SavedPath;
  std::uint64_t Run = 0;   ///< fingerprint of this run (input and settings), for checkpoints
  std::string Stopped;     ///< why the run was stopped (Ctrl-C, abort); empty: it runs
  std::string CheckpointError; ///< why the last checkpoint failed ("" when it succeeded)
  vtkMTimeType AdviceTime = 0;      ///< this filter's MTime when SuggestedStrainRate was estimated ahead
  vtkMTimeType AdviceInputTime = 0; ///< the input data's MTime then
};

void vtkDEMLoadTest::SetCheckpointFile(const char* path)
{
  const std::string now = this->CheckpointFile ? this->CheckpointFile : "";
  const std::string wanted = path ? path : "";
  if (now == wanted)
  {
    return;
  }
  delete[] this->CheckpointFile;
  this->CheckpointFile = nullptr;
  if (path)
  {
    this->CheckpointFile = new char[wanted.size() + 1];
    std::copy(wanted.c_str(), wanted.c_str() + wanted.size() + 1, this->CheckpointFile);
  }
  // Where the run is saved is not a parameter of the run: keep the computed frames.
  const bool fresh = this->Internals->Valid && this->Internals->BuildTime >= this->GetMTime();
  this->Modified();
  if (fresh)
  {
    this->Internals->BuildTime = this->GetMTime();
  }
}

void vtkDEMLoadTest::SetCheckpointEvery(int frames)
{
  if (frames == this->CheckpointEvery)
  {
    return;
  }
  this->CheckpointEvery = frames;
  const bool fresh = this->Internals->Valid && this->Internals->BuildTime >= this->GetMTime();
  this->Modified();
  if (fresh)
  {
    this->Internals->BuildTime = this->GetMTime();
  }
}

void vtkDEMLoadTest::WriteCheckpoint()
{
  vtkInternals& in = *this->Internals;
  // Never overwrite a checkpoint with an earlier frame of the same run (going back in
  // time replays frames that were already saved).
  if (!this->CheckpointFile || !*this->CheckpointFile ||
    (in.SavedPath == this->CheckpointFile && in.Frame <= in.SavedFrame))
  {
    return;
  }
  try
  {
    dem::writeStateAndHistory(in.Model, this->CheckpointFile);
    rockdem::CheckpointRecord record;
    record.run = in.Run;
    record.stepsPerFrame = in.StepsPerFrame;
    record.frame = in.Frame;
    record.finished = in.FinishFrame >= 0 && in.FinishFrame == in.Frame;
    rockdem::WriteCheckpointRecord(this->CheckpointFile, record);
    in.SavedFrame = in.Frame;
    in.SavedPath = this->CheckpointFile;
    in.CheckpointError.clear();
  }
  catch (const std::exception& e)
  {
    // The run goes on; the user learns that the checkpoint is missing: in Status and Last
    // Message, and in Output Messages once per distinct failure (not every frame).
    const std::string error = std::string("Checkpoint File: ") + e.what();
    if (error != in.CheckpointError)
    {
      vtkErrorMacro(<< error << " The run goes on without this checkpoint.");
    }
    in.CheckpointError = error;
    this->LastMessageText = error + " (frame " + std::to_string(in.Frame) + " is not saved)";
  }
}

int vtkDEMLoadTest::WriteHistory(const char* path)
{
  vtkInternals& in = *this->Internals;
  try
  {
    if (!path || !*path)
    {
      throw dem::InputError("Export Test History: no file name given.");
    }
    if (!in.Valid)
    {
      throw dem::InputError("Export Test History: the stage has not run yet (no history).");
    }
    dem::writeHistoryCSV(in.Model.test, path);
    this->LastExportMessage = "Exported " + std::to_string(in.Model.test.history.size()) +
      " history rows to '" + path + "'.";
    vtkOutputWindowDisplayText(("DEM Load Test: " + this->LastExportMessage + "\n").c_str());
    return 1;
  }
  catch (const std::exception& e)
  {
    this->LastExportMessage = e.what();
    vtkErrorMacro(<< e.what());
    return 0;
  }
}

int vtkDEMLoadTest::GetTimeStepsRevision()
{
  return this->Internals->Revision;
}

vtkDEMLoadTest::vtkDEMLoadTest()
  : Mode(MODE_OFF)
  , FrameInterval(0.0)
  , NumberOfFrames(0)
  , StepsPerBatch(100)
  , ContactLaw(HERTZ_MINDLIN)
  , TimestepSafety(0.1)
  , RequestedTimestep(0.0)
  , SettlingDamping(0.7)
  , Threads(0)
  , GPUSolver(0)
  , CriticalTimestep(0.0)
  , Timestep(0.0)
  , CurrentPorosity(1.0)
  , KineticEnergy(0.0)
  , NumberOfContacts(0)
  , UnbalancedForceRatio(0.0)
  , ModelTime(0.0)
  , CurrentFrame(0)
  , Internals(new vtkInternals)
{
  this->Gravity[0] = 0.0;
  this->Gravity[1] = 0.0;
  this->Gravity[2] = -9.81;
  this->SetNumberOfOutputPorts(2);
}

vtkDEMLoadTest::~vtkDEMLoadTest()
{
  this->SetHistoryFile(nullptr);
  delete[] this->CheckpointFile;
  delete this->Internals;
}

int vtkDEMLoadTest::FillOutputPortInformation(int port, vtkInformation* info)
{
  if (port == 1)
  {
    info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkTable");
    return 1;
  }
  return this->Superclass::FillOutputPortInformation(port, info);
}

int vtkDEMLoadTest::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkMultiBlockDataSet");
  return 1;
}

int vtkDEMLoadTest::LastFrame()
{
  const vtkInternals& in = *this->Internals;
  if (!(this->FrameInterval >= 0.0) || !std::isfinite(this->FrameInterval) ||
    this->NumberOfFrames < 0 || this->NumberOfFrames > dem::MaxFrames)
  {
    return -1; // reported in RequestData
  }
  const bool current = in.Valid && in.BuildTime >= this->GetMTime();
  int last = 0;
  if (this->NumberOfFrames > 0)
  {
    // Before the stage has run with Frame Interval 0, its frames are not known yet.
    last = current || this->FrameInterval > 0.0 ? this->NumberOfFrames : 0;
  }
  else
  {
    last = current ? in.Published : 0;
  }
  if (current && in.FinishFrame >= 0)
  {
    last = std::min(last, in.FinishFrame);
  }
  return last;
}

void vtkDEMLoadTest::PublishTimeSteps(vtkInformationVector* outputVector)
{
  const vtkInternals& in = *this->Internals;
  const int last = this->LastFrame();
  const bool current = in.Valid && in.BuildTime >= this->GetMTime();
  // Both ports (model and history table) publish the same frames.
  for (int port = 0; port < outputVector->GetNumberOfInformationObjects(); ++port)
  {
    vtkInformation* outInfo = outputVector->GetInformationObject(port);
    if (last < 0)
    {
      outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
      outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
      continue;
    }
    // Once the stage has run the frames are times the model reaches (whole steps);
    // before, k x Frame Interval.
    const double spacing = current
      ? static_cast<double>(in.StepsPerFrame) * in.Timestep
      : this->FrameInterval;
    std::vector<double> times(static_cast<std::size_t>(last) + 1);
    for (std::size_t k = 0; k < times.size(); ++k)
    {
      times[k] = static_cast<double>(k) * spacing;
    }
    outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(),
      static_cast<int>(times.size()));
    const double range[2] = { times.front(), times.back() };
    outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  }
}

dem::LoadTestSettings vtkDEMLoadTest::PressSettings() const
{
  dem::LoadTestSettings press;
  press.mode = static_cast<dem::TestMode>(this->Mode);
  press.axis = this->Axis;
  press.confiningStress = this->ConfiningStress;
  press.strainRate = this->StrainRate;
  press.maxStrain = this->MaxStrain;
  press.servoAlpha = this->ServoAlpha;
  press.sampleInterval = this->SampleInterval;
  press.gripLength = this->GripLength;
  press.platenFriction = this->PlatenFriction;
  press.consolidationDamping = this->ConsolidationDamping;
  press.confinement = static_cast<dem::Confinement>(this->Confinement);
  return press;
}

int vtkDEMLoadTest::ComputePipelineMTime(vtkInformation* request, vtkInformationVector** inInfoVec,
  vtkInformationVector* outInfoVec, int requestFromOutputPort, vtkMTimeType* mtime)
{
  vtkInternals& in = *this->Internals;
  if (in.TimesChanged)
  {
    in.TimesChanged = false;
    in.TimesTime.Modified();
  }
  if (!this->Superclass::ComputePipelineMTime(
        request, inInfoVec, outInfoVec, requestFromOutputPort, mtime))
  {
    return 0;
  }
  *mtime = std::max<vtkMTimeType>(*mtime, in.TimesTime.GetMTime());
  return 1;
}

dem::SolverDevice vtkDEMLoadTest::Device() const
{
  return this->GPUSolver ? dem::SolverDevice::GPU : dem::SolverDevice::CPU;
}

int vtkDEMLoadTest::FrameOf(double time)
{
  const vtkInternals& in = *this->Internals;
  // With Number Of Frames 0 a frame past those published so far is still a frame of the
  // run (the stage publishes more as it goes), up to where it finishes.
  const bool open = this->NumberOfFrames == 0 && in.Valid && in.FinishFrame < 0;
  const int last = open ? static_cast<int>(dem::MaxFrames) : std::max(0, this->LastFrame());
  if (!std::isfinite(time) || time <= 0.0)
  {
    return 0;
  }
  double frame = 0.0;
  const double spacing = static_cast<double>(in.StepsPerFrame) * in.Timestep;
  const bool known = in.Valid && spacing > 0.0;
  // A published time (exact), else a time on the k x Frame Interval grid (what a script
  // computes, and what was published before the stage had run).
  const double exact = known ? std::round(time / spacing) : -1.0;
  if (known && std::abs(time - exact * spacing) <= 1e-9 * std::max(time, spacing))
  {
    frame = exact;
  }
  else if (this->FrameInterval > 0.0)
  {
    frame = std::round(time / this->FrameInterval);
  }
  else if (known)
  {
    frame = exact;
  }
  return static_cast<int>(std::min<double>(frame, last));
}

int vtkDEMLoadTest::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  this->PublishTimeSteps(outputVector);
  this->EstimateSuggestedStrainRate(
    vtkMultiBlockDataSet::GetData(inputVector[0]->GetInformationObject(0)));
  return 1;
}

void vtkDEMLoadTest::EstimateSuggestedStrainRate(vtkMultiBlockDataSet* input)
{
  vtkInternals& in = *this->Internals;
  // A stage that has run keeps the rate refined from its measured stress.
  const bool current = in.Valid && in.BuildTime >= this->GetMTime() &&
    (!input || input->GetMTime() == in.InputTime);
  if (current || !input)
  {
    return;
  }
  if (in.AdviceTime == this->GetMTime() && in.AdviceInputTime == input->GetMTime())
  {
    return;
  }
  in.AdviceTime = this->GetMTime();
  in.AdviceInputTime = input->GetMTime();
  try
  {
    // Before the run (the input has data, e.g. after Apply upstream): from the peak
    // stress estimated from the cement strengths and the Confining Stress.
    this->SuggestedStrainRate =
      dem::suggestedStrainRate(rockdem::MultiBlockToModel(input), this->PressSettings());
  }
  catch (const std::exception&)
  {
    this->SuggestedStrainRate = 0.0; // an input that cannot run says why in RequestData
  }
}

int vtkDEMLoadTest::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // A stepped upstream model is consumed at a fixed time (its last time step), so that
  // changing this stage's time never re-runs the stage before it.
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  rockdem::RequestLastUpstreamTime(inInfo);
  return 1;
}

void vtkDEMLoadTest::Start(vtkMultiBlockDataSet* input)
{
  vtkInternals& in = *this->Internals;
  in.Valid = false;
  in.Failed = false;
  in.Stopped.clear();
  in.Checkpoints.clear();
  in.Simulation.reset();
  in.SavedFrame = -1;
  in.FinishFrame = -1;
  in.CheckpointError.clear();
  this->LastMessageText.clear();
  in.Model = rockdem::MultiBlockToModel(input);
  if (in.Model.particles.empty())
  {
    this->LastMessageText = "The input model has no particles: there is nothing to run.";
    vtkWarningMacro(<< this->LastMessageText);
  }
  dem::SolverSettings& s = in.Model.solver;
  s.contactLaw = static_cast<dem::ContactLaw>(this->ContactLaw);
  s.timestepSafety = this->TimestepSafety;
  s.requestedTimestep = this->RequestedTimestep;
  s.settlingDamping = this->SettlingDamping;
  s.threads = this->Threads;
  in.Model.gravity = dem::Vec3(this->Gravity[0], this->Gravity[1], this->Gravity[2]);
  in.GravityNote.clear();
  if (in.Model.domain.section2D && this->Gravity[0] == 0.0 && this->Gravity[1] == 0.0 &&
    this->Gravity[2] != 0.0)
  {
    in.Model.gravity = dem::Vec3(0.0, -std::abs(this->Gravity[2]), 0.0);
    in.GravityNote = "2D section: gravity " + dem::formatValue(this->Gravity[2]) +
      " m/s^2 along Z acts along -Y in the section plane.";
  }
  const dem::LoadTestSettings press = this->PressSettings();
  // Start the press (Mode Off restores the box) before the simulation sees the model,
  // unless the input's test is this one in progress (a reopened state file): then it
  // continues exactly where it stopped.
  if (this->ContinueTest && dem::continuesTest(in.Model.test, press))
  {
    in.Model.test.settings = press;
  }
  else
  {
    const std::string removed = dem::startLoadTest(in.Model, press).summary(
      "whose centres lay beyond the walls of this stage (grains that escaped while those walls "
      "were down, in an unconfined test)");
    if (!removed.empty())
    {
      vtkWarningMacro(<< removed);
      this->LastMessageText = removed;
    }
  }
  in.Simulation.reset(new dem::Simulation(in.Model, this->Device()));
  in.Timestep = in.Simulation->timestep();
  this->SuggestedStrainRate = in.Simulation->measurements().suggestedStrainRate;
  if (!in.Simulation->gpuFallbackReason().empty())
  {
    const std::string fallback =
      "GPU Solver: running on the CPU because " + in.Simulation->gpuFallbackReason() + ".";
    vtkWarningMacro(<< fallback);
    this->LastMessageText = fallback;
  }

  // Frames: whole steps. How far the stage runs: Number Of Frames, or the test's end.
  const bool untilDone = this->NumberOfFrames == 0;
  const bool testing = this->Mode != MODE_OFF;
  const dem::TestEstimate test = dem::estimateRemainingTestSteps(in.Model, in.Timestep);
  in.StepsPerFrame = this->FrameInterval > 0.0
    ? dem::stepsPerFrame(this->FrameInterval, in.Timestep)
    : static_cast<std::int64_t>(this->StepsPerBatch);
  if (untilDone && testing && test.steps > 0)
  {
    // The frames the test is expected to need (5 % more, at least one).
    std::int64_t frames = (test.steps + test.steps / 20) / in.StepsPerFrame + 1;
    if (frames > dem::MaxFrames)
    {
      if (this->FrameInterval > 0.0)
      {
        throw dem::InputError("Frame Interval = " + dem::formatValue(this->FrameInterval) +
          " s is too short for this test: with Number Of Frames 0 it needs about " +
          std::to_string(frames) + " frames of " + std::to_string(in.StepsPerFrame) +
          " steps, more than the " + std::to_string(dem::MaxFrames) +
          " a stage publishes. Use a longer Frame Interval (or 0 for automatic frames).");
      }
      // Automatic frames: longer ones, so the test fits the published frames.
      in.StepsPerFrame = (test.steps + test.steps / 20) / dem::MaxFrames + 1;
      frames = dem::MaxFrames;
    }
    in.Published = static_cast<int>(frames);
  }
  else
  {
    // Settling, or a consolidation: publish some frames, more as it goes on.
    in.Published = untilDone ? 50 : this->NumberOfFrames;
  }
  in.Frame = 0;
  in.Checkpoints[0] = in.Model;
  this->ResumeFromCheckpointFile(input);
  in.BuildTime = this->GetMTime();
  in.InputTime = input ? input->GetMTime() : 0;
  in.Valid = true;
  ++in.Revision;
  this->FrameSteps = static_cast<vtkIdType>(in.StepsPerFrame);

  // Say how long the stage is before it steps.
  const double fixedSteps = static_cast<double>(this->NumberOfFrames) *
    static_cast<double>(in.StepsPerFrame);
  double steps = 0.0;
  std::string covers;
  if (!testing)
  {
    steps = untilDone ? 0.0 : fixedSteps;
    covers = untilDone ? "until the model has settled (length unknown)"
                       : std::to_string(this->NumberOfFrames) + " frames";
  }
  else if (untilDone)
  {
    steps = test.complete ? static_cast<double>(test.steps) : 0.0;
    covers = "until the test finishes: " + test.summary;
  }
  else
  {
    steps = test.complete && test.steps > 0 ? std::min(fixedSteps, static_cast<double>(test.steps))
                                            : fixedSteps;
    covers = std::to_string(this->NumberOfFrames) + " frames (" + test.summary + ")";
  }
  this->EstimatedSteps = steps;
  this->MeasuredThroughput = dem::measureThroughput(in.Model);
  const double particles = static_cast<double>(in.Model.particles.size());
  this->EstimatedRunTime = this->MeasuredThroughput > 0.0
    ? steps * particles / this->MeasuredThroughput
    : 0.0;
  std::ostringstream estimate;
  estimate << "DEM Load Test: frames of " << in.StepsPerFrame << " steps of "
           << dem::formatValue(in.Timestep) << " s (" << dem::formatValue(
                static_cast<double>(in.StepsPerFrame) * in.Timestep)
           << " s of model time per frame";
  if (this->FrameInterval > 0.0 &&
    static_cast<double>(in.StepsPerFrame) * in.Timestep != this->FrameInterval)
  {
    estimate << "; Frame Interval " << dem::formatValue(this->FrameInterval)
             << " s snapped to whole steps";
  }
  estimate << "); the stage runs " << covers << ": ";
  if (steps > 0.0)
  {
    estimate << "about " << dem::formatValue(steps) << " steps of "
             << in.Model.particles.size() << " particles, " << Duration(this->EstimatedRunTime)
             << " of computing at the measured "
             << dem::formatValue(this->MeasuredThroughput) << " particle-steps/s";
  }
  else
  {
    estimate << "length not known ahead";
  }
  estimate << ".";
  if (this->EstimatedRunTime > LongRunSeconds)
  {
    vtkWarningMacro(<< estimate.str()
                    << " It can be stopped between frames (Pause in the GUI) or with Ctrl-C "
                       "in pvpython; a shorter Max Strain, a faster Strain Rate, fewer frames "
                       "or a larger Timestep Safety shortens it.");
  }
  else
  {
    vtkOutputWindowDisplayText((estimate.str() + "\n").c_str());
  }
  // A strain rate far above the suggestion is risky (a strength too high), one far below it
  // wasteful (many more steps for a test already quasi-static): what the atlas measured
  // (dem::strainRateAdvice, dem::slowStrainRateAdvice).
  if (testing && press.mode != dem::TestMode::Isotropic)
  {
    const std::string advice = dem::strainRateAdvice(this->StrainRate, this->SuggestedStrainRate);
    if (!advice.empty())
    {
      vtkWarningMacro(<< "DEM Load Test: " << advice);
    }
    const std::string slow = dem::slowStrainRateAdvice(
      this->StrainRate, this->SuggestedStrainRate, in.Timestep, this->MaxStrain);
    if (!slow.empty())
    {
      vtkWarningMacro(<< "DEM Load Test: " << slow);
    }
  }
  // A cemented specimen narrower than the widths where the atlas's strengths converge is
  // risky, a tension specimen far wider wasteful (dem::resolutionAdvice).
  if (testing)
  {
    const std::string advice =
      dem::resolutionAdvice(dem::grainsAcross(in.Model, press.axis), in.Model, press);
    if (!advice.empty())
    {
      vtkWarningMacro(<< "DEM Load Test: " << advice);
    }
  }
  // A timestep near the stability boundary the atlas measured for this model is risky
  // (dem::timestepSafetyAdvice): the timestep used, as a fraction of the critical one.
  if (in.Simulation->criticalTimestep() > 0.0)
  {
    const std::string advice =
      dem::timestepSafetyAdvice(in.Timestep / in.Simulation->criticalTimestep(),
        dem::bondToContactStiffnessRatio(in.Model), this->SettlingDamping);
    if (!advice.empty())
    {
      vtkWarningMacro(<< "DEM Load Test: " << advice);
    }
  }
  if (!in.Simulation->timestepMessage().empty())
  {
    vtkWarningMacro(<< in.Simulation->timestepMessage());
    this->LastMessageText = in.Simulation->timestepMessage();
  }
  if (!in.GravityNote.empty())
  {
    vtkOutputWindowDisplayText(("DEM Load Test: " + in.GravityNote + "\n").c_str());
  }
}

std::string vtkDEMLoadTest::RunSettings()
{
  // Everything of this stage that shapes its run (not where it is saved, nor Threads:
  // results never depend on the thread count).
  std::ostringstream text;
  text << std::setprecision(17) << "mode " << this->Mode << " axis " << this->Axis
       << " confining " << this->ConfiningStress << " rate " << this->StrainRate << " max "
       << this->MaxStrain << " servo " << this->ServoAlpha << " sample " << this->SampleInterval
       << " continue " << this->ContinueTest << " interval " << this->FrameInterval << " batch "
       << (this->FrameInterval > 0.0 ? 0 : this->StepsPerBatch) << " law " << this->ContactLaw
       << " safety " << this->TimestepSafety << " timestep " << this->RequestedTimestep
       << " damping " << this->SettlingDamping << " consolidation damping " << this->ConsolidationDamping
       << " gravity " << this->Gravity[0] << " "
       << this->Gravity[1] << " " << this->Gravity[2];
  return text.str();
}

void vtkDEMLoadTest::ResumeFromCheckpointFile(vtkMultiBlockDataSet* input)
{
  vtkInternals& in = *this->Internals;
  in.Run = rockdem::RunFingerprint(input, this->RunSettings());
  if (!this->ResumeFromCheckpoint || !this->CheckpointFile || !*this->CheckpointFile)
  {
    return;
  }
  rockdem::CheckpointRecord record;
  if (!rockdem::ReadCheckpointRecord(this->CheckpointFile, record))
  {
    return;
  }
  const std::string file = this->CheckpointFile;
  if (record.run != in.Run || record.stepsPerFrame != in.StepsPerFrame ||
    (this->NumberOfFrames > 0 && record.frame > this->NumberOfFrames))
  {
    vtkOutputWindowDisplayText(("DEM Load Test: the Checkpoint File '" + file +
      "' holds another run (its input or settings differ): computing from the start; the file "
      "is replaced when this run is saved.\n")
                                 .c_str());
    return;
  }
  try
  {
    dem::Model saved = dem::readState(file);
    in.Checkpoints[record.frame] = std::move(saved);
    in.SavedFrame = record.frame;
    in.SavedPath = file;
    if (record.finished)
    {
      in.FinishFrame = record.frame;
    }
    if (this->NumberOfFrames == 0)
    {
      in.Published = std::max(in.Published, record.frame);
    }
    vtkOutputWindowDisplayText(("DEM Load Test: frame " + std::to_string(record.frame) +
      " of this run is taken from the Checkpoint File '" + file +
      "' (written by this stage with the same input and settings), not computed again.\n")
                                 .c_str());
  }
  catch (const std::exception& e)
  {
    vtkWarningMacro(<< "Checkpoint File: " << e.what() << " Computing from the start.");
  }
}

int vtkDEMLoadTest::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInternals& in = *this->Internals;
  // The time comes from the port that asked (the model or the history table).
  int port = 0;
  if (request && request->Has(vtkDemandDrivenPipeline::FROM_OUTPUT_PORT()))
  {
    port = request->Get(vtkDemandDrivenPipeline::FROM_OUTPUT_PORT());
  }
  if (port < 0 || port >= outputVector->GetNumberOfInformationObjects() ||
    !outputVector->GetInformationObject(port)->Has(
      vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
  {
    port = 0;
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(port);
  auto* output = vtkMultiBlockDataSet::GetData(outputVector, 0);
  auto* history = vtkTable::GetData(outputVector, 1);
  auto* input = vtkMultiBlockDataSet::GetData(inputVector[0], 0);
  const auto start = std::chrono::steady_clock::now();
  const int revision = in.Revision;
  std::string stopped;
  int frameAsked = 0;
  try
  {
    if (this->Mode < MODE_OFF || this->Mode > MODE_BRAZILIAN)
    {
      throw dem::InputError("Mode = " + std::to_string(this->Mode) +
        " is out of range: valid modes are Off (0), Compression (1), Tension (2), Triaxial (3), "
        "Isotropic (4), Brazilian (5).");
    }
    const dem::LoadTestSettings press = this->PressSettings();
    dem::validate(press);
    if (!(this->FrameInterval >= 0.0) || !std::isfinite(this->FrameInterval))
    {
      throw dem::InputError("Frame Interval = " + dem::formatValue(this->FrameInterval) +
        " s is out of range: it must be 0 (frames of Steps Per Batch steps) or a finite number "
        "of seconds of at least one timestep.");
    }
    if (this->NumberOfFrames < 0 || this->NumberOfFrames > dem::MaxFrames)
    {
      throw dem::InputError("Number Of Frames = " + std::to_string(this->NumberOfFrames) +
        " is out of range: it must be 0 (until the test finishes) to " +
        std::to_string(dem::MaxFrames) +
        " (a longer run takes a longer Frame Interval, not more frames).");
    }
    if (this->CheckpointEvery < 0)
    {
      throw dem::InputError("Checkpoint Every = " + std::to_string(this->CheckpointEvery) +
        " is out of range: it must be 0 (only the last frame) or more frames.");
    }
    if (this->StepsPerBatch < 1)
    {
      throw dem::InputError("Steps per Batch = " + std::to_string(this->StepsPerBatch) +
        " is out of range: it must be 1 or more.");
    }
    if (this->ContactLaw != HERTZ_MINDLIN && this->ContactLaw != LINEAR)
    {
      throw dem::InputError("Contact Law = " + std::to_string(this->ContactLaw) +
        " is out of range: valid values are 0 (Hertz-Mindlin) and 1 (Linear).");
    }
    for (int k = 0; k < 3; ++k)
    {
      if (!std::isfinite(this->Gravity[k]))
      {
        throw dem::InputError("Gravity has a non-finite component: every component must be a "
                              "finite number (m/s^2).");
      }
    }

    // (Re)build the cache when a parameter or the input changed.
    const bool stale = !in.Valid || this->GetMTime() > in.BuildTime ||
      (input && input->GetMTime() != in.InputTime);
    if (stale)
    {
      this->Start(input);
    }

    // Time requested, snapped to a frame.
    double requested = 0.0;
    if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
    {
      requested = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
    }
    int frame = this->FrameOf(requested);
    frameAsked = frame;
    // The end of the run (what a stage downstream asks for): with Number Of Frames 0,
    // until the test finishes.
    const bool toEnd = requested >= rockdem::EndOfRun;

    if (frame < in.Frame)
    {
      // Back in time: restore the nearest earlier checkpoint and replay.
      auto it = in.Checkpoints.upper_bound(frame);
      --it; // frame 0 is always kept
      in.Model = it->second;
      in.Simulation.reset(new dem::Simulation(in.Model, this->Device()));
      in.Frame = it->first;
      in.Failed = false;
    }
    else if (frame > in.Frame)
    {
      // Forward: start from the latest frame already computed, if it is ahead.
      auto it = in.Checkpoints.upper_bound(frame);
      --it;
      if (it->first > in.Frame)
      {
        in.Model = it->second;
        in.Simulation.reset(new dem::Simulation(in.Model, this->Device()));
        in.Frame = it->first;
      }
    }

    InterruptGuard interrupt;
    auto lastStatus = std::chrono::steady_clock::now() - std::chrono::seconds(2);
    const std::int64_t totalSteps = (frame - in.Frame) * in.StepsPerFrame;
    std::int64_t done = 0;
    stopped = in.Stopped;
    while (in.Frame < frame && !in.Failed && stopped.empty())
    {
      std::int64_t remaining = in.StepsPerFrame;
      while (remaining > 0)
      {
        if (Interrupted || this->GetAbortExecute())
        {
          stopped = Interrupted ? "interrupted (Ctrl-C)" : "aborted";
          in.Stopped = stopped;
          break;
        }
        const std::int64_t batch = std::min<std::int64_t>(remaining, this->StepsPerBatch);
        in.Simulation->advance(batch);
        remaining -= batch;
        done += batch;
        this->UpdateProgress(static_cast<double>(done) / static_cast<double>(totalSteps));
        const auto now = std::chrono::steady_clock::now();
        if (now - lastStatus > std::chrono::seconds(1))
        {
          lastStatus = now;
          const dem::Diagnostics d = in.Simulation->diagnostics();
          std::ostringstream line;
          line << "DEM Load Test: t = " << dem::formatValue(d.time) << " s (frame " << in.Frame
               << "/" << frame << ", step " << d.step << "), elapsed "
               << std::chrono::duration<double>(now - start).count() << " s, RMS displacement "
               << dem::formatValue(d.rmsDisplacement) << " m, kinetic energy "
               << dem::formatValue(d.kineticEnergy) << " J, contacts " << d.contacts
               << ", unbalanced force ratio " << dem::formatValue(d.unbalancedForceRatio) << ", "
               << in.Simulation->path() << "\n";
          vtkOutputWindowDisplayText(line.str().c_str());
        }
      }
      if (!stopped.empty())
      {
        // Back to the last whole frame: published times stay times the model reached.
        auto it = in.Checkpoints.upper_bound(in.Frame);
        --it;
        in.Model = it->second;
        in.Simulation.reset(new dem::Simulation(in.Model, this->Device()));
        in.Frame = it->first;
        break;
      }
      ++in.Frame;
      in.Checkpoints[in.Frame] = in.Model;
      if (this->CheckpointEvery > 0 && in.Frame % this->CheckpointEvery == 0)
      {
        this->WriteCheckpoint();
      }
      // Keep the checkpoints within budget: drop every other one (never frame 0).
      double bytes = 0.0;
      for (const auto& c : in.Checkpoints)
      {
        bytes += ModelBytes(c.second);
      }
      if (bytes > CheckpointBudgetBytes && in.Checkpoints.size() > 2)
      {
        bool drop = false;
        for (auto it = std::next(in.Checkpoints.begin()); it != in.Checkpoints.end();)
        {
          if (drop && it->first != in.Frame)
          {
            it = in.Checkpoints.erase(it);
          }
          else
          {
            ++it;
          }
          drop = !drop;
        }
      }
      // With Number Of Frames 0 the stage ends where the test finished, or (Mode Off)
      // where the model settled: its frames end here. (A fixed Number Of Frames runs on to
      // its last frame; a finished test stands still.)
      const bool finished = this->NumberOfFrames == 0 &&
        (this->Mode != MODE_OFF ? in.Model.test.stage == dem::TestStage::Done
                                : dem::isSettled(in.Simulation->diagnostics()));
      if (finished && in.FinishFrame < 0)
      {
        in.FinishFrame = in.Frame;
        ++in.Revision;
        break;
      }
      if (this->NumberOfFrames == 0 && in.Frame >= in.Published && in.Published < dem::MaxFrames)
      {
        // Not finished at the last frame published: publish more.
        in.Published = static_cast<int>(
          std::min<std::int64_t>(dem::MaxFrames, in.Published + std::max(10, in.Published / 2)));
        ++in.Revision;
      }
      if (toEnd)
      {
        frame = std::max(0, this->LastFrame()); // grows with the frames published
      }
    }
  }
  catch (const dem::InstabilityError& e)
  {
    // The solver restored the last good state: report, output it, stop stepping.
    in.Failed = true;
    vtkErrorMacro(<< e.what());
    this->StatusText = e.what();
  }
  catch (const std::exception& e)
  {
    in.Valid = false;
    in.Simulation.reset();
    vtkErrorMacro(<< e.what());
    this->StatusText = e.what();
    this->LastMessageText = e.what();
    this->StageText = "idle";
    this->Finished = 0;
    this->EstimatedSteps = 0.0;
    this->EstimatedRunTime = 0.0;
    output->Initialize();
    if (history)
    {
      history->Initialize();
    }
    return 0;
  }

  if (in.Frame == this->LastFrame() || in.FinishFrame == in.Frame ||
    in.Model.test.stage == dem::TestStage::Done)
  {
    // The end of the run: the last frame, or a test that has finished (a script that
    // stops at Stage done, as rockdem.run_test does, never asks for the last frame).
    this->WriteCheckpoint();
  }
  this->Finished = in.FinishFrame >= 0 ? (in.Frame >= in.FinishFrame ? 1 : 0)
                                         : (this->NumberOfFrames > 0 && in.Frame >= this->LastFrame() ? 1 : 0);
  // The particles' stresses from the running solver's own lists: those a Simulation made
  // from the frame's state shows (a saved and reloaded frame), without building one.
  const std::vector<dem::StressTensor> stresses =
    dem::particleStresses(in.Model, in.Simulation->freshInteractionForces());
  rockdem::ModelToMultiBlock(in.Model, output, &stresses);
  if (auto* particles = vtkPolyData::SafeDownCast(output->GetBlock(0)))
  {
    // A running model is coloured by how far its particles moved (the default colouring of
    // ParaView is the active scalars); the radius stays the size of the spheres.
    if (particles->GetPointData()->GetArray("Displacement"))
    {
      particles->GetPointData()->SetActiveScalars("Displacement");
    }
  }
  const dem::Diagnostics d = in.Simulation->diagnostics();
  this->CriticalTimestep = in.Simulation->criticalTimestep();
  this->Timestep = in.Simulation->timestep();
  this->CurrentPorosity = dem::currentPorosity(in.Model, in.Simulation->overlaps().volume);
  const dem::BondCounts bondCounts = dem::countBonds(in.Model.bonds);
  this->NumberOfBonds = static_cast<vtkIdType>(bondCounts.installed);
  this->NumberOfBrokenBonds = static_cast<vtkIdType>(bondCounts.broken);
  this->Damage = bondCounts.damage();
  this->BrokenInTension = static_cast<vtkIdType>(bondCounts.tension);
  this->BrokenInShear = static_cast<vtkIdType>(bondCounts.shear);
  this->KineticEnergy = d.kineticEnergy;
  this->NumberOfContacts = static_cast<vtkIdType>(d.contacts);
  this->UnbalancedForceRatio = d.unbalancedForceRatio;
  this->ModelTime = in.Model.clock.time;
  this->CurrentFrame = in.Frame;
  this->SolverPathText = in.Simulation->path();
  const dem::TestMeasurements me = in.Simulation->measurements();
  const int axis = std::max(0, std::min(2, in.Model.test.settings.axis));
  this->StageText = dem::stageName(in.Model.test.stage);
  this->AxialStrain = me.strain[static_cast<std::size_t>(axis)];
  this->VolumetricStrain = me.volumetricStrain;
  this->AxialStress = me.axialStress;
  this->LateralStress = me.lateralStress;
  this->DeviatorStress = me.deviatorStress;
  this->PeakStress = in.Model.test.peakStress;
  const dem::TestMode testMode = in.Model.test.settings.mode;
  this->BrazilianStrength = testMode == dem::TestMode::Brazilian ? in.Model.test.peakStress : 0.0;
  this->TensileStrength = testMode == dem::TestMode::Tension ? std::abs(in.Model.test.peakStress) : 0.0;
  const std::array<double, 2> disc = testMode == dem::TestMode::Brazilian
    ? dem::brazilianDisc(in.Model) : std::array<double, 2>{ { 0.0, 0.0 } };
  this->DiscDiameter = disc[0];
  this->DiscThickness = disc[1];
  this->InertialNumber = me.inertialNumber;
  this->SuggestedStrainRate = me.suggestedStrainRate;
  // The frame's time: a whole number of steps since the start of the stage.
  const double dataTime =
    static_cast<double>(in.Frame) * static_cast<double>(in.StepsPerFrame) * in.Timestep;
  if (history)
  {
    HistoryToTable(in.Model.test, axis, history);
    history->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), dataTime);
    if (this->HistoryFile && *this->HistoryFile)
    {
      try
      {
        WriteTableCSV(history, this->HistoryFile);
      }
      catch (const std::exception& e)
      {
        vtkWarningMacro(<< e.what());
        this->LastMessageText = e.what();
      }
    }
  }
  if (!in.Failed)
  {
    std::ostringstream line;
    line << "t = " << dem::formatValue(dataTime) << " s (frame " << in.Frame << ", step "
         << d.step << ")";
    if (!stopped.empty())
    {
      line << " - " << stopped << ": stopped at the last whole frame (change a property to run again)";
    }
    else if (in.FinishFrame >= 0 && in.Frame >= in.FinishFrame)
    {
      line << (this->Mode != MODE_OFF ? " - the test has finished" : " - settled");
    }
    line << ", elapsed "
         << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
         << " s, RMS displacement " << dem::formatValue(d.rmsDisplacement) << " m, kinetic energy "
         << dem::formatValue(d.kineticEnergy) << " J, contacts " << d.contacts
         << ", unbalanced force ratio " << dem::formatValue(d.unbalancedForceRatio)
         << ", porosity " << dem::formatValue(this->CurrentPorosity) << ", "
         << in.Simulation->path();
    if (!in.CheckpointError.empty())
    {
      line << "; FAILED " << in.CheckpointError;
    }
    this->StatusText = line.str();
    vtkOutputWindowDisplayText(("DEM Load Test: " + line.str() + "\n").c_str());
    if (!stopped.empty() && stopped == in.Stopped && frameAsked > in.Frame)
    {
      vtkWarningMacro(<< "the run was " << stopped << " at frame " << in.Frame
                      << "; it stays there until a property changes.");
    }
  }
  output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), dataTime);
  if (in.Revision != revision)
  {
    // The stage learnt its frames while it ran (its timestep, more frames, its end). They
    // are published on the output now; the next pipeline pass sees a newer pipeline
    // MTime (ComputePipelineMTime), so the information pass runs again downstream and
    // ParaView's post filters and the filters after the stage (DEM Section, Fractures To
    // DFN, ...) copy the new times instead of keeping those published before the run.
    // (Not Modified() here: the executives mark the information up to date after this
    // data pass.) The client proxy then updates their information (vtkSMDEMLoadTestProxy).
    this->PublishTimeSteps(outputVector);
    in.TimesChanged = true;
  }
  return 1;
}

void vtkDEMLoadTest::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Mode: " << this->Mode << "\n";
  os << indent << "FrameInterval: " << this->FrameInterval << " s\n";
  os << indent << "NumberOfFrames: " << this->NumberOfFrames << "\n";
  os << indent << "StepsPerBatch: " << this->StepsPerBatch << "\n";
  os << indent << "ContactLaw: " << this->ContactLaw << "\n";
  os << indent << "TimestepSafety: " << this->TimestepSafety << "\n";
  os << indent << "RequestedTimestep: " << this->RequestedTimestep << " s\n";
  os << indent << "SettlingDamping: " << this->SettlingDamping << "\n";
  os << indent << "Gravity: " << this->Gravity[0] << " " << this->Gravity[1] << " "
     << this->Gravity[2] << " m/s^2\n";
  os << indent << "Threads: " << this->Threads << "\n";
  os << indent << "GPUSolver: " << this->GPUSolver << "\n";
  os << indent << "Axis: " << this->Axis << "\n";
  os << indent << "ConfiningStress: " << this->ConfiningStress << " Pa\n";
  os << indent << "StrainRate: " << this->StrainRate << " 1/s\n";
  os << indent << "MaxStrain: " << this->MaxStrain << "\n";
  os << indent << "ServoAlpha: " << this->ServoAlpha << "\n";
  os << indent << "SampleInterval: " << this->SampleInterval << "\n";
  os << indent << "GripLength: " << this->GripLength << "\n";
  os << indent << "PlatenFriction: " << this->PlatenFriction << "\n";
  os << indent << "ConsolidationDamping: " << this->ConsolidationDamping << "\n";
  os << indent << "Confinement: " << this->Confinement << "\n";
  os << indent << "HistoryFile: " << (this->HistoryFile ? this->HistoryFile : "(none)") << "\n";
  os << indent << "CheckpointFile: " << (this->CheckpointFile ? this->CheckpointFile : "(none)") << "\n";
  os << indent << "CheckpointEvery: " << this->CheckpointEvery << "\n";
  os << indent << "ContinueTest: " << this->ContinueTest << "\n";
  os << indent << "Stage: " << this->StageText << "\n";
  os << indent << "AxialStress: " << this->AxialStress << " Pa\n";
  os << indent << "PeakStress: " << this->PeakStress << " Pa\n";
  os << indent << "CriticalTimestep: " << this->CriticalTimestep << " s\n";
  os << indent << "Timestep: " << this->Timestep << " s\n";
  os << indent << "FrameSteps: " << this->FrameSteps << "\n";
  os << indent << "EstimatedSteps: " << this->EstimatedSteps << "\n";
  os << indent << "EstimatedRunTime: " << this->EstimatedRunTime << " s\n";
  os << indent << "MeasuredThroughput: " << this->MeasuredThroughput << " particle-steps/s\n";
  os << indent << "CurrentPorosity: " << this->CurrentPorosity << "\n";
  os << indent << "KineticEnergy: " << this->KineticEnergy << " J\n";
  os << indent << "NumberOfContacts: " << this->NumberOfContacts << "\n";
  os << indent << "UnbalancedForceRatio: " << this->UnbalancedForceRatio << "\n";
  os << indent << "ModelTime: " << this->ModelTime << " s\n";
  os << indent << "CurrentFrame: " << this->CurrentFrame << "\n";
  os << indent << "Status: " << this->StatusText << "\n";
  os << indent << "SolverPath: " << this->SolverPathText << "\n";
}
