// RockDEM engine: the virtual press (reference guide "Loading the model", "Running a
// triaxial test", "How fast to load"; PHYSICS.md section 4).
//
// The load-test state machine lives in the Model (so a saved run resumes mid-test) and
// is driven by the Simulation each step: it sets the wall velocities (platen at the
// strain rate, servo-controlled faces), and every Sample Interval steps it appends a row
// to the test history. Stresses are compression positive (geomechanics convention),
// strains are shortening positive. SI units: Pa, s, 1/s.
#pragma once

#include "dem/RemovedParticles.h"
#include "dem/SolverState.h"

#include <array>
#include <limits>
#include <cstdint>
#include <string>
#include <vector>

namespace dem {

struct Model;
struct Particles;

enum class TestMode : std::uint8_t { Off = 0, Compression = 1, Tension = 2, Triaxial = 3, Isotropic = 4, Brazilian = 5 };
enum class TestStage : std::uint8_t { Idle = 0, Consolidate = 1, Shear = 2, Done = 3 };
/// How Triaxial and Isotropic confine the specimen's sides: four rigid servo-controlled
/// faces (a box), or a flexible membrane around a cylinder (dem/Membrane.h).
enum class Confinement : std::uint8_t { RigidWalls = 0, Membrane = 1 };

/// The guide's words for modes and stages ("Off", "Compression", ...; "consolidate", "shear").
const char* modeName(TestMode mode);
const char* stageName(TestStage stage);
/// "Rigid Walls", "Membrane".
const char* confinementName(Confinement confinement);

/// Press parameters.
struct LoadTestSettings {
  TestMode mode = TestMode::Off;
  /// Triaxial and Isotropic: rigid side faces, or a membrane around a cylindrical specimen
  /// along Axis (the confining stress on its lateral surface grains). Rigid Walls for files
  /// written before Confinement existed.
  Confinement confinement = Confinement::RigidWalls;
  int axis = 2;                  ///< platen axis: 0 X, 1 Y, 2 Z
  double confiningStress = 1e6;  ///< Pa, Triaxial and Isotropic (> 0 there)
  double strainRate = 0.1;       ///< 1/s, fraction of the starting length per second (> 0)
  double maxStrain = 0.02;       ///< the shearing stage stops at this axial strain, (0, 1)
  double servoAlpha = 0.5;       ///< servo aggressiveness, (0, 1]
  std::int64_t sampleInterval = 100; ///< physics steps between history rows, >= 1
  double settleTolerance = 0.01; ///< servo faces within this relative error count as settled
  /// Tension: the particles whose surface lies within this many largest particle diameters
  /// of each platen are held to it (the grips), dimensionless, > 0. 1 is the grip of state
  /// files written before Grip Length existed.
  double gripLength = 1.0;
  /// Coulomb friction coefficient between the grains and the two platens (the walls on the
  /// test axis), dimensionless, [0, 1]. 0 (the default, and the value of state files
  /// written before Platen Friction existed): lubricated, frictionless platens. A
  /// laboratory's unlubricated steel platens are about 0.2-0.5: they hold the specimen's
  /// ends against its lateral expansion (end restraint). The side walls stay frictionless.
  double platenFriction = 0.0;
  /// Cundall local damping alpha while a Triaxial or Isotropic test consolidates (its
  /// Consolidate stage: the servo faces bring the specimen to the confining stress),
  /// dimensionless, [0, 1); the shear stage runs at the solver's Settling Damping. Bringing
  /// a cemented specimen to sigma3 undamped overshoots and breaks bonds before the shear
  /// (a quarter of them at 20 % of the UCS, Rock.md); the consolidation is a quasi-static
  /// preparation, so it keeps 0.7 when the shear is run undamped. State files written
  /// before Consolidation Damping existed read it as their Settling Damping (what they ran).
  double consolidationDamping = 0.7;
};

struct LoadTestState;
/// The Cundall local damping alpha of the next step: the test's Consolidation Damping while
/// a Triaxial or Isotropic test is in its Consolidate stage, `settlingDamping` (the solver's
/// Settling Damping) otherwise. Both backends take it per step (it changes only at a sample).
double localDamping(const LoadTestState& test, double settlingDamping);

/// Field-by-field equality (two stages with equal settings run the same test).
bool operator==(const LoadTestSettings& a, const LoadTestSettings& b);
inline bool operator!=(const LoadTestSettings& a, const LoadTestSettings& b) { return !(a == b); }

/// Names of the history columns, in order (units in the names).
const std::vector<std::string>& historyColumns();
constexpr std::size_t HistoryColumnCount = 28;
/// State files written before the Gauge Strain column hold the first 27 columns; they read
/// with the gauge strain unknown (NaN).
constexpr std::size_t HistoryColumnCountBeforeGaugeStrain = 27;

/// State of a test in progress (part of the Model).
struct LoadTestState {
  LoadTestSettings settings;
  TestStage stage = TestStage::Idle;
  std::array<double, 3> initialLength{ { 0.0, 0.0, 0.0 } }; ///< m, specimen size at the start
  double initialVolume = 0.0;      ///< m^3
  /// m, centreSpread() of the particles along each unwalled side axis at the start of a
  /// Compression or Tension test: the reference of the lateral strain; and along Axis at
  /// the start of a test (of its shear stage in Triaxial): the reference of the Gauge
  /// Strain. 0 elsewhere (and along Axis in state files written before the gauge strain).
  std::array<double, 3> initialSpread{ { 0.0, 0.0, 0.0 } };
  double peakStress = 0.0;         ///< Pa, largest axial stress so far
  double peakDeviator = 0.0;       ///< Pa, largest axial minus lateral stress so far
  std::int64_t settledChecks = 0;  ///< consecutive samples with every servo face settled
  std::int64_t stepsSinceSample = 0;
  std::vector<std::array<double, HistoryColumnCount>> history; ///< rows, see historyColumns()
};

/// Latest measurements (also the last history row).
struct TestMeasurements {
  std::array<double, 3> strain{ { 0, 0, 0 } };       ///< -, shortening positive, per axis
  double volumetricStrain = 0.0;                      ///< -, sum of the axial strains
  std::array<double, 6> faceStress{ { 0, 0, 0, 0, 0, 0 } }; ///< Pa, compression positive (x-, x+, y-, y+, z-, z+)
  std::array<double, 6> stressTensor{ { 0, 0, 0, 0, 0, 0 } }; ///< Pa, Love-Weber xx yy zz xy yz zx, compression positive
  double axialStress = 0.0;    ///< Pa, mean of the two platen faces
  double lateralStress = 0.0;  ///< Pa, mean of the side faces (0 when unconfined)
  double deviatorStress = 0.0; ///< Pa, axial - lateral
  double meanStress = 0.0;     ///< Pa
  double inertialNumber = 0.0; ///< -, strain rate x mean diameter x sqrt(density / mean stress)
  double suggestedStrainRate = 0.0; ///< 1/s, dem::suggestedStrainRate (dem/StrainRateAdvice.h): inertial number 1e-4 at the estimated peak
  /// -, shortening positive: the axial strain of the specimen itself, 1 - (spread of the
  /// particle centres along Axis) / (that spread at the start), as the laboratory's gauges
  /// on the specimen read it. Unlike the platen strain (Strain X/Y/Z, platen displacement
  /// over the starting length) it leaves out the compliance of the platen-grain contacts
  /// (spheres on a flat platen: Hertz contacts, most of the platen displacement at small
  /// stress). Elastic constants (E, nu) are read from it. NaN where it is not measured
  /// (Mode Off; tests started by older builds, whose state files hold no reference).
  double gaugeStrain = std::numeric_limits<double>::quiet_NaN();
};

/// The Brazilian (indirect tensile) stress at the centre of a disc of the given diameter
/// and thickness (m) squeezed along a diameter by the load (N): 2 P / (pi D t), Pa (ISRM
/// 1978; the elastic solution of Hertz 1883 / Timoshenko and Goodier for a diametral load).
double brazilianStress(double load, double diameter, double thickness);

/// The disc of a Brazilian test (Mode Brazilian) as {diameter D, thickness t} (m): D is
/// the specimen's starting length along Axis (the platens start on the disc), t the slab
/// thickness in a 2D section, else the smaller starting extent across Axis (a disc carved
/// by DEM Specimen is no thicker than its diameter).
std::array<double, 2> brazilianDisc(const Model& model);

/// Spread of the particle centres along an axis (m): their mean absolute deviation from
/// the mean, sum |x_i - xbar| / N, summed in slot order. A homogeneous deformation
/// x' = xbar + (1 + e)(x - xbar) scales it by exactly (1 + e), and one particle that flies
/// off moves it by O(1/N) of its distance, where the particles' extent would follow it
/// all the way. The lateral strain of an unconfined specimen (no side walls) is measured
/// with it: length = initial length x spread / initial spread.
double centreSpread(const Particles& particles, int axis);

/// Throws InputError naming the parameter for an invalid setting (for the given mode).
void validate(const LoadTestSettings& settings);

/// The farthest a platen may move in one timestep, as a fraction of the smallest radius.
/// A platen that moves farther drives grains into one another faster than the contacts can
/// push back within a step, and the run blows up (Documentation/Press.md, "How fast").
constexpr double MaxPlatenTravelPerStep = 0.01;

/// Throws InputError naming Strain Rate when the platen of the model's test (Compression,
/// Tension, Triaxial) would travel more than MaxPlatenTravelPerStep x the smallest radius in
/// one step of `timestep` (s): Strain Rate x starting length x timestep. The message gives
/// the largest Strain Rate this model and timestep can follow.
void validatePlatenSpeed(const Model& model, double timestep);

/// Starts a test on the model: records the specimen size, sets up the walls for the
/// mode (Compression, Brazilian and Tension remove the side walls; Tension attaches the
/// particles within Grip Length of each platen to it) and the first stage. Mode Off restores the six walls at
/// the current box and ends any test. Once the new stage's walls are in place, removes
/// the particles whose centres lie beyond them (beyondActiveWalls: grains that escaped
/// while those walls were down, in an unconfined test) with their bonds and contacts, and
/// returns what it removed (Documentation/Press.md, "Escaped grains"). Throws
/// InputError for invalid settings, for Mode Tension on a model without intact bonds and
/// for grips that would leave no gauge length between them.
RemovedParticles startLoadTest(Model& model, const LoadTestSettings& settings);

/// Whether a stage asked to run `settings` on a model whose test state is `test` continues
/// that test instead of starting a new one (startLoadTest): the test is in progress
/// (consolidate or shear) with exactly these settings, or both are Off (an Off run keeps
/// its walls where they are). A reopened state file continues this way.
bool continuesTest(const LoadTestState& test, const LoadTestSettings& settings);

} // namespace dem
