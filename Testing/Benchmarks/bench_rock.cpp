// Rock behaviour benchmark: builds a dense cemented specimen (Compact Elements, then DEM
// Cement over a Bond Range) and runs the laboratory tests on it with the engine, printing
// the figures of Documentation/Rock.md: porosity, bonded coordination, UCS, E,
// nu, direct tensile strength, UCS / sigma_t, triaxial peaks and the Mohr-Coulomb fit, the
// share of broken bonds near the platens when the unconfined stress has fallen to 70 % of
// its peak, and the DFN (DEM Fractures To DFN at default settings) of that frame.
//
//   rockdem_bench_rock [--particles 10000] [--range 1.4] [--tests ucs,tension,triaxial]
//                      [--confining 0.05,0.1,0.2] [--tensile 1e6] [--cohesion 4e6]
//                      [--moment-contribution 1] [--rate-factor F] ...
//   rockdem_bench_rock --tests rates --rate-factors 0.0625,0.25,1,4,16,64
//     unconfined tests at those multiples of the Suggested Strain Rate on one specimen,
//     one "rate-sweep:" line each (examples/speed_accuracy_atlas.py reads them);
//     --inertial-target I: the suggestion at inertial number I (the engine's rule otherwise);
//     --rate-factor F loads at F x the Suggested Strain Rate known before the test
//     (dem::suggestedStrainRate) instead of --strain-per-step, and the UCS line is followed
//     by a "rate:" line (rate, suggestion, inertial number at the peak, unbalanced force
//     ratio up to it), read by examples/speed_accuracy_atlas.py
//   rockdem_bench_rock --tests tension,brazilian: a Brazilian disc (diameter = width, thickness
//     width / 2) carved from the same pack, its strength over the direct tensile strength.
//   rockdem_bench_rock --tests envelopes --specimen both --sigma3 1e6,2e6,4e6 [--dump DIR]
//     triaxial tests at absolute confining stresses on a box (rigid walls) and on a cylinder
//     carved from the same pack (Confinement Membrane), both cemented alike; each prints its
//     peaks and Mohr-Coulomb fit ("envelope" lines, read by scripts/plot_envelopes.py);
//     --dump writes DIR/membrane_failed.csv, the cylinder after its highest-stress test, with
//     each grain's displacement to the start of shear, the peak and the fall to 90 % of it and
//     the bonds broken after the peak (scripts/plot_localisation.py), and a "membrane frames"
//     line; --triaxial-stop F (default 0.8) runs a triaxial test after its peak until the
//     stress has fallen to F x the peak (or Max Strain), to see the deformation later.
//   rockdem_bench_rock --tests tsmap --safeties 0.05,0.3,1,2 --bond-ratios 0.1,1,10,100 [--rate-factor 16]
//   rockdem_bench_rock --tests servomap --dampings 0,0.7,0.95 --servo-alphas 0.05,0.5,1 [--rate-factor 16]
//     the stability map of Documentation/SpeedAccuracy.md: tsmap, unconfined tests at each
//     Timestep Safety (above 1: that multiple of the critical timestep, forced) on a specimen
//     cemented at each Bond Modulus / grain Young's modulus ratio; servomap, triaxial tests
//     (--sigma3's first value) at each Settling Damping and Servo Alpha (at --safety, on the
//     specimen cemented at --bond-modulus); one "stability:" line each with
//     whether the engine stopped the run (InstabilityError, its message on the next line),
//     the peak, the confining stress error of the servo, the largest grain speed against the
//     P-wave speed sqrt(E / density), and the count of non-finite values in what the run
//     left (every sample's measurements, the model after the run: particles, walls, bonds,
//     test history), which must be 0.
//   --bond-modulus B: Bond Modulus B (Pa) instead of --modulus; --servo-alpha A; --max-steps N
//     stops a test after N steps; --to-max-strain: the stability runs go on to Max Strain.
//   --consolidation-damping D (default 0.7): the triaxial tests' Consolidation Damping (they
//     shear at --damping; each triaxial line also prints the bonds broken when the shear
//     started; --tests servomap sweeps the damping of the whole test). --ucs P: the triaxial
//     series' confining stresses are fractions of P (Pa) when --tests has no ucs.
//   --min-peak-strain S: the stop rule (the stress fallen to 70 %, triaxial 80 %, of its peak)
//     counts a peak only at an axial strain of S or more (default 1 % of --max-strain), so
//     that the stress oscillation at the start of an undamped test does not end it.
//   --dump DIR with --tests ucs also writes DIR/ucs_failed.csv, the unconfined specimen at the
//     frame where the stress has fallen to 70 % of the peak (scripts/plot_failed_specimen.py),
//     and DIR/ucs_failed.rdem, the model at that frame (a state file: DEM Fractures To DFN,
//     the pictures or a further test can be run on it).
//   --tests ucs,tension --specimen cylinder|both: the unconfined and direct tension tests (and
//     the localisation figures, the DFN, --dump's DIR/ucs_failed_cylinder.csv) also, or only, on
//     the cylinder that --tests envelopes carves (diameter = the box's width, length = its
//     height, cut before the cement: its curved side is a carved surface, its ends the pack's
//     walled faces); the box's lines are as before, the cylinder's start with "cylinder".
//   --carve-margin M (mean grain diameters, default 0): the pack a cylinder is carved from is
//     the box specimen's pack widened by M nominal mean diameters (rmin + rmax) on each side
//     face (holding proportionally more grains; the same height: the ends stay the pack's flat
//     walled faces, as ground ends), so that the cylinder's curved side touches no wall;
//     0: the cylinder inscribed in the box specimen's own pack, as before.
//   --contact-law hertz|linear: the grains' contact law (default hertz, Hertz-Mindlin), set
//     before Compact Elements so that the pack is compacted, cemented and tested with it.
//   --dimension 2 [--slab T]: a 2D section instead: discs in the XY plane (slab thickness T,
//     default 2 mm), a W x aspect W rectangle compacted to --porosity (default 0.16 in 2D,
//     0.36 in 3D), loaded along Y; --tests ucs, tension, triaxial and rates (the others
//     and --specimen cylinder are refused).
//   --depth D (3D, mean diameters): a slab instead of the square cross-section: the box is W x
//     D (rmin + rmax) x aspect W (X x Y x Z, loaded along Z), W from the particle count at
//     --porosity as before; 0 (default): W x W x aspect W. A slab of the width of a 2D section
//     (examples/speed_accuracy_atlas.py, section "dims"). Only with --specimen box and the
//     tests that load the box (ucs, tension, triaxial, rates, tsmap, servomap).
//   --device cpu|gpu: the tests step on the CPU backend (default) or request the GPU (Vulkan)
//     backend (dem::SolverDevice::GPU; the CPU when no device can run it); each test's path
//     ("CPU serial ...", "GPU Vulkan: <device>", or the fallback and why) is printed on a
//     "path:" line (--tests rates: "rate-sweep-path:").
// Every option is listed by --help. SI units.
#include "CommaList.h"
#include "dem/Bonds.h"
#include "dem/Cement.h"
#include "dem/Errors.h"
#include "dem/Fractures.h"
#include "dem/LoadTest.h"
#include "dem/Membrane.h"
#include "dem/Pack.h"
#include "dem/Specimen.h"
#include "dem/StateFile.h"
#include "dem/Random.h"
#include "dem/Simulation.h"
#include "dem/StrainRateAdvice.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <unordered_map>
#include <string>
#include <vector>

using namespace dem;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Options {
  long particles = 10000;
  int dimension = 3;            // 3: spheres in a box loaded along Z; 2: discs in the XY plane loaded along Y
  double aspect = 2.0;          // specimen height / width
  double rmin = 0.001;          // m
  double rmax = 0.002;          // m
  double porosity = -1.0;       // Compact Elements target; < 0: 0.36 (3D), 0.16 (2D)
  double slab = 0.002;          // m, 2D: the slab thickness (a disc weighs rho pi r^2 t, a bond's section is 2 r t)
  double depth = 0.0;           // 3D: > 0, the box's Y size in nominal mean diameters (rmin + rmax); 0: square (Y = X)
  double modulus = 1e8;         // Pa, grains and bonds
  double friction = 0.5;
  double rolling = 0.0;
  double range = 1.4;
  double gap = 0.05;
  double multiplier = 1.0;
  double ratio = 0.4;           // bond stiffness ratio
  double tensile = 1e6;         // Pa
  double cohesion = 4e6;        // Pa
  double bondFriction = 30.0;   // degrees
  double beta = 1.0;            // moment contribution factor
  double softening = 0.0;       // Softening Ratio (tension softening; 0 = brittle)
  double scatter = 0.2;
  double strainPerStep = 2e-7;  // platen strain per step (sets the strain rate)
  double rateFactor = 0.0;      // > 0: the strain rate is this x the Suggested Strain Rate (overrides --strain-per-step)
  double inertialTarget = 0.0;  // > 0: the suggestion at this inertial number instead of the engine's target
  double safety = 0.3;
  double damping = 0.7;
  double consolidationDamping = 0.7; // Consolidation Damping of the triaxial tests (the shear: --damping)
  double maxStrain = 0.03;
  double minPeakStrain = -1.0;  // the stop rule's smallest peak strain; < 0: 1 % of maxStrain
  double platenFriction = 0.0;  // Platen Friction of the compression and triaxial tests
  double bondModulus = 0.0;     // Pa; 0: --modulus
  double servoAlpha = 0.5;      // Servo Alpha of the triaxial tests
  double maxSteps = 0.0;        // > 0: a test stops after this many steps
  double ucs = 0.0;             // > 0: the triaxial series' reference UCS (Pa), when --tests has no ucs
  double triaxialStop = 0.8;    // a triaxial test stops when its stress falls to this fraction of the peak
  bool probeToMaxStrain = false; // --tests stability: run every test to Max Strain (no stop after the peak)
  std::vector<double> safeties{ 0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0, 1.5 }; // --tests stability
  std::vector<double> bondRatios{ 0.1, 1.0, 10.0, 100.0 };                // x --modulus
  std::vector<double> dampings{ 0.0, 0.3, 0.7, 0.9, 0.95 };
  std::vector<double> servoAlphas{ 0.05, 0.2, 0.5, 1.0 };
  std::string tests = "ucs,tension";
  std::vector<double> confining{ 0.05, 0.1, 0.2 }; // x UCS
  std::vector<double> sigma3{ 1e6, 2e6, 4e6 };     // Pa, --tests envelopes
  std::vector<double> rateFactors;                 // --tests rates: x the Suggested Strain Rate
  std::string specimen = "box";                    // box, cylinder, both (--tests envelopes, ucs, tension)
  double carveMargin = 0.0;                        // mean diameters of pack around a carved cylinder
  std::string dump;                                // directory for membrane_failed.csv
  std::uint64_t seed = 1;
  int threads = 0;
  bool profile = false;         // print the broken-bond profile along the axis
  bool lengthStiffness = false; // experiment: kn = Bond Modulus / (bond length at cementing)
  ContactLaw contactLaw = ContactLaw::HertzMindlin; // --contact-law hertz|linear: the grains' law from the pack on
  SolverDevice device = SolverDevice::CPU;          // --device cpu|gpu: where the tests step
};

Options parse(int argc, char** argv)
{
  Options o;
  std::map<std::string, double*> doubles = { { "--aspect", &o.aspect }, { "--rmin", &o.rmin },
    { "--rmax", &o.rmax }, { "--porosity", &o.porosity }, { "--modulus", &o.modulus },
    { "--friction", &o.friction }, { "--rolling", &o.rolling }, { "--range", &o.range },
    { "--gap", &o.gap }, { "--multiplier", &o.multiplier }, { "--ratio", &o.ratio },
    { "--tensile", &o.tensile }, { "--cohesion", &o.cohesion }, { "--bond-friction", &o.bondFriction },
    { "--moment-contribution", &o.beta }, { "--softening", &o.softening },
    { "--scatter", &o.scatter }, { "--strain-per-step", &o.strainPerStep }, { "--safety", &o.safety },
    { "--damping", &o.damping }, { "--consolidation-damping", &o.consolidationDamping }, { "--max-strain", &o.maxStrain },
    { "--platen-friction", &o.platenFriction }, { "--rate-factor", &o.rateFactor },
    { "--inertial-target", &o.inertialTarget }, { "--bond-modulus", &o.bondModulus },
    { "--servo-alpha", &o.servoAlpha }, { "--max-steps", &o.maxSteps },
    { "--min-peak-strain", &o.minPeakStrain }, { "--triaxial-stop", &o.triaxialStop }, { "--ucs", &o.ucs },
    { "--carve-margin", &o.carveMargin }, { "--slab", &o.slab }, { "--depth", &o.depth } };
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (doubles.count(a) && i + 1 < argc) {
      *doubles[a] = std::atof(argv[++i]);
    } else if (a == "--dimension" && i + 1 < argc) {
      o.dimension = std::atoi(argv[++i]);
    } else if (a == "--particles" && i + 1 < argc) {
      o.particles = std::atol(argv[++i]);
    } else if (a == "--tests" && i + 1 < argc) {
      o.tests = argv[++i];
    } else if (a == "--confining" && i + 1 < argc) {
      o.confining = rockdem_bench::parseList<double>(argv[++i]);
    } else if (a == "--rate-factors" && i + 1 < argc) {
      o.rateFactors = rockdem_bench::parseList<double>(argv[++i]);
    } else if (a == "--safeties" && i + 1 < argc) {
      o.safeties = rockdem_bench::parseList<double>(argv[++i]);
    } else if (a == "--bond-ratios" && i + 1 < argc) {
      o.bondRatios = rockdem_bench::parseList<double>(argv[++i]);
    } else if (a == "--dampings" && i + 1 < argc) {
      o.dampings = rockdem_bench::parseList<double>(argv[++i]);
    } else if (a == "--servo-alphas" && i + 1 < argc) {
      o.servoAlphas = rockdem_bench::parseList<double>(argv[++i]);
    } else if (a == "--sigma3" && i + 1 < argc) {
      o.sigma3 = rockdem_bench::parseList<double>(argv[++i]);
    } else if (a == "--specimen" && i + 1 < argc) {
      o.specimen = argv[++i];
    } else if (a == "--dump" && i + 1 < argc) {
      o.dump = argv[++i];
    } else if (a == "--seed" && i + 1 < argc) {
      o.seed = static_cast<std::uint64_t>(std::atol(argv[++i]));
    } else if (a == "--threads" && i + 1 < argc) {
      o.threads = std::atoi(argv[++i]);
    } else if (a == "--profile") {
      o.profile = true;
    } else if (a == "--to-max-strain") {
      o.probeToMaxStrain = true;
    } else if (a == "--length-stiffness") {
      o.lengthStiffness = true;
    } else if (a == "--contact-law" && i + 1 < argc) {
      const std::string law = argv[++i];
      if (law != "hertz" && law != "linear") {
        std::fprintf(stderr, "--contact-law = %s is not a contact law: use hertz or linear\n", law.c_str());
        std::exit(2);
      }
      o.contactLaw = law == "linear" ? ContactLaw::Linear : ContactLaw::HertzMindlin;
    } else if (a == "--device" && i + 1 < argc) {
      const std::string device = argv[++i];
      if (device != "cpu" && device != "gpu") {
        std::fprintf(stderr, "--device = %s is not a device: use cpu or gpu\n", device.c_str());
        std::exit(2);
      }
      o.device = device == "gpu" ? SolverDevice::GPU : SolverDevice::CPU;
    } else {
      std::fprintf(stderr, "usage: %s [--particles N] [--tests ucs,tension,triaxial,brazilian,envelopes] [--confining f1,f2,..]"
                           " [--specimen box|cylinder|both] [--dimension 3|2] [--seed S] [--threads T] [--profile] [--contact-law hertz|linear]"
                           " [--device cpu|gpu]", argv[0]);
      for (const auto& d : doubles) {
        std::fprintf(stderr, " [%s %g]", d.first.c_str(), *d.second);
      }
      std::fprintf(stderr, "\n");
      std::exit(2);
    }
  }
  if (!(o.triaxialStop > 0.0 && o.triaxialStop < 1.0)) {
    std::fprintf(stderr, "--triaxial-stop = %g is out of range: valid range is (0, 1) (a fraction of the peak)\n",
                 o.triaxialStop);
    std::exit(2);
  }
  if (o.specimen != "box" && o.specimen != "cylinder" && o.specimen != "both") {
    std::fprintf(stderr, "--specimen = %s: valid values are box, cylinder, both\n", o.specimen.c_str());
    std::exit(2);
  }
  if (!(o.carveMargin >= 0.0)) {
    std::fprintf(stderr, "--carve-margin = %g is out of range: valid range is [0, inf) (mean diameters)\n", o.carveMargin);
    std::exit(2);
  }
  if (o.dimension != 2 && o.dimension != 3) {
    std::fprintf(stderr, "--dimension = %d: valid values are 3 (spheres) and 2 (discs in the XY plane)\n", o.dimension);
    std::exit(2);
  }
  if (o.dimension == 2) {
    // The 2D specimen is a W x aspect W section loaded along Y; the carved specimens and the
    // map sweeps are built for the 3D box only.
    for (const char* test : { "brazilian", "envelopes", "tsmap", "servomap" }) {
      if (o.tests.find(test) != std::string::npos) {
        std::fprintf(stderr, "--tests %s is not available with --dimension 2 (valid there: ucs, tension, triaxial, rates)\n", test);
        std::exit(2);
      }
    }
    if (o.specimen != "box") {
      std::fprintf(stderr, "--specimen = %s is not available with --dimension 2 (valid there: box)\n", o.specimen.c_str());
      std::exit(2);
    }
    if (!(o.slab > 0.0)) {
      std::fprintf(stderr, "--slab = %g m is out of range: valid range is (0, inf)\n", o.slab);
      std::exit(2);
    }
  }
  if (o.depth != 0.0) {
    // A slab: a 3D box whose Y size is set apart from its width; the carved specimens assume
    // the square cross-section.
    if (!(o.depth >= 1.0 && o.depth <= 1000.0)) {
      std::fprintf(stderr, "--depth = %g mean diameters is out of range: valid range is [1, 1000] (0, the default: "
                           "a square cross-section)\n", o.depth);
      std::exit(2);
    }
    if (o.dimension == 2) {
      std::fprintf(stderr, "--depth = %g is not available with --dimension 2 (a 2D section's thickness is --slab, in m)\n",
                   o.depth);
      std::exit(2);
    }
    if (o.specimen != "box") {
      std::fprintf(stderr, "--depth = %g is not available with --specimen %s (valid there: box)\n", o.depth,
                   o.specimen.c_str());
      std::exit(2);
    }
    for (const char* test : { "brazilian", "envelopes" }) {
      if (o.tests.find(test) != std::string::npos) {
        std::fprintf(stderr, "--tests %s is not available with --depth (valid there: ucs, tension, triaxial, rates, tsmap, servomap)\n",
                     test);
        std::exit(2);
      }
    }
  }
  if (o.porosity < 0.0) {
    o.porosity = o.dimension == 2 ? 0.16 : 0.36;
  }
  if (!(o.porosity > 0.0 && o.porosity < 1.0)) {
    std::fprintf(stderr, "--porosity = %g is out of range: valid range is (0, 1)\n", o.porosity);
    std::exit(2);
  }
  return o;
}

/// The loading axis: Z for a 3D specimen, Y for a 2D section (discs in the XY plane).
int loadAxis(const Model& m)
{
  return m.domain.section2D ? 1 : 2;
}

/// The lateral axes of the specimen (not the loading axis; in 2D X only).
std::vector<int> lateralAxes(const Model& m)
{
  return m.domain.section2D ? std::vector<int>{ 0 } : std::vector<int>{ 0, 1 };
}

double secondsSince(std::chrono::steady_clock::time_point t)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

/// The specimen: a W x W x aspect W box holding about `particles` grains at the target
/// porosity, placed, compacted and cemented.
enum class Carve { None, Cylinder, BrazilianDisc };

Model buildSpecimen(const Options& o, CementReport& cemented, CompactReport& compacted, Carve carve = Carve::None)
{
  Model m;
  const double a = o.rmin;
  const double b = o.rmax;
  const bool planar = o.dimension == 2;
  // Mean grain volume for radii uniform in [a, b] (3D: 4/3 pi E[r^3]; 2D: pi t E[r^2]).
  const double meanVolume = planar ? kPi * o.slab * (a * a + a * b + b * b) / 3.0
                                   : 4.0 / 3.0 * kPi * (a + b) * (a * a + b * b) / 4.0;
  const double volume = o.particles * meanVolume / (1.0 - o.porosity);
  // A slab (--depth): Y is depth x the nominal mean diameter, X and Z share the rest.
  const double depth = o.depth > 0.0 ? o.depth * (a + b) : 0.0;
  const double width = planar ? std::sqrt(volume / (o.slab * o.aspect))
                              : depth > 0.0 ? std::sqrt(volume / (depth * o.aspect)) : std::cbrt(volume / o.aspect);
  // The specimen's box; a cylinder carved with a margin comes from a pack that much wider on
  // each side (not longer: its ends stay the pack's flat walled faces, as a laboratory grinds
  // a core's ends flat; carved ends are rough and the platens crush the grains that stick
  // out), at the same grain density (the grain count scales with the volume).
  const Vec3 specimenSize = planar ? Vec3(width, o.aspect * width, o.slab)
                                    : Vec3(width, depth > 0.0 ? depth : width, o.aspect * width);
  m.domain.section2D = planar;
  const double margin = carve == Carve::Cylinder ? o.carveMargin * (o.rmin + o.rmax) : 0.0;
  m.domain.size = specimenSize + Vec3(2.0 * margin, 2.0 * margin, 0.0);
  const double packScale = m.domain.size.prod() / specimenSize.prod();
  m.material.youngsModulus = o.modulus;
  m.material.friction = o.friction;
  m.material.rollingFriction = o.rolling;
  m.gravity.setZero();
  m.solver.threads = o.threads;
  m.solver.contactLaw = o.contactLaw; // compacted, cemented and tested with the same law
  m.solver.parallelThreshold = o.threads == 1 ? 1000000000 : 0;
  PackParameters p;
  p.initialElements = static_cast<std::int64_t>(std::llround(static_cast<double>(o.particles) * packScale));
  p.minimumSize = a;
  p.maximumSize = b;
  p.randomSeed = o.seed;
  // Placed loose, at porosity 0.7 (2D: 0.45) in a box `grow` times larger, then the whole
  // pack is scaled down into the specimen box; Compact Elements grows the radii back. A 2D
  // section keeps its slab (and its discs at mid-slab).
  const Vec3 full = m.domain.size;
  const double grow = planar ? std::sqrt((1.0 - o.porosity) / 0.55) : std::cbrt((1.0 - o.porosity) / 0.3);
  m.domain.size = planar ? Vec3(full.x() * grow, full.y() * grow, full.z()) : Vec3(full * grow);
  buildPack(m, p);
  for (std::size_t i = 0; i < m.particles.size(); ++i) {
    Vec3& x = m.particles.position[i];
    x.x() /= grow;
    x.y() /= grow;
    if (!planar) {
      x.z() /= grow;
    }
    m.particles.radius[i] /= grow;
  }
  m.domain.size = full;
  updateMassProperties(m);
  CompactParameters c;
  c.targetPorosity = o.porosity;
  compacted = compactElements(m, c);
  if (carve != Carve::None) {
    // Carved before the cement as in the laboratory workflow (Documentation/Specimens.md):
    // the cylinder of the box specimen's width and height at the pack's centre (inscribed in
    // it without --carve-margin; its ends are the pack's end faces either way), or the
    // Brazilian disc at the box's centre (diameter = width, thickness = width / 2, axis Z).
    SpecimenSettings shape;
    shape.shape = carve == Carve::Cylinder ? SpecimenShape::Cylinder : SpecimenShape::Disc;
    shape.axis = 2;
    shape.diameter = specimenSize.x();
    shape.length = carve == Carve::Cylinder ? specimenSize.z() : 0.5 * specimenSize.x();
    carveSpecimen(m, shape);
  }
  CementParameters cp;
  cp.bondRange = o.range;
  cp.gapTolerance = o.gap;
  cp.bondRadiusMultiplier = o.multiplier;
  cp.bondModulus = o.bondModulus > 0.0 ? o.bondModulus : o.modulus;
  cp.bondStiffnessRatio = o.ratio;
  cp.tensileStrength = o.tensile;
  cp.cohesion = o.cohesion;
  cp.frictionAngle = o.bondFriction;
  cp.momentContribution = o.beta;
  cp.softeningRatio = o.softening;
  cp.strengthScatter = o.scatter;
  cp.randomSeed = o.seed;
  cemented = cement(m, cp);
  if (o.lengthStiffness) {
    std::map<std::int64_t, std::size_t> slot;
    for (std::size_t i = 0; i < m.particles.size(); ++i) {
      slot[m.particles.id[i]] = i;
    }
    for (std::size_t k = 0; k < m.bonds.size(); ++k) {
      const std::size_t i = slot[m.bonds.idA[k]];
      const std::size_t j = slot[m.bonds.idB[k]];
      const double length = (m.particles.position[j] - m.particles.position[i]).norm();
      const double contact = m.particles.radius[i] + m.particles.radius[j];
      const double factor = contact / std::max(length, contact);
      m.bonds.normalStiffness[k] *= factor;
      m.bonds.shearStiffness[k] *= factor;
    }
  }
  m.solver.timestepSafety = o.safety;
  m.solver.settlingDamping = o.damping;
  return m;
}

struct TestResult {
  double peak = 0.0;          // Pa (tension: the largest pull, positive)
  double peakStrain = 0.0;
  double E = 0.0, nu = 0.0;
  std::size_t broken = 0;
  double seconds = 0.0;
  std::int64_t steps = 0;
  double nearPlatens = 0.0;   // share of broken bonds within two mean diameters of a platen
  std::string dfn;
  std::size_t discs = 0;
  double largestDisc = 0.0;   // m
  double discShare = 0.0;     // broken bonds in discs / broken bonds
  double strainAt70 = 0.0;
  std::size_t brokenAtPeak = 0; // broken bonds at the sample of the peak stress
  std::size_t brokenAtShear = 0; // broken bonds when the shear stage starts (after the consolidation)
  std::size_t softeningAtPeak = 0; // intact bonds past their strength (damage > 0) then
  std::string damage;           // damageBreakdown at the end
  std::string earlyBreaks;      // failureCauses: what broke the first 10 % of the breaks at the peak
  bool peaked = false;        // the stress fell after its peak (to 70 %, triaxial 80 %) within Max Strain
  double strainRate = 0.0;    // 1/s, of the test
  double suggested = 0.0;     // 1/s, Suggested Strain Rate before the test (dem::suggestedStrainRate)
  double target = 0.0;        // the inertial number the suggestion aims at
  double timestep = 0.0;      // s
  double inertialAtPeak = 0.0;  // inertial number at the peak sample
  double ufrBeforePeak = 0.0;   // mean unbalanced force ratio over the samples up to the peak
  std::string path;             // where the test stepped (Simulation::path())
};

/// Broken bonds near the platens (within two mean diameters of either end of the specimen
/// along the loading axis, at their failure positions), over all broken bonds; optional profile.
double platenShare(const Model& m, bool profile)
{
  const int ax = loadAxis(m);
  const Wall& low = m.walls[2 * ax];
  const Wall& high = m.walls[2 * ax + 1];
  const double band = 2.0 * meanParticleDiameter(m);
  std::size_t near = 0, all = 0;
  const int bins = 10;
  std::vector<std::size_t> histogram(bins, 0);
  for (std::size_t k = 0; k < m.bonds.size(); ++k) {
    if (!m.bonds.broken(k)) {
      continue;
    }
    ++all;
    const double z = m.bonds.failurePosition[k][ax];
    near += (z - low.position < band || high.position - z < band) ? 1 : 0;
    const int bin = std::clamp(static_cast<int>((z - low.position) / (high.position - low.position) * bins), 0, bins - 1);
    ++histogram[bin];
  }
  if (profile && all > 0) {
    std::printf("    broken-bond profile along %c (low platen first, %d bins):", "XYZ"[ax], bins);
    for (std::size_t h : histogram) {
      std::printf(" %.3f", static_cast<double>(h) / all);
    }
    std::printf("\n");
  }
  return all ? static_cast<double>(near) / all : 0.0;
}

/// Where and how the bonds broke (the localisation measurements of Rock.md): the share of
/// tensile failures, of long bonds (a gap at cementing) among the broken and among all
/// bonds, and of the outer grain layer (grains whose centre lies within one mean diameter
/// of a side face of the specimen as cemented; of the cylinder's curved side when
/// `cylinder`): its share of the broken bonds and of all bonds, and the bonded coordination of
/// its grains against the inner grains'.
std::string damageBreakdown(const Model& cemented, const Model& failed, bool cylinder)
{
  const Particles& p = cemented.particles;
  std::unordered_map<std::int64_t, std::size_t> slot;
  for (std::size_t i = 0; i < p.size(); ++i) {
    slot[p.id[i]] = i;
  }
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (std::size_t i = 0; i < p.size(); ++i) {
    lo = lo.cwiseMin(p.position[i]);
    hi = hi.cwiseMax(p.position[i]);
  }
  const double d = meanParticleDiameter(cemented);
  // A cylinder (axis Z): the outermost grain centre's distance from the axis less one diameter.
  const double cx = 0.5 * (lo.x() + hi.x()), cy = 0.5 * (lo.y() + hi.y());
  const auto axisDistance = [&](const Vec3& x) { return std::hypot(x.x() - cx, x.y() - cy); };
  double outer = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    outer = std::max(outer, axisDistance(p.position[i]));
  }
  std::vector<std::uint8_t> skin(p.size(), 0);
  std::size_t skinGrains = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3& x = p.position[i];
    bool nearSide = false;
    for (const int k : lateralAxes(cemented)) {
      nearSide = nearSide || x[k] - lo[k] < d || hi[k] - x[k] < d;
    }
    skin[i] = cylinder ? (outer - axisDistance(x) < d ? 1 : 0) : (nearSide ? 1 : 0);
    skinGrains += skin[i];
  }
  const Bonds& b = failed.bonds;
  std::size_t broken = 0, tensile = 0, longAll = 0, longBroken = 0, skinAll = 0, skinBroken = 0;
  std::size_t skinEnds = 0, innerEnds = 0;
  for (std::size_t k = 0; k < b.size(); ++k) {
    const std::size_t i = slot.at(b.idA[k]);
    const std::size_t j = slot.at(b.idB[k]);
    const double gap = minimumImage(cemented.domain, p.position[i], p.position[j]).norm() - p.radius[i] - p.radius[j];
    const bool isLong = gap > 0.0;
    const bool inSkin = skin[i] || skin[j];
    skinEnds += skin[i] + skin[j];
    innerEnds += 2 - skin[i] - skin[j];
    longAll += isLong;
    skinAll += inSkin;
    if (b.broken(k)) {
      ++broken;
      tensile += b.failure[k] == static_cast<std::uint8_t>(BondFailure::Tension);
      longBroken += isLong;
      skinBroken += inSkin;
    }
  }
  const auto pct = [](std::size_t a, std::size_t n) { return n ? 100.0 * static_cast<double>(a) / n : 0.0; };
  char line[800];
  std::snprintf(line, sizeof line,
    "damage: %zu broken (%.1f %% of bonds): %.1f %% in tension; %.1f %% long bonds (long: %.1f %% of all bonds, %.1f %% of them broken, contact bonds %.1f %%); "
    "outer grain layer (%zu grains within one diameter of %s, coordination %.2f against %.2f inside): %.1f %% of the broken bonds, %.1f %% of all bonds, %.1f %% of its bonds broken (inside %.1f %%)",
    broken, pct(broken, b.size()), pct(tensile, broken), pct(longBroken, broken), pct(longAll, b.size()),
    pct(longBroken, longAll), pct(broken - longBroken, b.size() - longAll), skinGrains,
    cylinder ? "the curved side" : "a side face",
    skinGrains ? static_cast<double>(skinEnds) / skinGrains : 0.0,
    p.size() > skinGrains ? static_cast<double>(innerEnds) / (p.size() - skinGrains) : 0.0,
    pct(skinBroken, broken), pct(skinAll, b.size()), pct(skinBroken, skinAll), pct(broken - skinBroken, b.size() - skinAll));
  return line;
}

/// Least-squares slope of y on x.
double slope(const std::vector<double>& x, const std::vector<double>& y)
{
  const double n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

/// The control for the DFN measure: as many tensile and shear cracks as the failed
/// specimen has, on bonds drawn at random (deterministic), each at its contact point with
/// the bond axis as normal. A DFN that reads real fractures gives fewer discs here.
std::string randomDamageControl(Model m)
{
  Bonds& b = m.bonds;
  std::vector<std::uint8_t> failures;
  for (std::size_t k = 0; k < b.size(); ++k) {
    if (b.broken(k)) {
      failures.push_back(b.failure[k]);
    }
    b.failure[k] = static_cast<std::uint8_t>(BondFailure::Intact);
  }
  std::vector<std::size_t> order(b.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    order[k] = k;
  }
  Random rng(12);
  for (std::size_t k = order.size(); k > 1; --k) { // Fisher-Yates
    std::swap(order[k - 1], order[static_cast<std::size_t>(rng.uniform() * k) % k]);
  }
  std::unordered_map<std::int64_t, std::size_t> slot;
  for (std::size_t i = 0; i < m.particles.size(); ++i) {
    slot[m.particles.id[i]] = i;
  }
  for (std::size_t n = 0; n < failures.size(); ++n) {
    const std::size_t k = order[n];
    const std::size_t i = slot.at(b.idA[k]);
    const std::size_t j = slot.at(b.idB[k]);
    const Vec3 branch = minimumImage(m.domain, m.particles.position[i], m.particles.position[j]);
    const double ri = m.particles.radius[i];
    b.failure[k] = failures[n];
    b.failurePosition[k] = m.particles.position[i] + ri / (ri + m.particles.radius[j]) * branch;
    b.failureNormal[k] = branch.normalized();
  }
  const FractureNetwork dfn = extractFractures(m, FractureParameters{});
  double largest = 0.0;
  for (const FractureDisc& d : dfn.discs) {
    largest = std::max(largest, d.radius);
  }
  char line[240];
  std::snprintf(line, sizeof line,
    "control, the same %zu cracks on bonds drawn at random: %zu discs, largest radius %.3g m, %.1f %% of broken bonds in discs",
    failures.size(), dfn.discs.size(), largest,
    failures.empty() ? 0.0 : 100.0 * static_cast<double>(dfn.report.total.cracksInDiscs) / static_cast<double>(failures.size()));
  return line;
}

/// What broke the bonds, in the order they broke (the cause of the pre-peak cracking,
/// Rock.md "Localisation"). At every sample the stretch term Fn / A and the bending term
/// beta |Mb| Rb / I of each intact bond's peripheral tensile stress are kept; a bond found
/// broken at the next sample is recorded with the terms it had at the last one (at most
/// one sample interval earlier).
struct BreakRecord {
  std::uint8_t failure = 0;
  double stretch = 0.0; // Pa
  double bending = 0.0; // Pa
  bool isLong = false;  // a gap at cementing
};

class BreakTracker {
public:
  explicit BreakTracker(const Model& m)
    : stretch_(m.bonds.size(), 0.0), bending_(m.bonds.size(), 0.0), seen_(m.bonds.size(), 0), long_(m.bonds.size(), 0)
  {
    std::unordered_map<std::int64_t, std::size_t> slot;
    for (std::size_t i = 0; i < m.particles.size(); ++i) {
      slot[m.particles.id[i]] = i;
    }
    for (std::size_t k = 0; k < m.bonds.size(); ++k) {
      const std::size_t i = slot.at(m.bonds.idA[k]);
      const std::size_t j = slot.at(m.bonds.idB[k]);
      const double gap = minimumImage(m.domain, m.particles.position[i], m.particles.position[j]).norm() -
        m.particles.radius[i] - m.particles.radius[j];
      long_[k] = gap > 0.0;
      seen_[k] = m.bonds.broken(k);
    }
  }
  void sample(const Model& m)
  {
    const Bonds& b = m.bonds;
    for (std::size_t k = 0; k < b.size(); ++k) {
      if (b.broken(k)) {
        if (!seen_[k]) {
          seen_[k] = 1;
          records.push_back({ b.failure[k], stretch_[k], bending_[k], long_[k] != 0 });
        }
        continue;
      }
      const BondSection s = bondSection(b.radius[k], m.domain.section2D, m.domain.slabThickness());
      stretch_[k] = b.normalForce[k] / s.area;
      bending_[k] = b.momentContribution[k] * b.bendingMoment[k].norm() * b.radius[k] / s.inertia;
    }
  }
  /// The first `count` breaks: how many in tension, how many of those with the bending
  /// term above the stretch term, the mean bending share of the peripheral stress, long bonds.
  std::string summary(std::size_t count) const
  {
    count = std::min(count, records.size());
    std::size_t tension = 0, bendingLed = 0, longBonds = 0;
    double share = 0.0;
    for (std::size_t n = 0; n < count; ++n) {
      const BreakRecord& r = records[n];
      longBonds += r.isLong;
      if (r.failure == static_cast<std::uint8_t>(BondFailure::Tension)) {
        ++tension;
        bendingLed += r.bending > r.stretch;
        const double total = std::max(r.stretch, 0.0) + r.bending;
        share += total > 0.0 ? r.bending / total : 0.0;
      }
    }
    const auto pct = [](std::size_t a, std::size_t n) { return n ? 100.0 * static_cast<double>(a) / n : 0.0; };
    char line[400];
    std::snprintf(line, sizeof line,
      "first %zu breaks: %.1f %% in tension, of them %.1f %% with bending above stretch (mean bending share of the "
      "tensile stress %.1f %%); %.1f %% long bonds",
      count, pct(tension, count), pct(bendingLed, tension), tension ? 100.0 * share / tension : 0.0,
      pct(longBonds, count));
    return line;
  }
  std::vector<BreakRecord> records;

private:
  std::vector<double> stretch_, bending_;
  std::vector<std::uint8_t> seen_, long_;
};

/// DEM Fractures To DFN at its default settings on the model as it is: the disc count, the
/// largest disc radius (m), the share of the broken bonds in discs, and the report with
/// one line per disc (dip, azimuth, radius, centre, cracks, planarity, fill).
struct DfnReading {
  std::size_t discs = 0;
  double largestDisc = 0.0; // m
  double discShare = 0.0;   // broken bonds in discs / broken bonds
  std::string text;
};

DfnReading readDfn(const Model& m, bool cylinder = false)
{
  const FractureNetwork dfn = extractFractures(m, FractureParameters{});
  DfnReading r;
  r.discs = dfn.discs.size();
  for (const FractureDisc& d : dfn.discs) {
    r.largestDisc = std::max(r.largestDisc, d.radius);
  }
  r.discShare = dfn.report.total.brokenBonds
    ? static_cast<double>(dfn.report.total.cracksInDiscs) / dfn.report.total.brokenBonds : 0.0;
  r.text = dfn.report.summary();
  for (const FractureDisc& d : dfn.discs) {
    char line[360];
    const Vec3 c = d.center - m.domain.origin;
    const Vec3& size = m.domain.size;
    // How deep inside the side surface the centre lies (box: the nearest side face;
    // cylinder along Z: the model box's inscribed circle, the carved diameter).
    double depth = 1e300;
    for (const int k : lateralAxes(m)) {
      depth = std::min({ depth, c[k], size[k] - c[k] });
    }
    if (cylinder) {
      depth = 0.5 * std::min(size.x(), size.y()) - std::hypot(c.x() - 0.5 * size.x(), c.y() - 0.5 * size.y());
    }
    std::snprintf(line, sizeof line,
      "\n    %s disc: dip %.1f, azimuth %.1f deg, radius %.3g m, centre (%.3g, %.3g, %.3g) m from the box origin, "
      "%.3g m inside the side surface, %zu cracks, planarity %.3f, fill %.2f",
      fractureSetName(d.set), d.dip, d.azimuth, d.radius, c.x(), c.y(), c.z(), depth, d.crackCount(), d.planarity, d.fill);
    r.text += line;
  }
  return r;
}

/// The specimen a test leaves, for --dump: the model at the end (its displacements those of
/// the test only) and two earlier frames, to read the deformation after the peak (the
/// increment from the peak, or from 90 % of it, to the end) rather than the cumulative
/// damage: each grain's displacement from the start of the test to the start of the shear
/// stage (the first sample of it: the end of the consolidation), to the peak and to the first
/// sample after it where the stress has fallen to 90 % of the peak, which bonds were broken
/// at the peak, and (under the membrane) which grains formed the surface at the start of the
/// shear stage, the peak and the end.
struct FailedSpecimen {
  Model end;
  std::vector<Vec3> toShear, toPeak, toFall;  // m, displacement during the test (toFall empty: never at 90 %)
  std::vector<std::uint8_t> brokenAtPeak;     // per bond
  std::vector<std::uint8_t> surface;          // per grain: 1 at the start of shear, 2 at the peak, 4 at the end
  double peakStrain = 0.0, fallStrain = 0.0, endStrain = 0.0;
  double peakStress = 0.0, fallStress = 0.0, endStress = 0.0; // Pa
};

/// Sets `bit` in `surface` for every grain the membrane pushes now (nothing without a membrane).
void markSurface(const Model& m, std::vector<std::uint8_t>& surface, std::uint8_t bit)
{
  surface.resize(m.particles.size(), 0);
  for (std::uint8_t& s : surface) {
    s &= static_cast<std::uint8_t>(~bit);
  }
  if (!membraneActive(m)) {
    return;
  }
  std::vector<Vec3> forces;
  membraneSurface(m, &forces);
  for (std::size_t i = 0; i < forces.size() && i < surface.size(); ++i) {
    if (forces[i].squaredNorm() > 0.0) {
      surface[i] |= bit;
    }
  }
}

/// The stop rule's smallest peak strain: a peak before it (the stress oscillation at the
/// start of an undamped test) does not end a test when the stress falls after it.
double minPeakStrain(const Options& o)
{
  return o.minPeakStrain >= 0.0 ? o.minPeakStrain : 0.01 * o.maxStrain;
}

/// Runs a test until the stress has fallen to 70 % of the peak after it (compression,
/// tension; a peak at --min-peak-strain or later), the shear stage's max strain, or the
/// test is done.
TestResult runTest(Model m, TestMode mode, double confining, const Options& o, bool analyse,
                   Confinement confinement = Confinement::RigidWalls, FailedSpecimen* failed = nullptr,
                   bool cylinder = false)
{
  const Model start0 = m;
  TestResult r;
  const auto start = std::chrono::steady_clock::now();
  LoadTestSettings s;
  s.mode = mode;
  s.confinement = confinement;
  s.axis = loadAxis(m);
  const int ax = s.axis;
  s.confiningStress = confining > 0.0 ? confining : 1e6;
  s.maxStrain = o.maxStrain;
  s.sampleInterval = 50;
  s.platenFriction = mode == TestMode::Tension ? 0.0 : o.platenFriction;
  s.servoAlpha = o.servoAlpha;
  s.consolidationDamping = o.consolidationDamping;
  startLoadTest(m, s);
  Simulation sim(m);
  s.strainRate = o.strainPerStep / sim.timestep();
  const PeakStressEstimate estimate = estimatePeakStress(m, s);
  r.target = o.inertialTarget > 0.0 ? o.inertialTarget
                                    : (estimate.cemented ? CementedTargetInertialNumber : TargetInertialNumber);
  r.suggested = o.inertialTarget > 0.0 ? strainRateForInertialNumber(m, estimate.mean, o.inertialTarget)
                                       : suggestedStrainRate(m, s);
  if (o.rateFactor > 0.0) {
    s.strainRate = o.rateFactor * r.suggested;
  }
  r.strainRate = s.strainRate;
  r.timestep = sim.timestep();
  startLoadTest(m, s); // again, with the rate that gives the strain per step
  const std::vector<Vec3> startPosition = m.particles.position; // for the dump's displacements
  const auto displacementSinceStart = [&]() {
    std::vector<Vec3> u(m.particles.size());
    for (std::size_t i = 0; i < u.size() && i < startPosition.size(); ++i) {
      u[i] = m.particles.position[i] - startPosition[i];
    }
    return u;
  };
  Simulation run(m, o.device);
  r.path = run.path();
  if (failed) {
    failed->surface.clear();
    failed->toFall.clear();
    failed->toShear.clear();
  }
  std::vector<double> strain, stress, lateral, gauge, ufr;
  std::size_t peakSample = 0;
  BreakTracker breaks(m);
  bool fallen = false;
  while (m.test.stage != TestStage::Done && !fallen && !(o.maxSteps > 0.0 && r.steps >= o.maxSteps)) {
    run.advance(s.sampleInterval);
    r.steps += s.sampleInterval;
    if (analyse) {
      breaks.sample(m);
    }
    if (m.test.stage != TestStage::Shear) {
      continue;
    }
    if (strain.empty()) {
      r.brokenAtShear = countBonds(m.bonds).broken;
    }
    if (failed && failed->toShear.empty()) {
      failed->toShear = displacementSinceStart(); // the first sample of the shear stage
      markSurface(m, failed->surface, 1);
    }
    const TestMeasurements me = run.measurements();
    const double sign = mode == TestMode::Tension ? -1.0 : 1.0;
    const double e = sign * me.strain[ax];
    const double sigma = mode == TestMode::Triaxial ? me.axialStress : sign * me.axialStress;
    strain.push_back(e);
    stress.push_back(sigma);
    if (std::getenv("RB_TRACE") && strain.size() % 20 == 0) {
      std::fprintf(stderr, "  %s step %lld strain %.5f stress %.4g peak %.4g broken %zu (%.1f s)\n", modeName(mode),
                   static_cast<long long>(r.steps), e, sigma, r.peak, countBonds(m.bonds).broken, secondsSince(start));
    }
    double lateralStrain = 0.0;
    for (const int k : lateralAxes(m)) {
      lateralStrain += me.strain[k] / static_cast<double>(lateralAxes(m).size());
    }
    lateral.push_back(lateralStrain);
    gauge.push_back(sign * me.gaugeStrain); // the specimen's own axial strain (E and nu)
    ufr.push_back(run.diagnostics().unbalancedForceRatio);
    if (sigma > r.peak) {
      r.peak = sigma;
      r.peakStrain = e;
      r.brokenAtPeak = countBonds(m.bonds).broken;
      r.softeningAtPeak = 0;
      for (std::size_t k = 0; k < m.bonds.size(); ++k) {
        r.softeningAtPeak += !m.bonds.broken(k) && m.bonds.damage[k] > 0.0;
      }
      r.inertialAtPeak = me.inertialNumber;
      peakSample = ufr.size();
      if (failed) {
        failed->toPeak = displacementSinceStart();
        failed->brokenAtPeak.assign(m.bonds.size(), 0);
        for (std::size_t k = 0; k < m.bonds.size(); ++k) {
          failed->brokenAtPeak[k] = m.bonds.broken(k) ? 1 : 0;
        }
        markSurface(m, failed->surface, 2);
        failed->peakStrain = e;
        failed->peakStress = sigma;
        failed->toFall.clear(); // a new peak: the fall to 90 % is still to come
      }
    }
    if (failed && failed->toFall.empty() && r.peak > 0.0 && sigma <= 0.9 * r.peak && e > r.peakStrain) {
      failed->toFall = displacementSinceStart();
      failed->fallStrain = e;
      failed->fallStress = sigma;
    }
    if (failed) {
      failed->endStrain = e;
      failed->endStress = sigma;
    }
    const bool peakCounts = r.peak > 0.0 && r.peakStrain >= minPeakStrain(o);
    if (mode != TestMode::Triaxial && peakCounts && sigma < 0.7 * r.peak && e > r.peakStrain) {
      fallen = true;
      r.strainAt70 = e;
    }
    if (mode == TestMode::Triaxial && peakCounts && sigma < o.triaxialStop * r.peak && e > r.peakStrain) {
      fallen = true; // past the peak: the envelope needs only the peak (--triaxial-stop, default 80 %)
    }
  }
  r.peaked = fallen;
  for (std::size_t i = 0; i < peakSample; ++i) {
    r.ufrBeforePeak += ufr[i] / static_cast<double>(peakSample);
  }
  // Elastic constants between 10 % and 50 % of the peak, before it, against the Gauge
  // Strain (the specimen's own axial strain), as rockdem.elastic_constants reads them.
  std::vector<double> x, y, l;
  for (std::size_t i = 0; i < stress.size(); ++i) {
    if (strain[i] <= r.peakStrain && stress[i] >= 0.1 * r.peak && stress[i] <= 0.5 * r.peak) {
      x.push_back(gauge[i]);
      y.push_back(stress[i]);
      l.push_back(lateral[i]);
    }
  }
  if (x.size() >= 2) {
    r.E = slope(x, y);
    r.nu = -slope(x, l);
  }
  r.broken = countBonds(m.bonds).broken;
  if (analyse) {
    r.earlyBreaks = breaks.summary(std::max<std::size_t>(1, r.brokenAtPeak / 10)) + "\n  up to the peak, " +
      breaks.summary(r.brokenAtPeak);
    r.damage = damageBreakdown(start0, m, cylinder);
    r.nearPlatens = platenShare(m, o.profile);
    const DfnReading dfn = readDfn(m, cylinder);
    r.discs = dfn.discs;
    r.largestDisc = dfn.largestDisc;
    r.discShare = dfn.discShare;
    r.dfn = dfn.text + "\n  " + randomDamageControl(m);
  }
  r.seconds = secondsSince(start);
  if (failed) {
    failed->end = m;
    // The displacements of this test only (slots do not change during a test).
    failed->end.particles.displacement = displacementSinceStart();
    markSurface(m, failed->surface, 4);
  }
  return r;
}

/// The Brazilian test on a disc (axis Z) squeezed along Y at the platen strain per step of
/// the other tests, until the load has fallen to 70 % of its peak: Brazilian Strength
/// (2P / (pi D t) at the peak), the broken bonds then, and the DFN of that frame.
struct BrazilianRun {
  double strength = 0.0;      // Pa
  double peakStrain = 0.0;
  std::size_t brokenAtPeak = 0, broken = 0;
  double centralBand = 0.0;   // share of the broken bonds within D/6 of the loaded diameter (x = centre)
  std::string dfn;
  std::size_t discs = 0;
  double largestDisc = 0.0, discShare = 0.0;
  std::int64_t steps = 0;
  double seconds = 0.0;
  bool peaked = false;
  std::array<double, 2> disc{ 0.0, 0.0 }; // m, diameter D and thickness t
};

BrazilianRun runBrazilian(Model m, const Options& o)
{
  BrazilianRun r;
  const auto start = std::chrono::steady_clock::now();
  LoadTestSettings s;
  s.mode = TestMode::Brazilian;
  s.axis = 1;
  s.maxStrain = o.maxStrain;
  s.sampleInterval = 50;
  s.platenFriction = o.platenFriction;
  startLoadTest(m, s);
  {
    Simulation sim(m);
    s.strainRate = o.strainPerStep / sim.timestep();
  }
  startLoadTest(m, s);
  const std::array<double, 2> disc = brazilianDisc(m);
  r.disc = disc;
  double centreX = 0.0;
  for (const Vec3& p : m.particles.position) {
    centreX += p.x() / static_cast<double>(m.particles.size());
  }
  Simulation run(m);
  while (m.test.stage != TestStage::Done) {
    run.advance(s.sampleInterval);
    r.steps += s.sampleInterval;
    const TestMeasurements me = run.measurements();
    if (me.axialStress > r.strength) {
      r.strength = me.axialStress;
      r.peakStrain = me.strain[1];
      r.brokenAtPeak = countBonds(m.bonds).broken;
    }
    if (r.strength > 0.0 && me.axialStress < 0.7 * r.strength) {
      r.peaked = true;
      break;
    }
  }
  r.broken = countBonds(m.bonds).broken;
  std::size_t band = 0;
  for (std::size_t b = 0; b < m.bonds.size(); ++b) {
    if (m.bonds.broken(b) && std::abs(m.bonds.failurePosition[b].x() - centreX) <= disc[0] / 6.0) {
      ++band;
    }
  }
  r.centralBand = r.broken ? static_cast<double>(band) / r.broken : 0.0;
  const DfnReading dfn = readDfn(m);
  r.discs = dfn.discs;
  r.largestDisc = dfn.largestDisc;
  r.discShare = dfn.discShare;
  r.dfn = dfn.text;
  r.seconds = secondsSince(start);
  return r;
}

/// Writes a failed specimen for scripts/plot_envelopes.py and scripts/plot_localisation.py:
/// one line per particle (x, y, z, radius at the end; its displacement during the test dx,
/// dy, dz; to the peak px, py, pz; to the fall to 90 % of the peak fx, fy, fz, or the end's
/// when the stress never fell that far; to the start of the shear stage sx, sy, sz; m;
/// `surface`, the membrane's surface grain at the start of shear 1, peak 2, end 4, summed) and per broken bond (kind tension or shear, its failure
/// position; `after_peak` 1 when it broke after the peak). Written to a temporary file and
/// renamed, so a failed write leaves no half file.
void dumpSpecimen(const FailedSpecimen& s, const std::string& path)
{
  const Model& m = s.end;
  const std::string tmp = path + ".tmp";
  FILE* f = std::fopen(tmp.c_str(), "w");
  if (!f) {
    std::fprintf(stderr, "cannot write %s\n", tmp.c_str());
    return;
  }
  std::fprintf(f, "kind,x,y,z,radius,dx,dy,dz,px,py,pz,fx,fy,fz,sx,sy,sz,surface,after_peak\n");
  for (std::size_t i = 0; i < m.particles.size(); ++i) {
    const Vec3& x = m.particles.position[i];
    const Vec3& u = m.particles.displacement[i];
    const Vec3 p = i < s.toPeak.size() ? s.toPeak[i] : u;
    const Vec3 q = i < s.toFall.size() ? s.toFall[i] : u;
    const Vec3 c = i < s.toShear.size() ? s.toShear[i] : Vec3(0.0, 0.0, 0.0);
    std::fprintf(f, "particle,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%d,0\n",
                 x.x(), x.y(), x.z(), m.particles.radius[i], u.x(), u.y(), u.z(), p.x(), p.y(), p.z(), q.x(), q.y(),
                 q.z(), c.x(), c.y(), c.z(), i < s.surface.size() ? static_cast<int>(s.surface[i]) : 0);
  }
  for (std::size_t k = 0; k < m.bonds.size(); ++k) {
    if (m.bonds.broken(k)) {
      const Vec3& x = m.bonds.failurePosition[k];
      const bool tension = m.bonds.failure[k] == static_cast<std::uint8_t>(BondFailure::Tension);
      const bool afterPeak = k >= s.brokenAtPeak.size() || !s.brokenAtPeak[k];
      std::fprintf(f, "%s,%.9g,%.9g,%.9g,0,0,0,0,0,0,0,0,0,0,0,0,0,0,%d\n", tension ? "tension" : "shear", x.x(), x.y(),
                   x.z(), afterPeak ? 1 : 0);
    }
  }
  const bool ok = std::fflush(f) == 0 && !std::ferror(f);
  std::fclose(f);
  if (!ok || std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    std::fprintf(stderr, "cannot write %s\n", path.c_str());
  }
}

/// The frames of a dump on one line: strain and stress at the peak, at the fall to 90 % of
/// it and at the end, and the bonds broken by each.
void printFrames(const char* label, const FailedSpecimen& s)
{
  std::size_t atPeak = 0;
  for (std::uint8_t b : s.brokenAtPeak) {
    atPeak += b;
  }
  std::printf("%s frames: peak strain %.5g stress %.5g Pa (%zu bonds broken); 90 %% %s strain %.5g stress %.5g Pa; "
              "end strain %.5g stress %.5g Pa (%zu broken of %zu)\n",
              label, s.peakStrain, s.peakStress, atPeak, s.toFall.empty() ? "not reached, end" : "at",
              s.toFall.empty() ? s.endStrain : s.fallStrain, s.toFall.empty() ? s.endStress : s.fallStress,
              s.endStrain, s.endStress, countBonds(s.end.bonds).broken, s.end.bonds.size());
}

/// One run of the stability map: a test at Timestep Safety `safety` (above 1: that multiple
/// of the critical timestep, forced with allowUnsafeTimestep), Settling Damping `damping`
/// and Servo Alpha `alpha`, at --rate-factor x the Suggested Strain Rate, until the stress
/// has fallen after its peak (compression 70 %, triaxial 80 %), the test ends, --max-steps,
/// or the engine stops it (InstabilityError).
struct ProbeResult {
  bool stopped = false;          // the engine threw InstabilityError
  std::string message;           // its message
  bool lastGood = true;          // after a stop: the model is at the step before the failed advance()
  double timestep = 0.0, critical = 0.0; // s
  double peak = 0.0, peakStrain = 0.0;   // Pa (triaxial: sigma1), -
  std::int64_t steps = 0;
  double servoMax = 0.0, servoMean = 0.0; // |lateral - sigma3| / sigma3 over the shear samples to the peak
  double maxStress = 0.0;        // Pa, largest |axial| or |lateral| stress of any sample
  double maxSpeed = 0.0;         // m/s, largest grain speed of any sample
  std::size_t nonFinite = 0;     // non-finite values in the samples and in the model after the run
  std::size_t brokenFirst = 0;   // bonds broken after the first sample (50 steps; a stable run breaks none there)
  std::size_t broken = 0, bonds = 0; // broken bonds at the end, bonds
  bool settled = false;          // triaxial: the consolidation ended
  bool peaked = false;
  double seconds = 0.0;
};

std::size_t countNonFinite(const Model& m)
{
  std::size_t n = 0;
  const auto vec = [&n](const std::vector<Vec3>& v) {
    for (const Vec3& x : v) {
      n += !x.allFinite();
    }
  };
  const auto num = [&n](const std::vector<double>& v) {
    for (double x : v) {
      n += !std::isfinite(x);
    }
  };
  vec(m.particles.position);
  vec(m.particles.velocity);
  vec(m.particles.angularVelocity);
  num(m.bonds.normalForce);
  vec(m.bonds.shearForce);
  vec(m.bonds.bendingMoment);
  for (const Wall& w : m.walls) {
    n += !std::isfinite(w.position) + !std::isfinite(w.velocity);
  }
  for (const auto& row : m.test.history) {
    for (double x : row) {
      n += !std::isfinite(x);
    }
  }
  return n;
}

ProbeResult probeRun(Model m, TestMode mode, double confining, const Options& o, double safety, double damping,
                     double alpha)
{
  ProbeResult r;
  const auto start = std::chrono::steady_clock::now();
  m.solver.settlingDamping = damping;
  r.critical = criticalTimestep(m, m.solver.contactLaw);
  if (safety > 1.0) {
    m.solver.timestepSafety = 1.0;
    m.solver.requestedTimestep = safety * r.critical;
    m.solver.allowUnsafeTimestep = true;
  } else {
    m.solver.timestepSafety = safety;
  }
  LoadTestSettings s;
  s.mode = mode;
  s.axis = 2;
  s.confiningStress = confining > 0.0 ? confining : 1e6;
  s.maxStrain = o.maxStrain;
  s.sampleInterval = 50;
  s.servoAlpha = alpha;
  s.consolidationDamping = damping; // the map sweeps the damping of the whole test
  s.platenFriction = o.platenFriction;
  startLoadTest(m, s);
  s.strainRate = (o.rateFactor > 0.0 ? o.rateFactor : 16.0) * suggestedStrainRate(m, s);
  startLoadTest(m, s);
  double servoSum = 0.0;
  std::size_t servoSamples = 0;
  try {
    Simulation run(m);
    r.timestep = run.timestep();
    while (m.test.stage != TestStage::Done && !(o.maxSteps > 0.0 && r.steps >= o.maxSteps)) {
      const std::int64_t before = m.clock.step;
      try {
        run.advance(s.sampleInterval);
      } catch (const InstabilityError& e) {
        r.stopped = true;
        r.message = e.what();
        r.lastGood = m.clock.step == before;
        break;
      }
      r.steps += s.sampleInterval;
      if (r.steps == s.sampleInterval) {
        r.brokenFirst = countBonds(m.bonds).broken;
      }
      const TestMeasurements me = run.measurements();
      for (double x : { me.axialStress, me.lateralStress, me.deviatorStress, me.meanStress, me.volumetricStrain,
                        me.inertialNumber, me.suggestedStrainRate, me.strain[0], me.strain[1], me.strain[2] }) {
        r.nonFinite += !std::isfinite(x);
      }
      for (double x : me.faceStress) {
        r.nonFinite += !std::isfinite(x);
      }
      r.maxStress = std::max({ r.maxStress, std::abs(me.axialStress), std::abs(me.lateralStress) });
      for (const Vec3& v : m.particles.velocity) {
        r.maxSpeed = std::max(r.maxSpeed, v.norm());
      }
      if (m.test.stage != TestStage::Shear && m.test.stage != TestStage::Done) {
        continue;
      }
      r.settled = true;
      const double sigma = me.axialStress;
      if (sigma > r.peak) {
        r.peak = sigma;
        r.peakStrain = me.strain[2];
        r.servoMean = servoSamples ? servoSum / servoSamples : 0.0;
      }
      if (mode == TestMode::Triaxial) {
        const double error = std::abs(me.lateralStress - s.confiningStress) / s.confiningStress;
        if (sigma >= r.peak) {
          r.servoMax = std::max(r.servoMax, error);
        }
        servoSum += error;
        ++servoSamples;
      }
      const double fall = mode == TestMode::Triaxial ? 0.8 : 0.7;
      if (std::getenv("RB_TRACE")) {
        std::fprintf(stderr, "  step %lld strain %.5g stress %.4g lateral %.4g speed %.3g ke %.4g broken %zu\n", static_cast<long long>(r.steps),
                     me.strain[2], sigma, me.lateralStress, r.maxSpeed, run.diagnostics().kineticEnergy, countBonds(m.bonds).broken);
      }
      if (!o.probeToMaxStrain && r.peak > 0.0 && r.peakStrain >= minPeakStrain(o) && sigma < fall * r.peak &&
          me.strain[2] > r.peakStrain) {
        r.peaked = true;
        break;
      }
    }
  } catch (const InputError& e) {
    r.stopped = true;
    r.message = std::string("input refused: ") + e.what();
  }
  r.nonFinite += countNonFinite(m);
  r.broken = countBonds(m.bonds).broken;
  r.bonds = m.bonds.size();
  r.seconds = secondsSince(start);
  return r;
}

void printProbe(const char* map, double ratio, double safety, double damping, double alpha, const ProbeResult& r,
                double waveSpeed)
{
  std::printf("stability: map %s ratio %g safety %g damping %g alpha %g timestep %.6g critical %.6g status %s "
              "peak %.17g strain %.6g steps %lld servo-max %.6g servo-mean %.6g max-stress %.6g max-speed %.6g "
              "wave-speed %.6g nonfinite %zu last-good %d settled %d peaked %d broken-first %zu broken %zu bonds %zu seconds %.3f\n",
              map, ratio, safety, damping, alpha, r.timestep, r.critical, r.stopped ? "stopped" : "ran", r.peak,
              r.peakStrain, static_cast<long long>(r.steps), r.servoMax, r.servoMean, r.maxStress, r.maxSpeed,
              waveSpeed, r.nonFinite, r.lastGood ? 1 : 0, r.settled ? 1 : 0, r.peaked ? 1 : 0, r.brokenFirst, r.broken, r.bonds,
              r.seconds);
  if (r.stopped) {
    std::printf("  message: %s\n", r.message.c_str());
  }
  std::fflush(stdout);
}

/// Least-squares Mohr-Coulomb fit sigma1 = a + b sigma3: prints it with the friction angle
/// and cohesion under `label`.
void printMohrCoulomb(const char* label, const std::vector<double>& s3, const std::vector<double>& s1);

bool wants(const Options& o, const char* test)
{
  return o.tests.find(test) != std::string::npos;
}

} // namespace

int main(int argc, char** argv)
{
  const Options o = parse(argc, argv);
  auto start = std::chrono::steady_clock::now();
  CementReport cemented;
  CompactReport compacted;
  const Model m = buildSpecimen(o, cemented, compacted);
  const double width = m.domain.size.x();
  const double diameter = meanParticleDiameter(m);
  char slabLabel[160] = "";
  if (o.depth > 0.0) {
    std::snprintf(slabLabel, sizeof slabLabel, "3D slab (depth %g nominal mean diameters along Y = %.1f mean diameters, loaded along Z), ",
                  o.depth, m.domain.size.y() / diameter);
  }
  std::printf("specimen: %s%zu particles, %.4g x %.4g x %.4g m, %.1f mean diameters across; %s\n",
              m.domain.section2D ? "2D section (discs in XY, loaded along Y, slab = Z), " : slabLabel,
              m.particles.size(), width, m.domain.size.y(), m.domain.size.z(), width / diameter,
              compacted.summary().c_str());
  std::printf("cement: Bond Range %.3g, Moment Contribution %.3g, Softening Ratio %.3g -> %s (%.1f s)\n", o.range, o.beta, o.softening,
              cemented.summary().c_str(), secondsSince(start));
  std::fflush(stdout);

  // The cylinder carved from the same pack (or from a larger one, --carve-margin), built once
  // for the unconfined, tension and envelope tests that ask for it.
  const bool onBox = o.specimen != "cylinder";
  const bool onCylinder = o.specimen != "box";
  Model carved;
  CementReport carvedCement;
  bool haveCylinder = false;
  const auto cylinderSpecimen = [&]() -> const Model& {
    if (!haveCylinder) {
      CompactReport p2;
      const auto built = std::chrono::steady_clock::now();
      carved = buildSpecimen(o, carvedCement, p2, Carve::Cylinder);
      haveCylinder = true;
      std::printf("cylinder: %zu particles carved from a pack of %zu grains (margin %g mean diameters), diameter %.4g m, "
                  "length %.4g m, %.1f mean diameters across; %s; %s (%.1f s)\n",
                  carved.particles.size(), p2.particles, o.carveMargin, width, m.domain.size.z(),
                  width / meanParticleDiameter(carved), p2.summary().c_str(), carvedCement.summary().c_str(),
                  secondsSince(built));
      std::fflush(stdout);
    }
    return carved;
  };

  // The unconfined test on the box (label "") or the cylinder ("cylinder "): its figures, the
  // localisation measurements and the DFN at 70 % of the peak, and --dump's frame.
  const auto unconfined = [&](const Model& spec, bool cylinder, std::size_t bonds) {
    const char* label = cylinder ? "cylinder " : "";
    FailedSpecimen failed;
    const TestResult u = runTest(spec, TestMode::Compression, 0.0, o, true, Confinement::RigidWalls, &failed, cylinder);
    if (!o.dump.empty()) {
      dumpSpecimen(failed, o.dump + (cylinder ? "/ucs_failed_cylinder.csv" : "/ucs_failed.csv")); // the frame at 70 % of the peak
      writeState(failed.end, o.dump + (cylinder ? "/ucs_failed_cylinder.rdem" : "/ucs_failed.rdem")); // the same frame, to run on
      printFrames(cylinder ? "cylinder ucs" : "ucs", failed);
    }
    std::printf("%sUCS %.4g Pa at strain %.4g; E %.4g Pa; nu %.3f; broken %zu (%.1f %% of bonds); "
                "70 %% of peak at strain %.4g; broken within 2 diameters of a platen: %.1f %% (%lld steps, %.1f s)\n",
                label, u.peak, u.peakStrain, u.E, u.nu, u.broken, 100.0 * u.broken / bonds, u.strainAt70,
                100.0 * u.nearPlatens, static_cast<long long>(u.steps), u.seconds);
    std::printf("  rate: strain rate %.6g 1/s = %.4g x Suggested Strain Rate %.6g 1/s (timestep %.4g s); "
                "inertial number at the peak %.4g; mean unbalanced force ratio up to the peak %.4g\n",
                u.strainRate, u.suggested > 0.0 ? u.strainRate / u.suggested : 0.0, u.suggested, u.timestep,
                u.inertialAtPeak, u.ufrBeforePeak);
    std::printf("  path: %s\n", u.path.c_str());
    std::printf("  broken at the peak: %zu (%.1f %% of bonds); softening then (intact, damage > 0): %zu (%.1f %%)\n  %s\n  %s\n",
                u.brokenAtPeak, 100.0 * u.brokenAtPeak / bonds, u.softeningAtPeak,
                100.0 * u.softeningAtPeak / bonds, u.damage.c_str(), u.earlyBreaks.c_str());
    if (!u.peaked) {
      std::printf("  no peak: the stress did not fall to 70 %% of its largest value within Max Strain %g\n", o.maxStrain);
    }
    std::printf("  DFN: %zu discs, largest radius %.4g m (%.0f %% of the width), %.1f %% of broken bonds in discs\n  %s\n",
                u.discs, u.largestDisc, 100.0 * u.largestDisc / width, 100.0 * u.discShare, u.dfn.c_str());
    std::fflush(stdout);
    return u.peak;
  };
  double ucs = o.ucs;        // the box's (the triaxial series' reference); --ucs when not measured here
  double cylinderUcs = 0.0;
  if (wants(o, "ucs")) {
    if (onBox) {
      ucs = unconfined(m, false, cemented.bonds);
    }
    if (onCylinder) {
      const Model& spec = cylinderSpecimen();
      cylinderUcs = unconfined(spec, true, carvedCement.bonds);
    }
  }
  if (wants(o, "rates")) {
    // The strain-rate sweep of Documentation/SpeedAccuracy.md: one unconfined test per
    // factor on the same specimen; the peak also with all its digits (thread agreement).
    for (double f : o.rateFactors) {
      Options at = o;
      at.rateFactor = f;
      const TestResult u = runTest(m, TestMode::Compression, 0.0, at, false);
      std::printf("rate-sweep: factor %g strain rate %.6g 1/s suggested %.6g 1/s target %g timestep %.6g s UCS %.17g Pa "
                  "strain at peak %.6g E %.6g Pa inertial %.6g ufr %.6g steps %lld seconds %.3f peaked %d\n",
                  f, u.strainRate, u.suggested, u.target, u.timestep, u.peak, u.peakStrain, u.E, u.inertialAtPeak,
                  u.ufrBeforePeak, static_cast<long long>(u.steps), u.seconds, u.peaked ? 1 : 0);
      std::printf("rate-sweep-path: factor %g %s\n", f, u.path.c_str());
      std::fflush(stdout);
    }
  }
  if (wants(o, "tsmap")) {
    // The stability map of Documentation/SpeedAccuracy.md. 1: Timestep Safety against the
    // Bond Modulus / grain Young's modulus ratio (a specimen cemented at each ratio from the
    // same pack), unconfined; 2: Settling Damping against Servo Alpha, triaxial at the
    // first --sigma3, on the specimen cemented at --bond-modulus (or --modulus).
    const double density = m.material.density;
    for (double ratio : o.bondRatios) {
      Options at = o;
      at.bondModulus = ratio * o.modulus;
      CementReport c2;
      CompactReport p2;
      const Model spec = buildSpecimen(at, c2, p2);
      const double wave = std::sqrt(std::max(o.modulus, at.bondModulus) / density);
      for (double safety : o.safeties) {
        printProbe("timestep", ratio, safety, o.damping, o.servoAlpha,
                   probeRun(spec, TestMode::Compression, 0.0, o, safety, o.damping, o.servoAlpha), wave);
      }
    }
  }
  if (wants(o, "servomap")) {
    const double density = m.material.density;
    const double ratio = (o.bondModulus > 0.0 ? o.bondModulus : o.modulus) / o.modulus;
    const double wave = std::sqrt(std::max(o.modulus, ratio * o.modulus) / density);
    for (double damping : o.dampings) {
      for (double alpha : o.servoAlphas) {
        printProbe("servo", ratio, o.safety, damping, alpha,
                   probeRun(m, TestMode::Triaxial, o.sigma3.front(), o, o.safety, damping, alpha), wave);
      }
    }
  }
  double tensile = 0.0;
  if (wants(o, "tension")) {
    // Direct tension on a twin of each unconfined specimen (the same specimen, fresh).
    for (const bool cylinder : { false, true }) {
      if (!(cylinder ? onCylinder : onBox)) {
        continue;
      }
      const TestResult t = runTest(cylinder ? cylinderSpecimen() : m, TestMode::Tension, 0.0, o, false);
      const char* label = cylinder ? "cylinder " : "";
      std::printf("%sdirect tension %.4g Pa at strain %.4g; broken %zu (%lld steps, %.1f s)\n", label, t.peak,
                  t.peakStrain, t.broken, static_cast<long long>(t.steps), t.seconds);
      std::printf("  path: %s\n", t.path.c_str());
      const double compression = cylinder ? cylinderUcs : ucs;
      if (compression > 0.0) {
        std::printf("%sUCS / sigma_t = %.2f\n", label, compression / t.peak);
      }
      if (!cylinder) {
        tensile = t.peak;
      }
      std::fflush(stdout);
    }
  }
  if (wants(o, "brazilian")) {
    // The Brazilian disc carved from the same pack (the same compaction, the same cement
    // parameters; the bonds of the carved set): Brazilian Strength against the direct
    // tensile strength of the box specimen above.
    CementReport c2;
    CompactReport p2;
    const Model disc = buildSpecimen(o, c2, p2, Carve::BrazilianDisc);
    const BrazilianRun b = runBrazilian(disc, o);
    const std::array<double, 2> dt = b.disc;
    std::printf("brazilian disc: %zu particles carved from the same pack, diameter %.4g m, thickness %.4g m, "
                "%.1f mean diameters across; %s\n",
                disc.particles.size(), dt[0], dt[1], dt[0] / meanParticleDiameter(disc), c2.summary().c_str());
    std::printf("Brazilian Strength %.4g Pa at strain %.4g; broken at the peak %zu (%.1f %% of bonds), %zu at 70 %% "
                "of the peak; %.1f %% of them within D/6 of the loaded diameter (%lld steps, %.1f s)%s\n",
                b.strength, b.peakStrain, b.brokenAtPeak, 100.0 * b.brokenAtPeak / c2.bonds, b.broken,
                100.0 * b.centralBand, static_cast<long long>(b.steps), b.seconds,
                b.peaked ? "" : " (no fall to 70 % within Max Strain)");
    std::printf("  Brazilian DFN: %zu discs, largest radius %.4g m (%.0f %% of D), %.1f %% of broken bonds in discs\n  %s\n",
                b.discs, b.largestDisc, 100.0 * b.largestDisc / dt[0], 100.0 * b.discShare, b.dfn.c_str());
    if (tensile > 0.0) {
      std::printf("Brazilian / direct tensile strength = %.2f (laboratory: about 1.1-1.4)\n", b.strength / tensile);
    }
    std::fflush(stdout);
  }
  if (wants(o, "envelopes")) {
    // The same rock in a rigid box and in a membrane cylinder: triaxial tests at the same
    // absolute confining stresses.
    for (const char* kind : { "box", "cylinder" }) {
      if (o.specimen != "both" && o.specimen != kind) {
        continue;
      }
      const bool cylinder = std::string(kind) == "cylinder";
      const Model& spec = cylinder ? cylinderSpecimen() : m;
      std::vector<double> s3, s1;
      for (std::size_t k = 0; k < o.sigma3.size(); ++k) {
        FailedSpecimen failed;
        const bool last = k + 1 == o.sigma3.size();
        const TestResult t = runTest(spec, TestMode::Triaxial, o.sigma3[k], o, false,
                                     cylinder ? Confinement::Membrane : Confinement::RigidWalls,
                                     cylinder && last ? &failed : nullptr);
        s3.push_back(o.sigma3[k]);
        s1.push_back(t.peak);
        std::printf("envelope %s sigma3 %.6g sigma1 %.6g strain %.5g broken %zu %s (%lld steps, %.1f s)\n", kind,
                    o.sigma3[k], t.peak, t.peakStrain, t.broken, t.peaked ? "peak" : "no-peak",
                    static_cast<long long>(t.steps), t.seconds);
        if (cylinder && last) {
          const MembraneSurface ms = membraneSurface(failed.end);
          std::printf("membrane after the test at %.4g Pa: radius %.5g m, spread %.4g m (%.2f %%), min %.5g, max %.5g m\n",
                      o.sigma3[k], ms.radius, ms.radiusSpread, 100.0 * ms.radiusSpread / ms.radius, ms.minRadius,
                      ms.maxRadius);
          if (!o.dump.empty()) {
            dumpSpecimen(failed, o.dump + "/membrane_failed.csv");
            printFrames("membrane", failed);
          }
        }
        std::fflush(stdout);
      }
      printMohrCoulomb(kind, s3, s1);
    }
  }
  if (wants(o, "triaxial") && ucs > 0.0) {
    std::vector<double> s3{ 0.0 }, s1{ ucs };
    for (double f : o.confining) {
      const TestResult t = runTest(m, TestMode::Triaxial, f * ucs, o, false);
      s3.push_back(f * ucs);
      s1.push_back(t.peak);
      std::printf("triaxial sigma3 %.4g Pa (%.0f %% UCS): %s sigma1 %.4g Pa at strain %.4g (%lld steps, %.1f s); "
                  "%zu bonds broken when the shear started, %zu at the peak\n",
                  f * ucs, 100 * f, t.peaked ? "peak" : "no peak within Max Strain: largest", t.peak, t.peakStrain,
                  static_cast<long long>(t.steps), t.seconds, t.brokenAtShear, t.brokenAtPeak);
      std::fflush(stdout);
    }
    const double b = slope(s3, s1);
    double mean = 0.0;
    for (double v : s1) {
      mean += v / s1.size();
    }
    double a = mean;
    {
      double m3 = 0.0;
      for (double v : s3) {
        m3 += v / s3.size();
      }
      a = mean - b * m3;
    }
    double ssr = 0.0, sst = 0.0;
    for (std::size_t i = 0; i < s1.size(); ++i) {
      ssr += std::pow(s1[i] - (a + b * s3[i]), 2);
      sst += std::pow(s1[i] - mean, 2);
    }
    const double phi = std::asin((b - 1.0) / (b + 1.0)) * 180.0 / kPi;
    std::printf("Mohr-Coulomb: sigma1 = %.4g + %.4g sigma3; friction angle %.1f deg, cohesion %.4g Pa, R^2 %.4f\n",
                a, b, phi, a * (1.0 - std::sin(phi * kPi / 180)) / (2.0 * std::cos(phi * kPi / 180)),
                sst > 0 ? 1.0 - ssr / sst : 1.0);
  }
  std::printf("total %.1f s\n", secondsSince(start));
  return 0;
}

namespace {
void printMohrCoulomb(const char* label, const std::vector<double>& s3, const std::vector<double>& s1)
{
  const double b = slope(s3, s1);
  double m1 = 0.0, m3 = 0.0;
  for (std::size_t i = 0; i < s1.size(); ++i) {
    m1 += s1[i] / s1.size();
    m3 += s3[i] / s3.size();
  }
  const double a = m1 - b * m3;
  const double phi = b > 1.0 ? std::asin((b - 1.0) / (b + 1.0)) * 180.0 / kPi : 0.0;
  std::printf("envelope-fit %s: sigma1 = %.6g + %.6g sigma3; friction angle %.2f deg, cohesion %.6g Pa\n", label, a,
              b, phi, a * (1.0 - std::sin(phi * kPi / 180)) / (2.0 * std::cos(phi * kPi / 180)));
}
} // namespace
