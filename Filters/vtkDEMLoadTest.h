/**
 * @class   vtkDEMLoadTest
 * @brief   The time-stepping stage of a RockDEM pipeline: runs the model.
 *
 * With Mode Off it simply runs its input model (a pack settling under gravity, say); the
 * other modes are the virtual press (Documentation/LoadTest.md): Compression, Tension,
 * Triaxial, Isotropic. Output port 0 is the model; output port 1 ("History") is the test
 * history as a vtkTable (one row every Sample Interval steps).
 *
 * Time (DESIGN.md time contract, Documentation/LoadTest.md "Time"): the stage publishes
 * frames, t_k = k x n x timestep (s, model time since the start of this stage), where a
 * frame is n whole physics steps: n = round(Frame Interval / timestep), or Steps Per Batch
 * when Frame Interval is 0 (the default), so a Play frame is a bounded amount of work.
 * Published times are times the model reaches; until the stage has run once (the
 * timestep is known then) it publishes k x Frame Interval, or only time 0. Number Of
 * Frames 0 (the default) runs until the test finishes (Stage done), or with Mode Off
 * until the model has settled (unbalanced force ratio below 0.01): the stage publishes
 * the frames it estimates the test needs, more when it needs more, and ends its frames
 * at the frame where it finished (a fixed Number Of Frames runs to its last frame). A
 * request for a later time advances the cached state (from the latest
 * in-memory checkpoint at or before it); an earlier time restores the nearest earlier
 * checkpoint and replays (exact, the solver is deterministic); a parameter change or a
 * new input discards the cache. Requests snap to the nearest frame. TimeStepsRevision
 * counts changes of the published times (the client updates its time steps when it
 * changes).
 *
 * Before it steps, a stage estimates its length (Estimated Steps) and how long computing
 * it takes (Estimated Run Time, from a short measurement of this model's stepping speed)
 * and says so in Output Messages, as a warning when it is long. Steps Per Batch bounds the
 * steps between progress updates. A run can be stopped between batches: Ctrl-C (SIGINT)
 * in pvpython or pvbatch, or AbortExecute; the output is then the last whole frame, and the
 * stage stays there until a property changes (a second Ctrl-C ends pvpython as before).
 *
 * If the run goes unstable it stops with an error naming the cause and outputs the
 * last good state.
 *
 * Saving and reopening (Documentation/StateFile.md): with a Checkpoint File the model is
 * written as a RockDEM state file every Checkpoint Every frames and at the last frame
 * (atomically, the history as CSV beside it). An input model whose test is in progress
 * with the same settings as this stage (a model read by DEM State Reader) continues that
 * test instead of starting a new one, so a saved run resumes exactly (Continue Test).
 *
 * Units: SI (s, m/s^2, J).
 */
#ifndef vtkDEMLoadTest_h
#define vtkDEMLoadTest_h

#include "RockDEMFiltersModule.h" // for export macro
#include "vtkMultiBlockDataSetAlgorithm.h"

#include <string> // for the read-only strings

class vtkMultiBlockDataSet;

class vtkInformationVector;
namespace dem
{
struct LoadTestSettings;
enum class SolverDevice;
}

class ROCKDEMFILTERS_EXPORT vtkDEMLoadTest : public vtkMultiBlockDataSetAlgorithm
{
public:
  static vtkDEMLoadTest* New();
  vtkTypeMacro(vtkDEMLoadTest, vtkMultiBlockDataSetAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum ModeType
  {
    MODE_OFF = 0,
    MODE_COMPRESSION = 1,
    MODE_TENSION = 2,
    MODE_TRIAXIAL = 3,
    MODE_ISOTROPIC = 4,
    MODE_BRAZILIAN = 5
  };
  enum ContactLawType
  {
    HERTZ_MINDLIN = 0,
    LINEAR = 1
  };

  ///@{
  /// Loading mode (ModeType). Off: run the model as it is (settling under gravity).
  vtkSetMacro(Mode, int);
  vtkGetMacro(Mode, int);
  ///@}

  ///@{
  /// Platen axis: 0 X, 1 Y, 2 Z (default).
  vtkSetMacro(Axis, int);
  vtkGetMacro(Axis, int);
  ///@}

  ///@{
  /// Stress held by the servo-controlled faces (Triaxial, Isotropic), Pa.
  vtkSetMacro(ConfiningStress, double);
  vtkGetMacro(ConfiningStress, double);
  ///@}

  ///@{
  /// Platen speed as a fraction of the starting length per second, 1/s.
  vtkSetMacro(StrainRate, double);
  vtkGetMacro(StrainRate, double);
  ///@}

  ///@{
  /// The shearing stage stops at this axial strain, -, in (0, 1).
  vtkSetMacro(MaxStrain, double);
  vtkGetMacro(MaxStrain, double);
  ///@}

  ///@{
  /// Servo aggressiveness, (0, 1].
  vtkSetMacro(ServoAlpha, double);
  vtkGetMacro(ServoAlpha, double);
  ///@}

  ///@{
  /// Physics steps between history rows (>= 1).
  vtkSetMacro(SampleInterval, int);
  vtkGetMacro(SampleInterval, int);
  ///@}

  ///@{
  /// Tension: the particles within this many largest particle diameters of each platen
  /// are held to it (the grips), dimensionless, > 0 (default 1).
  /// Triaxial and Isotropic: 0 Rigid Walls (four servo-controlled faces), 1 Membrane (a
  /// flexible membrane around a cylindrical specimen along Axis; dem/Membrane.h).
  vtkSetMacro(Confinement, int);
  vtkGetMacro(Confinement, int);
  vtkSetMacro(GripLength, double);
  vtkGetMacro(GripLength, double);
  ///@}

  ///@{
  /// Coulomb friction between the grains and the two platens, dimensionless, [0, 1]
  /// (default 0: lubricated platens; the side walls are always frictionless).
  vtkSetMacro(PlatenFriction, double);
  vtkGetMacro(PlatenFriction, double);
  ///@}

  ///@{
  /// Cundall local damping while a Triaxial or Isotropic test consolidates, dimensionless,
  /// [0, 1) (default 0.7); the shear stage runs at Settling Damping.
  vtkSetMacro(ConsolidationDamping, double);
  vtkGetMacro(ConsolidationDamping, double);
  ///@}

  ///@{
  /// Optional CSV file the history is written to after every update (empty: none).
  vtkSetStringMacro(HistoryFile);
  vtkGetStringMacro(HistoryFile);
  ///@}

  ///@{
  /// Optional RockDEM state file (.rdem) the model is written to every CheckpointEvery
  /// frames and at the last frame, with the history as CSV beside it (empty: none).
  /// Changing it (or CheckpointEvery) does not discard the computed run.
  void SetCheckpointFile(const char* path);
  vtkGetStringMacro(CheckpointFile);
  ///@}

  ///@{
  /// Frames between checkpoints (>= 0); 0: only at the last frame.
  void SetCheckpointEvery(int frames);
  vtkGetMacro(CheckpointEvery, int);
  ///@}

  ///@{
  /// When the input model has a test in progress (consolidate or shear) with exactly this
  /// stage's settings, or both are Off, continue it rather than start a new test (on by
  /// default: a model read from a state file resumes exactly).
  vtkSetMacro(ContinueTest, int);
  vtkGetMacro(ContinueTest, int);
  vtkBooleanMacro(ContinueTest, int);
  ///@}

  ///@{
  /// When the Checkpoint File holds a frame of this very run (its record names the same
  /// input and settings, vtkDEMCheckpoint.h), take that frame from it instead of computing
  /// it again (on by default: a reloaded state reopens its run without recomputing it).
  vtkSetMacro(ResumeFromCheckpoint, int);
  vtkGetMacro(ResumeFromCheckpoint, int);
  vtkBooleanMacro(ResumeFromCheckpoint, int);
  ///@}

  ///@{
  /// Model time between published time steps, s (>= 0); 0: Steps Per Batch steps per frame.
  /// Snapped to a whole number of steps; shorter than one step is an error.
  vtkSetMacro(FrameInterval, double);
  vtkGetMacro(FrameInterval, double);
  ///@}

  ///@{
  /// Number of frames after the start, 0 .. dem::MaxFrames; 0: until the test finishes
  /// (Mode Off: until the model has settled).
  vtkSetMacro(NumberOfFrames, int);
  vtkGetMacro(NumberOfFrames, int);
  ///@}

  ///@{
  /// Upper bound on physics steps between progress updates (>= 1), and the steps of a
  /// frame when Frame Interval is 0.
  vtkSetMacro(StepsPerBatch, int);
  vtkGetMacro(StepsPerBatch, int);
  ///@}

  ///@{
  /// Contact law: 0 Hertz-Mindlin (default), 1 linear.
  vtkSetMacro(ContactLaw, int);
  vtkGetMacro(ContactLaw, int);
  ///@}

  ///@{
  /// Fraction of the critical timestep used, (0, 1].
  vtkSetMacro(TimestepSafety, double);
  vtkGetMacro(TimestepSafety, double);
  ///@}

  ///@{
  /// Requested timestep, s; 0 = automatic. A value above the safe one is overridden.
  vtkSetMacro(RequestedTimestep, double);
  vtkGetMacro(RequestedTimestep, double);
  ///@}

  ///@{
  /// Cundall local damping alpha, [0, 1); 0 for real dynamics.
  vtkSetMacro(SettlingDamping, double);
  vtkGetMacro(SettlingDamping, double);
  ///@}

  ///@{
  /// Gravity vector, m/s^2. In a 2D section a gravity along Z is turned to -Y (reported).
  vtkSetVector3Macro(Gravity, double);
  vtkGetVector3Macro(Gravity, double);
  ///@}

  ///@{
  /// Threads for large models (0 = all cores). Results never depend on it.
  vtkSetMacro(Threads, int);
  vtkGetMacro(Threads, int);
  ///@}

  ///@{
  /// GPU Solver: run the step on a Vulkan device (off by default). Without a usable device
  /// (no driver, no double precision, too little memory) the run falls back to the CPU
  /// with a warning; Solver Path says which path ran. The same bits on either path.
  vtkSetMacro(GPUSolver, vtkTypeBool);
  vtkGetMacro(GPUSolver, vtkTypeBool);
  vtkBooleanMacro(GPUSolver, vtkTypeBool);
  ///@}

  ///@{
  /// Read-only values of the last update.
  vtkGetMacro(CriticalTimestep, double);   ///< s
  vtkGetMacro(Timestep, double);           ///< s, the step in use
  vtkGetMacro(CurrentPorosity, double);    ///< -
  vtkGetMacro(KineticEnergy, double);      ///< J
  vtkGetMacro(NumberOfContacts, vtkIdType);
  vtkGetMacro(UnbalancedForceRatio, double);
  vtkGetMacro(ModelTime, double);          ///< s, the model clock
  vtkGetMacro(CurrentFrame, int);
  const char* GetStatus() const { return this->StatusText.c_str(); } ///< last status line (or error)
  const char* GetSolverPath() const { return this->SolverPathText.c_str(); } ///< e.g. "CPU serial (...)", "GPU Vulkan: <device>"
  /// The last warning or report (a failed checkpoint or History File, removed escaped
  /// grains, an overridden timestep); empty when none.
  const char* GetLastMessage() const { return this->LastMessageText.c_str(); }
  ///@}

  ///@{
  /// Read-only press measurements of the last update (compression positive).
  const char* GetStage() const { return this->StageText.c_str(); } ///< "idle", "consolidate", ...
  vtkGetMacro(AxialStrain, double);         ///< -, shortening positive
  vtkGetMacro(VolumetricStrain, double);    ///< -
  vtkGetMacro(AxialStress, double);         ///< Pa
  vtkGetMacro(LateralStress, double);       ///< Pa
  vtkGetMacro(DeviatorStress, double);      ///< Pa
  vtkGetMacro(PeakStress, double);          ///< Pa
  /// Pa: Peak Stress of a Brazilian test, 2 P / (pi D t) at the peak load (0 in other modes).
  vtkGetMacro(BrazilianStrength, double);
  /// Pa: the largest pull of a Tension test (magnitude of Peak Stress; 0 in other modes).
  vtkGetMacro(TensileStrength, double);
  /// m: Mode Brazilian, the disc's diameter D and thickness t in 2 P / (pi D t) (0 in other modes).
  vtkGetMacro(DiscDiameter, double);
  vtkGetMacro(DiscThickness, double);
  vtkGetMacro(InertialNumber, double);      ///< -
  vtkGetMacro(SuggestedStrainRate, double); ///< 1/s
  ///@}

  ///@{
  /// Read-only estimate of the stage as set, made before it steps: physics steps from its
  /// start to its end (0 when unknown: a consolidation, or settling with Number Of Frames
  /// 0), and the seconds of computing they take at the stepping speed measured on this
  /// model (particle-steps per second).
  vtkGetMacro(EstimatedSteps, double);
  vtkGetMacro(EstimatedRunTime, double);
  vtkGetMacro(MeasuredThroughput, double);
  ///@}

  /// Read-only: steps in one frame of the current run (0 before it has run).
  vtkGetMacro(FrameSteps, vtkIdType);

  /// Read-only: 1 when the current frame is the end of the run (its last frame, or with
  /// Number Of Frames 0 the frame where the test finished or the model settled).
  vtkGetMacro(Finished, int);

  /// Read-only: how many times the published time steps changed (the stage learns its
  /// timestep, how many frames a test needs, and where it finished, as it runs).
  int GetTimeStepsRevision();

  /// Writes the test history of the current frame as CSV (the engine's columns with a
  /// header; written to a temporary name and renamed). Returns 1 on success; 0 with the
  /// reason in GetLastExportMessage() (also reported as an error).
  int WriteHistory(const char* path);
  const char* GetLastExportMessage() const { return this->LastExportMessage.c_str(); }

  ///@{
  /// Read-only bond counts of the current model (reference guide "Reading damage").
  vtkGetMacro(NumberOfBonds, vtkIdType);       ///< Bonds: installed
  vtkGetMacro(NumberOfBrokenBonds, vtkIdType); ///< Broken Bonds
  vtkGetMacro(Damage, double);                 ///< broken / installed, 0-1
  vtkGetMacro(BrokenInTension, vtkIdType);
  vtkGetMacro(BrokenInShear, vtkIdType);
  ///@}

protected:
  vtkDEMLoadTest();
  ~vtkDEMLoadTest() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;


  int Mode;
  double FrameInterval;
  int NumberOfFrames;
  int StepsPerBatch;
  int ContactLaw;
  double TimestepSafety;
  double RequestedTimestep;
  double SettlingDamping;
  double Gravity[3];
  int Threads;
  vtkTypeBool GPUSolver;
  int Axis = 2;
  double ConfiningStress = 1e6;
  double StrainRate = 0.1;
  double MaxStrain = 0.02;
  double ServoAlpha = 0.5;
  int SampleInterval = 100;
  double GripLength = 1.0;
  double PlatenFriction = 0.0;
  double ConsolidationDamping = 0.7;
  int Confinement = 0;
  char* HistoryFile = nullptr;
  char* CheckpointFile = nullptr;
  int CheckpointEvery = 0;
  int ContinueTest = 1;
  int ResumeFromCheckpoint = 1;

  double CriticalTimestep;
  double Timestep;
  double CurrentPorosity;
  double KineticEnergy;
  vtkIdType NumberOfContacts;
  double UnbalancedForceRatio;
  double ModelTime;
  int CurrentFrame;
  // Read-only values are results, not parameters: setting them must not call Modified().
  std::string StatusText;
  std::string SolverPathText;
  std::string LastMessageText;
  vtkIdType NumberOfBonds = 0;
  vtkIdType NumberOfBrokenBonds = 0;
  double Damage = 0.0;
  vtkIdType BrokenInTension = 0;
  vtkIdType BrokenInShear = 0;
  std::string StageText = "idle";
  double AxialStrain = 0.0;
  double VolumetricStrain = 0.0;
  double AxialStress = 0.0;
  double LateralStress = 0.0;
  double DeviatorStress = 0.0;
  double PeakStress = 0.0;
  double BrazilianStrength = 0.0;
  double TensileStrength = 0.0;
  double DiscDiameter = 0.0;
  double DiscThickness = 0.0;
  double InertialNumber = 0.0;
  double SuggestedStrainRate = 0.0;
  double EstimatedSteps = 0.0;
  double EstimatedRunTime = 0.0;
  double MeasuredThroughput = 0.0;
  vtkIdType FrameSteps = 0;
  int Finished = 0;
  std::string LastExportMessage;

private:
  vtkDEMLoadTest(const vtkDEMLoadTest&) = delete;
  void operator=(const vtkDEMLoadTest&) = delete;

  void WriteCheckpoint();
  /// Publishes the frames on every output (RequestInformation, and RequestData when the
  /// stage learns more about its frames).
  void PublishTimeSteps(vtkInformationVector* outputVector);
  /// Before the stage has run (RequestInformation): Suggested Strain Rate from the input's
  /// cement and the press settings (dem::suggestedStrainRate), when the input has data.
  void EstimateSuggestedStrainRate(vtkMultiBlockDataSet* input);
  /// The frame a requested time asks for (snapped, clamped to the published frames).
  int FrameOf(double time);
  /// The press settings of this stage's properties (Mode, Axis, Confining Stress, ...).
  dem::LoadTestSettings PressSettings() const;
  /// The pipeline MTime is this filter's, or later when its last RequestData published
  /// new times (then the information pass runs again downstream).
  int ComputePipelineMTime(vtkInformation* request, vtkInformationVector** inInfoVec,
    vtkInformationVector* outInfoVec, int requestFromOutputPort, vtkMTimeType* mtime) override;
  /// The device GPU Solver asks for.
  dem::SolverDevice Device() const;
  /// The published frames, 0 .. LastFrame(); -1: nothing to publish (invalid settings).
  int LastFrame();
  /// Builds the cache from the input (the stage starts).
  void Start(vtkMultiBlockDataSet* input);
  /// The settings that shape the run, as text (part of the run's fingerprint).
  std::string RunSettings();
  /// Fingerprints the run and, when the Checkpoint File holds a frame of it, keeps that frame.
  void ResumeFromCheckpointFile(vtkMultiBlockDataSet* input);

  struct vtkInternals;
  vtkInternals* Internals;
};

#endif
