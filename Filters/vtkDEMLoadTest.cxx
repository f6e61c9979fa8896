#include "vtkDEMLoadTest.h"

#include "vtkDEMModelConversion.h"
#include "vtkDEMPipelineTime.h"

#include "dem/Bonds.h"
#include "dem/Errors.h"
#include "dem/LoadTest.h"
#include "dem/Model.h"
#include "dem/Pack.h"
#include "dem/Simulation.h"
#include "dem/StateFile.h"

#include <vtkDoubleArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkTable.h>

#include <array>
#include <chrono>
#include <cmath>
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
  std::map<int, dem::Model> Checkpoints;
  std::string GravityNote;
  int SavedFrame = -1;     ///< frame last written to SavedPath (-1: none since the rebuild)
  std::string SavedPath;
  std::string CheckpointError; ///< why the last checkpoint failed ("" when it succeeded)
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

vtkDEMLoadTest::vtkDEMLoadTest()
  : Mode(MODE_OFF)
  , FrameInterval(0.01)
  , NumberOfFrames(20)
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

int vtkDEMLoadTest::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // Both ports (model and history table) publish the same frames.
  for (int port = 0; port < outputVector->GetNumberOfInformationObjects(); ++port)
  {
    vtkInformation* outInfo = outputVector->GetInformationObject(port);
    if (!(this->FrameInterval > 0.0) || this->NumberOfFrames < 1)
    {
      // Reported in RequestData; publish no times meanwhile.
      outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
      outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
      continue;
    }
    std::vector<double> times(static_cast<std::size_t>(this->NumberOfFrames) + 1);
    for (std::size_t k = 0; k < times.size(); ++k)
    {
      times[k] = static_cast<double>(k) * this->FrameInterval;
    }
    outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(),
      static_cast<int>(times.size()));
    const double range[2] = { times.front(), times.back() };
    outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  }
  return 1;
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
  try
  {
    if (this->Mode < MODE_OFF || this->Mode > MODE_BRAZILIAN)
    {
      throw dem::InputError("Mode = " + std::to_string(this->Mode) +
        " is out of range: valid modes are Off (0), Compression (1), Tension (2), Triaxial (3), "
        "Isotropic (4), Brazilian (5).");
    }
    dem::LoadTestSettings press;
    press.mode = static_cast<dem::TestMode>(this->Mode);
    press.axis = this->Axis;
    press.confiningStress = this->ConfiningStress;
    press.strainRate = this->StrainRate;
    press.maxStrain = this->MaxStrain;
    press.servoAlpha = this->ServoAlpha;
    press.sampleInterval = this->SampleInterval;
    press.gripLength = this->GripLength;
    dem::validate(press);
    if (!(this->FrameInterval > 0.0) || !std::isfinite(this->FrameInterval))
    {
      throw dem::InputError("Frame Interval = " + dem::formatValue(this->FrameInterval) +
        " s is out of range: it must be greater than 0 s.");
    }
    if (this->NumberOfFrames < 1)
    {
      throw dem::InputError("Number Of Frames = " + std::to_string(this->NumberOfFrames) +
        " is out of range: it must be 1 or more.");
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

    // Time requested, snapped to a frame.
    double requested = 0.0;
    if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
    {
      requested = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
    }
    int frame = static_cast<int>(std::lround(requested / this->FrameInterval));
    frame = std::max(0, std::min(frame, this->NumberOfFrames));

    // (Re)build the cache when a parameter or the input changed.
    const bool stale = !in.Valid || this->GetMTime() > in.BuildTime ||
      (input && input->GetMTime() != in.InputTime);
    if (stale)
    {
      in.Valid = false;
      in.Failed = false;
      in.Checkpoints.clear();
      in.Simulation.reset();
      in.SavedFrame = -1;
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
      in.Simulation.reset(new dem::Simulation(in.Model, this->GPUSolver ? dem::SolverDevice::GPU : dem::SolverDevice::CPU));
      in.StepsPerFrame =
        std::max<std::int64_t>(1, std::llround(this->FrameInterval / in.Simulation->timestep()));
      in.Frame = 0;
      in.Checkpoints[0] = in.Model;
      in.BuildTime = this->GetMTime();
      in.InputTime = input ? input->GetMTime() : 0;
      in.Valid = true;
      if (!in.Simulation->timestepMessage().empty())
      {
        vtkWarningMacro(<< in.Simulation->timestepMessage());
        this->LastMessageText = in.Simulation->timestepMessage();
      }
      if (!in.Simulation->gpuFallbackReason().empty())
      {
        const std::string fallback =
          "GPU Solver: running on the CPU because " + in.Simulation->gpuFallbackReason() + ".";
        vtkWarningMacro(<< fallback);
        this->LastMessageText = fallback;
      }
      if (!in.GravityNote.empty())
      {
        vtkOutputWindowDisplayText(("DEM Load Test: " + in.GravityNote + "\n").c_str());
      }
    }

    if (frame < in.Frame)
    {
      // Back in time: restore the nearest earlier checkpoint and replay.
      auto it = in.Checkpoints.upper_bound(frame);
      --it; // frame 0 is always kept
      in.Model = it->second;
      in.Simulation.reset(new dem::Simulation(in.Model, this->GPUSolver ? dem::SolverDevice::GPU : dem::SolverDevice::CPU));
      in.Frame = it->first;
      in.Failed = false;
    }

    auto lastStatus = std::chrono::steady_clock::now() - std::chrono::seconds(2);
    const std::int64_t totalSteps = (frame - in.Frame) * in.StepsPerFrame;
    std::int64_t done = 0;
    while (in.Frame < frame && !in.Failed)
    {
      std::int64_t remaining = in.StepsPerFrame;
      while (remaining > 0)
      {
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
    output->Initialize();
    if (history)
    {
      history->Initialize();
    }
    return 0;
  }

  if (in.Frame == this->NumberOfFrames || in.Model.test.stage == dem::TestStage::Done)
  {
    // The end of the run: the last frame, or a test that has finished (a script that
    // stops at Stage done, as rockdem.run_test does, never asks for the last frame).
    this->WriteCheckpoint();
  }
  rockdem::ModelToMultiBlock(in.Model, output);
  const dem::Diagnostics d = in.Simulation->diagnostics();
  this->CriticalTimestep = in.Simulation->criticalTimestep();
  this->Timestep = in.Simulation->timestep();
  this->CurrentPorosity = dem::currentPorosity(in.Model);
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
  const double dataTime = static_cast<double>(in.Frame) * this->FrameInterval;
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
    line << "t = " << dem::formatValue(d.time) << " s (frame " << in.Frame << ", step " << d.step
         << "), elapsed "
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
  }
  output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), dataTime);
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
  os << indent << "HistoryFile: " << (this->HistoryFile ? this->HistoryFile : "(none)") << "\n";
  os << indent << "CheckpointFile: " << (this->CheckpointFile ? this->CheckpointFile : "(none)") << "\n";
  os << indent << "CheckpointEvery: " << this->CheckpointEvery << "\n";
  os << indent << "ContinueTest: " << this->ContinueTest << "\n";
  os << indent << "Stage: " << this->StageText << "\n";
  os << indent << "AxialStress: " << this->AxialStress << " Pa\n";
  os << indent << "PeakStress: " << this->PeakStress << " Pa\n";
  os << indent << "CriticalTimestep: " << this->CriticalTimestep << " s\n";
  os << indent << "Timestep: " << this->Timestep << " s\n";
  os << indent << "CurrentPorosity: " << this->CurrentPorosity << "\n";
  os << indent << "KineticEnergy: " << this->KineticEnergy << " J\n";
  os << indent << "NumberOfContacts: " << this->NumberOfContacts << "\n";
  os << indent << "UnbalancedForceRatio: " << this->UnbalancedForceRatio << "\n";
  os << indent << "ModelTime: " << this->ModelTime << " s\n";
  os << indent << "CurrentFrame: " << this->CurrentFrame << "\n";
  os << indent << "Status: " << this->StatusText << "\n";
  os << indent << "SolverPath: " << this->SolverPathText << "\n";
}
