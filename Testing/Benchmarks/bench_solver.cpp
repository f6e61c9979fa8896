// Solver benchmark: throughput of the time-stepping solver (CPU or GPU backend), and speed
// against accuracy.
//
// Throughput (default mode). Gravity settling of N spheres with Hertz-Mindlin contacts for
// a fixed number of steps; prints particle-steps per second with one thread and with all
// cores, plus resident memory per particle. Packs (SI units):
//   mono    buildPack, radius 1 mm, in the lower half of the box (loose random pack,
//           porosity ~0.75 where placed, particles start at rest, not touching);
//   poly    the same with radii uniform in [1, 2] mm (2:1);
//   lattice contact-rich: a simple cubic lattice of 1 mm spheres filling the whole box,
//           spacing 2r (1 - 2e-3), so that every particle starts with its 6 neighbours
//           (or walls) in contact (overlap 4 um, force ~100 particle weights): every contact
//           stays loaded for the whole run.
// Material: density 2650 kg/m^3, E 1e8 Pa, nu 0.25, restitution 0.5, friction 0.5,
// Settling Damping 0.7 (default), gravity 9.81 m/s^2, Timestep Safety 0.1 (default).
//   cemented the lattice without gravity, cemented (dem::cement: a bond between every pair
//           of touching neighbours, Benchmarks-GPU.md gives the parameters) and under
//           unconfined compression along Z at 1/s (history row every 100 steps).
// Only advance() is timed (pack building and the Simulation constructor are not).
// --backend cpu,gpu runs each configuration on the CPU backend and/or the GPU (Vulkan)
// backend; the GPU rows add the device memory per particle, per neighbour-pair slot and
// per bond (Documentation/Benchmarks-GPU.md).
//
//   rockdem_bench_solver [--sizes 10000,100000,1000000] [--steps N] [--packs mono,poly,lattice,cemented]
//                        [--backend cpu,gpu] [--threads 1,2] [--damping 0.7] [--restitution 0.5] [--sort]
//                        [--repeat R] [--csv FILE] [--quick]
//   rockdem_bench_solver --sweep [--csv FILE] [--sweep-particles 5000] [--safeties 0.05,0.1,...]
//   rockdem_bench_solver --write-pack FILE --pack poly --sizes 10000
//   rockdem_bench_solver --stream [--threads 1,2] [--repeat 5]
//   rockdem_bench_solver --read-pack FILE [--steps 2000] [--pre N] [--batch B] [--threads 1,2]
//                        [--repeat R] [--damping 0]
//
// --read-pack times a pack file (scripts/liggghts_deck.py's format: "# key value" header
// with box, timestep and material, then "id type diameter density x y z" rows), such as the
// peers' settled mono pack of scripts/benchmark_mono_pack.sh, with the settings of the
// user's path there (scripts/time_pack_pvpython.py: walls on the pack's box, gravity -z,
// Settling Damping 0 unless --damping, Timestep Safety 0.2, Requested Timestep = the pack's):
// --pre steps first (default: --steps; DEM Load Test's first, untimed frame), then --steps
// timed, in advance() calls of --batch steps (default 100, DEM Load Test's Steps per
// Batch; 0: one call). Prints the same columns as the throughput table.
// --stream measures the machine's memory bandwidth (a STREAM-like triad over 768 MiB), the
// bound on the step's memory traffic (Documentation/Benchmarks-Solver.md section 5).
// --quick (the ctest smoke test, ~1 s): 2000 particles x 50 steps per pack and thread
// count, then a two-point sweep (0.1 and 3.0) on reduced workloads.
// --repeat R runs each configuration R times and reports the fastest (the machine may be
// shared; the "others" column says how many cores other processes kept busy during the
// reported run, from /proc/stat minus this process's CPU time). --sort reorders the particle slots along a space-filling order before the run (an
// experiment: the solver keeps the order it is given; buildPack's order is random).
// --write-pack writes the pack as "id type diameter density x y z" lines (SI units) with
// "# key value" header lines (box, timestep, material) for the LIGGGHTS comparison
// (scripts/benchmark_liggghts.sh), and exits.
//
// Sweep (--sweep): for each Timestep Safety s (above 1 with the test-only
// allowUnsafeTimestep switch and requestedTimestep = s x critical):
//   (a) a 1 mm sphere hitting a wall at 1 m/s: delivered restitution for e = 0.5 (error =
//       |delivered - 0.5|), restitution and peak force of an elastic (e = 1) impact, the
//       latter against the Hertz closed form (PHYSICS.md s.1), steps in contact per
//       collision, wall seconds;
//   (b) 40 elastic frictionless spheres (e = 1, no gravity, no damping) in a 4 cm box for a
//       fixed model time (1e5 steps at s = 0.05): worst relative drift of the total energy;
//   (c) a settling pack (poly, --sweep-particles, placed in a flat region W x W x W/8 in
//       a box W/4 tall; damping 0.7, gravity; serial) for a fixed model time of 0.1 s:
//       final kinetic energy, porosity and unbalanced force ratio, wall seconds.
// Any dem::InstabilityError is caught and reported in the status columns ("unstable:..."),
// an impact that returns faster than it came is reported as "energy-gain"; the last
// column, stable, is 0 when any of the three threw. CSV on stdout (and in --csv FILE).
#include "CommaList.h"
#include "dem/Cement.h"
#include "dem/LoadTest.h"
#include "dem/Pack.h"
#include "dem/Simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <sys/resource.h>
#include <unistd.h>

#ifdef __GLIBC__
#include <malloc.h>
#endif
#ifdef _OPENMP
#include <omp.h>
#endif

namespace {

constexpr double kPi = 3.14159265358979323846;

// Benchmark material (SI).
constexpr double kDensity = 2650.0;      // kg/m^3
constexpr double kYoung = 1.0e8;         // Pa
constexpr double kPoisson = 0.25;
constexpr double kRestitution = 0.5;
constexpr double kFriction = 0.5;
constexpr double kPlacementPorosity = 0.75; // void fraction of the region the pack is placed in
constexpr double kLatticeOverlap = 2.0e-3;  // lattice spacing 2r (1 - this)
/// Restitution of the throughput / --write-pack models (--restitution; the sweep sets its own).
double gRestitution = kRestitution;

struct Options {
  std::vector<long> sizes{ 10000, 100000, 1000000 };
  long steps = -1; // -1: by size
  std::vector<std::string> packs{ "mono", "poly", "lattice" };
  std::vector<std::string> backends{ "cpu" };
  std::vector<int> threads;  // empty: 1 and all cores
  double damping = 0.7;
  bool sort = false;
  // Parallel threshold of the runs (work per step, particle-equivalents): -1 = 0 for more
  // than one thread (always on threads), the default for one; -2 = the model's default
  // (the serial/parallel switch as users get it).
  long long threshold = -1;
  int repeat = 1;  // runs per configuration; the fastest is reported
  bool quick = false;
  bool sweep = false;
  bool stream = false;
  std::string csv;
  std::string writePack;
  std::string pack = "poly"; // for --write-pack
  std::string readPack;        // --read-pack FILE
  long pre = -1;               // --pre: untimed steps before the timed ones (-1: --steps)
  long batch = 100;            // --batch: steps per advance() call (0: all in one)
  bool dampingGiven = false;
  long sweepParticles = 5000;
  std::vector<double> safeties{ 0.02, 0.035, 0.05, 0.07, 0.1, 0.15, 0.2, 0.3, 0.4, 0.5,
                                0.7, 1.0, 1.5, 2.0, 3.0 };
};

[[noreturn]] void usage(const char* argv0)
{
  std::fprintf(stderr,
    "usage: %s [--sizes N1,N2,...] [--steps N] [--packs mono,poly,lattice,cemented] [--backend cpu,gpu]\n"
    "          [--threads 1,2] [--threshold W|default]\n"
    "          [--damping A] [--restitution E] [--sort] [--repeat R] [--csv FILE] [--quick]\n"
    "       %s --sweep [--safeties s1,s2,...] [--sweep-particles N] [--csv FILE]\n"
    "       %s --stream [--threads 1,2] [--repeat R]\n"
    "       %s --write-pack FILE [--pack mono|poly|lattice] [--sizes N] [--restitution E] [--sort]\n"
    "       %s --read-pack FILE [--steps N] [--pre N] [--batch B] [--threads 1,2] [--repeat R] [--damping A]\n",
    argv0, argv0, argv0, argv0, argv0);
  std::exit(2);
}

Options parse(int argc, char** argv)
{
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool hasValue = i + 1 < argc;
    if (a == "--sizes" && hasValue) {
      o.sizes = rockdem_bench::parseList<long>(argv[++i]);
    } else if (a == "--steps" && hasValue) {
      o.steps = std::atol(argv[++i]);
    } else if (a == "--packs" && hasValue) {
      o.packs = rockdem_bench::parseList<std::string>(argv[++i]);
    } else if (a == "--backend" && hasValue) {
      o.backends = rockdem_bench::parseList<std::string>(argv[++i]);
    } else if (a == "--pack" && hasValue) {
      o.pack = argv[++i];
    } else if (a == "--threads" && hasValue) {
      o.threads = rockdem_bench::parseList<int>(argv[++i]);
    } else if (a == "--restitution" && hasValue) {
      gRestitution = std::atof(argv[++i]);
    } else if (a == "--damping" && hasValue) {
      o.damping = std::atof(argv[++i]);
      o.dampingGiven = true;
    } else if (a == "--repeat" && hasValue) {
      o.repeat = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--threshold" && hasValue) {
      const std::string v = argv[++i];
      o.threshold = v == "default" ? -2 : std::atoll(v.c_str());
    } else if (a == "--sort") {
      o.sort = true;
    } else if (a == "--quick") {
      o.quick = true;
    } else if (a == "--stream") {
      o.stream = true;
    } else if (a == "--sweep") {
      o.sweep = true;
    } else if (a == "--csv" && hasValue) {
      o.csv = argv[++i];
    } else if (a == "--write-pack" && hasValue) {
      o.writePack = argv[++i];
    } else if (a == "--sweep-particles" && hasValue) {
      o.sweepParticles = std::atol(argv[++i]);
    } else if (a == "--read-pack" && hasValue) {
      o.readPack = argv[++i];
    } else if (a == "--pre" && hasValue) {
      o.pre = std::atol(argv[++i]);
    } else if (a == "--batch" && hasValue) {
      o.batch = std::atol(argv[++i]);
    } else if (a == "--safeties" && hasValue) {
      o.safeties = rockdem_bench::parseList<double>(argv[++i]);
    } else {
      usage(argv[0]);
    }
  }
  for (const std::string& p : o.packs) {
    if (p != "mono" && p != "poly" && p != "lattice" && p != "cemented") {
      usage(argv[0]);
    }
  }
  for (const std::string& b : o.backends) {
    if (b != "cpu" && b != "gpu") {
      usage(argv[0]);
    }
  }
  return o;
}

double secondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

int coreCount()
{
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

// ---------------------------------------------------------------------------------------
// Resident memory (Linux /proc/self/status; 0 elsewhere)

long readStatusKiB(const char* key)
{
  std::ifstream in("/proc/self/status");
  std::string line;
  const std::size_t len = std::strlen(key);
  while (std::getline(in, line)) {
    if (line.compare(0, len, key) == 0 && line.size() > len && line[len] == ':') {
      return std::atol(line.c_str() + len + 1);
    }
  }
  return 0;
}

/// VmRSS in bytes, after giving freed heap memory back to the system.
double residentBytes()
{
#ifdef __GLIBC__
  malloc_trim(0);
#endif
  return 1024.0 * static_cast<double>(readStatusKiB("VmRSS"));
}

/// Resets the peak resident size (VmHWM) to the current one (Linux >= 4.0).
void resetPeakResident()
{
  std::ofstream out("/proc/self/clear_refs");
  out << "5";
}

double peakResidentBytes() { return 1024.0 * static_cast<double>(readStatusKiB("VmHWM")); }

/// CPU seconds: (all processes on the machine, this process). Used to report how many
/// cores other processes kept busy during a timed run (the machine may be shared).
std::pair<double, double> cpuSeconds()
{
  double machine = 0.0;
  std::ifstream in("/proc/stat");
  std::string cpu;
  if (in >> cpu && cpu == "cpu") {
    double v[8] = { 0, 0, 0, 0, 0, 0, 0, 0 }; // user nice system idle iowait irq softirq steal
    for (double& x : v) {
      in >> x;
    }
    const double ticks = static_cast<double>(sysconf(_SC_CLK_TCK));
    machine = (v[0] + v[1] + v[2] + v[5] + v[6] + v[7]) / ticks;
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double self = usage.ru_utime.tv_sec + 1e-6 * usage.ru_utime.tv_usec +
    usage.ru_stime.tv_sec + 1e-6 * usage.ru_stime.tv_usec;
  return { machine, self };
}

/// Cores other processes kept busy between two cpuSeconds() readings `elapsed` s apart.
double othersBusy(const std::pair<double, double>& before, const std::pair<double, double>& after, double elapsed)
{
  return std::max(0.0, ((after.first - before.first) - (after.second - before.second)) / elapsed);
}

// ---------------------------------------------------------------------------------------
// Models

void setMaterial(dem::Model& m)
{
  m.material.density = kDensity;
  m.material.youngsModulus = kYoung;
  m.material.poissonsRatio = kPoisson;
  m.material.restitution = gRestitution;
  m.material.friction = kFriction;
  m.material.rollingFriction = 0.0;
  m.gravity = dem::Vec3(0.0, 0.0, -9.81);
}

/// Reorders the particle slots along the cells of a grid (cell edge = largest diameter),
/// visited in Morton (Z-curve) order (dem::spatialOrder). Ids move with their particles.
void sortSpatially(dem::Model& m)
{
  dem::permuteParticles(m.particles, dem::spatialOrder(m));
}

/// The benchmark model of `pack` with about `n` particles (the lattice rounds n to a cube).
/// mono/poly: the pack is placed in a region of square base W x W and height
/// `heightRatio` W at the placement porosity, in a box twice that height.
dem::Model makeBenchModel(const std::string& pack, long n, dem::PackReport* report = nullptr,
                          double heightRatio = 1.0)
{
  dem::Model m;
  setMaterial(m);
  if (pack == "cemented") {
    // The lattice, every touching pair bonded, under unconfined compression along Z.
    m = makeBenchModel("lattice", n);
    m.gravity.setZero();
    dem::CementParameters cement;
    cement.bondModulus = kYoung;
    cement.tensileStrength = 1e6;
    cement.cohesion = 2e6;
    cement.strengthScatter = 0.2;
    dem::cement(m, cement);
    dem::LoadTestSettings press;
    press.mode = dem::TestMode::Compression;
    press.strainRate = 1.0;
    press.maxStrain = 0.5;
    press.sampleInterval = 100;
    dem::startLoadTest(m, press);
    return m;
  }
  if (pack == "lattice") {
    const double r = 0.001; // m
    const long side = std::max(1L, std::lround(std::cbrt(static_cast<double>(n))));
    const double spacing = 2.0 * r * (1.0 - kLatticeOverlap);
    m.domain.origin = dem::Vec3::Zero();
    m.domain.size = dem::Vec3::Constant(side * spacing);
    m.particles.reserve(static_cast<std::size_t>(side * side * side));
    for (long k = 0; k < side; ++k) {
      for (long j = 0; j < side; ++j) {
        for (long i = 0; i < side; ++i) {
          const dem::Vec3 x((i + 0.5) * spacing, (j + 0.5) * spacing, (k + 0.5) * spacing);
          m.particles.append(x, r, m.nextId++);
        }
      }
    }
    dem::updateMassProperties(m);
    return m;
  }
  dem::PackParameters params;
  params.minimumSize = 0.001; // m
  params.maximumSize = pack == "mono" ? 0.001 : 0.002;
  params.initialElements = n;
  params.randomSeed = 12345;
  const double a = params.minimumSize;
  const double b = params.maximumSize;
  const double meanVolume = 4.0 / 3.0 * kPi * (a + b) * (a * a + b * b) / 4.0; // m^3
  // Pack region: W x W x heightRatio W holding n particles at the placement porosity; the
  // box is twice as tall, so the pack fills its lower half.
  const double volume = static_cast<double>(n) * meanVolume / (1.0 - kPlacementPorosity);
  const double edge = std::cbrt(volume / heightRatio);
  const double height = heightRatio * edge;
  m.domain.origin = dem::Vec3::Zero();
  m.domain.size = dem::Vec3(edge, edge, height);
  const dem::PackReport built = dem::buildPack(m, params);
  if (report) {
    *report = built;
  }
  m.domain.size.z() = 2.0 * height;
  return m;
}

/// Sets the timestep to safety x critical (above 1 with the test-only unsafe switch).
void setSafety(dem::Model& m, double safety)
{
  if (safety <= 1.0) {
    m.solver.timestepSafety = safety;
    m.solver.requestedTimestep = 0.0;
    m.solver.allowUnsafeTimestep = false;
  } else {
    m.solver.allowUnsafeTimestep = true;
    m.solver.requestedTimestep = safety * dem::criticalTimestep(m, m.solver.contactLaw);
  }
}

// ---------------------------------------------------------------------------------------
// Throughput

struct CsvOut {
  std::FILE* file = nullptr;
  explicit CsvOut(const std::string& path)
  {
    if (!path.empty()) {
      file = std::fopen(path.c_str(), "w");
      if (!file) {
        std::fprintf(stderr, "cannot write %s\n", path.c_str());
        std::exit(1);
      }
    }
  }
  ~CsvOut()
  {
    if (file) {
      std::fclose(file);
    }
  }
  void line(const std::string& text, bool echo)
  {
    if (echo) {
      std::printf("%s\n", text.c_str());
      std::fflush(stdout);
    }
    if (file) {
      std::fprintf(file, "%s\n", text.c_str());
      std::fflush(file);
    }
  }
};

long defaultSteps(long n)
{
  if (n <= 20000) {
    return 2000;
  }
  if (n <= 200000) {
    return 500;
  }
  return 200;
}

int runThroughput(const Options& o)
{
  CsvOut csv(o.csv);
  std::vector<int> threadList = o.threads;
  if (threadList.empty()) {
    threadList.push_back(1);
    if (coreCount() > 1) {
      threadList.push_back(coreCount());
    }
  }
  std::printf("RockDEM solver throughput: Hertz-Mindlin, E %.3g Pa, nu %.2f, rho %.0f, e %.2f, mu %.2f, "
              "damping %.2f, gravity 9.81, Timestep Safety 0.1%s; %d cores\n",
              kYoung, kPoisson, kDensity, gRestitution, kFriction, o.damping,
              o.sort ? ", particles sorted spatially" : "", coreCount());
  std::printf("%-8s %9s %7s %-22s %6s %10s %8s %12s %9s %8s %8s %8s %7s\n", "pack", "N", "threads",
              "path", "steps", "dt(s)", "time(s)", "p-steps/s", "contacts", "model", "solver",
              "peak", "others");
  std::printf("%-8s %9s %7s %-22s %6s %10s %8s %12s %9s %8s %8s %8s %7s\n", "", "", "", "", "", "",
              "", "", "(end)", "B/part", "B/part", "B/part", "(cores)");
  csv.line("pack,N,threads,path,steps,timestep_s,seconds,particle_steps_per_s,contacts_end,"
           "model_bytes_per_particle,solver_bytes_per_particle,peak_bytes_per_particle,kinetic_energy_end_J,"
           "other_processes_cores",
           false);
  if (std::find(o.backends.begin(), o.backends.end(), "gpu") != o.backends.end()) {
    const std::string whyNot = dem::gpuUnavailableReason();
    if (!whyNot.empty()) {
      // The GPU rows then show the fallback (the CPU) and its reason.
      std::printf("GPU: no usable Vulkan device on this machine: %s\n", whyNot.c_str());
    }
  }
  for (long requested : o.sizes) {
    const long steps = o.steps > 0 ? o.steps : (o.quick ? 50 : defaultSteps(requested));
    for (const std::string& pack : o.packs) {
     for (const std::string& backend : o.backends) {
      const bool gpu = backend == "gpu";
      // The GPU backend's host side (its first neighbour list) uses all cores.
      const std::vector<int> threadsToRun = gpu ? std::vector<int>{ coreCount() } : threadList;
      for (int threads : threadsToRun) {
        double seconds = 0.0;
        dem::DeviceMemory device;
        std::size_t bonds = 0;
        double rss0 = 0.0, rss1 = 0.0, rss2 = 0.0, peak = 0.0, n = 0.0;
        std::size_t contacts = 0;
        double kinetic = 0.0;
        double others = 0.0; // cores used by other processes during the fastest run
        std::string path;
        double timestep = 0.0;
        dem::PackReport report;
        for (int rep = 0; rep < o.repeat; ++rep) {
          rss0 = residentBytes();
          dem::Model model = makeBenchModel(pack, requested, &report);
          if (o.sort) {
            sortSpatially(model);
          }
          model.solver.settlingDamping = o.damping;
          model.solver.threads = threads;
          if (o.threshold >= 0) {
            model.solver.parallelThreshold = o.threshold;
          } else if (o.threshold == -1 && threads > 1) {
            model.solver.parallelThreshold = 0;
          }
          n = static_cast<double>(model.particles.size());
          rss1 = residentBytes();
          dem::Simulation sim(model, gpu ? dem::SolverDevice::GPU : dem::SolverDevice::CPU);
          rss2 = residentBytes();
          resetPeakResident();
          const auto cpu0 = cpuSeconds();
          const auto start = std::chrono::steady_clock::now();
          sim.advance(steps);
          const double elapsed = secondsSince(start);
          const auto cpu1 = cpuSeconds();
          peak = peakResidentBytes();
          if (rep == 0 || elapsed < seconds) {
            seconds = elapsed;
            others = othersBusy(cpu0, cpu1, elapsed);
          }
          contacts = sim.diagnostics().contacts;
          kinetic = sim.diagnostics().kineticEnergy;
          path = sim.path();
          timestep = sim.timestep();
          device = sim.deviceMemory();
          bonds = model.bonds.size();
        }
        // The table keeps the path short; the device and any fallback reason follow it.
        const std::string fullPath = path;
        if (path.rfind("GPU Vulkan", 0) == 0) {
          path = "GPU Vulkan";
        } else if (path.find(": GPU requested") != std::string::npos) {
          path = path.substr(0, path.find(": GPU requested")) + " (fallback)";
        }
        const double rate = n * static_cast<double>(steps) / seconds;
        const double modelBytes = (rss1 - rss0) / n;
        const double solverBytes = (rss2 - rss1) / n;
        const double peakBytes = (peak - rss0) / n;
        std::printf("%-8s %9.0f %7d %-22s %6ld %10.4g %8.3f %12.4g %9zu %8.0f %8.0f %8.0f %7.2f\n",
                    pack.c_str(), n, threads, path.c_str(), steps, timestep, seconds, rate,
                    contacts, modelBytes, solverBytes, peakBytes, others);
        std::fflush(stdout);
        char line[512];
        std::string csvPath = path; // the path says why with commas: ';' keeps the columns
        std::replace(csvPath.begin(), csvPath.end(), ',', ';');
        std::snprintf(line, sizeof(line), "%s,%.0f,%d,%s,%ld,%.9g,%.6f,%.6g,%zu,%.1f,%.1f,%.1f,%.8g,%.2f",
                      pack.c_str(), n, threads, csvPath.c_str(), steps, timestep, seconds, rate,
                      contacts, modelBytes, solverBytes, peakBytes, kinetic, others);
        csv.line(line, false);
        if (report.saturated) {
          std::printf("  note: %s\n", report.summary().c_str());
        }
        if (gpu && device.total == 0) {
          std::printf("  %s\n", fullPath.c_str());
        } else if (gpu) {
          std::printf("  %s; device memory %.0f MiB: %.0f B/particle, %.0f B per pair slot (%.1f slots/particle), "
                      "%.0f B/bond (%zu bonds)\n",
                      fullPath.c_str(), device.total / 1048576.0, device.perParticle, device.perPair,
                      n > 0 ? device.pairSlots / n : 0.0, device.perBond, bonds);
        }
      }
     }
    }
  }
  return 0;
}

int writePack(const Options& o)
{
  const long n = o.sizes.empty() ? 10000 : o.sizes.front();
  dem::Model model = makeBenchModel(o.pack, n);
  if (o.sort) {
    sortSpatially(model);
  }
  model.solver.settlingDamping = o.damping;
  const double critical = dem::criticalTimestep(model, model.solver.contactLaw);
  std::FILE* f = std::fopen(o.writePack.c_str(), "w");
  if (!f) {
    std::fprintf(stderr, "cannot write %s\n", o.writePack.c_str());
    return 1;
  }
  const dem::Particles& p = model.particles;
  const dem::Vec3 lo = model.domain.origin;
  const dem::Vec3 hi = model.domain.upper();
  const auto [rmin, rmax] = std::minmax_element(p.radius.begin(), p.radius.end());
  std::fprintf(f, "# RockDEM bench_solver pack '%s'\n", o.pack.c_str());
  std::fprintf(f, "# particles %zu\n", p.size());
  std::fprintf(f, "# box %.17g %.17g %.17g %.17g %.17g %.17g\n", lo.x(), hi.x(), lo.y(), hi.y(),
               lo.z(), hi.z());
  std::fprintf(f, "# timestep %.17g\n", model.solver.timestepSafety * critical);
  std::fprintf(f, "# critical_timestep %.17g\n", critical);
  std::fprintf(f, "# skin %.17g\n", model.solver.skin * *rmin);
  std::fprintf(f, "# radius_min %.17g\n# radius_max %.17g\n", *rmin, *rmax);
  std::fprintf(f, "# density %.17g\n# youngs_modulus %.17g\n# poissons_ratio %.17g\n",
               model.material.density, model.material.youngsModulus,
               model.material.poissonsRatio);
  std::fprintf(f, "# restitution %.17g\n# friction %.17g\n# gravity %.17g\n",
               model.material.restitution, model.material.friction, -model.gravity.z());
  std::fprintf(f, "# columns: id type diameter density x y z\n");
  for (std::size_t i = 0; i < p.size(); ++i) {
    std::fprintf(f, "%lld 1 %.17g %.17g %.17g %.17g %.17g\n", static_cast<long long>(p.id[i] + 1),
                 2.0 * p.radius[i], model.material.density, p.position[i].x(),
                 p.position[i].y(), p.position[i].z());
  }
  std::fclose(f);
  std::printf("wrote %zu particles to %s (timestep %.9g s)\n", p.size(), o.writePack.c_str(),
              model.solver.timestepSafety * critical);
  return 0;
}

// ---------------------------------------------------------------------------------------
// Sweep: speed against accuracy

struct SweepScale {
  double energyModelSteps = 5000.0; // energy test model time, in critical timesteps
  long settleParticles = 5000;
  double settleTime = 0.1;          // s
};

std::string statusOf(const std::exception& e)
{
  std::string s = e.what();
  const bool escaped = s.find("escaped") != std::string::npos;
  const bool energy = s.find("kinetic energy") != std::string::npos;
  const bool nonFinite = s.find("non-finite") != std::string::npos;
  return escaped ? "unstable:escaped" : energy ? "unstable:energy" : nonFinite ? "unstable:nan" : "unstable";
}

dem::Model emptyBox(double e, double box)
{
  dem::Model m;
  m.domain.origin = dem::Vec3::Constant(-0.5 * box);
  m.domain.size = dem::Vec3::Constant(box);
  setMaterial(m);
  m.material.restitution = e;
  m.material.friction = 0.0;
  m.gravity.setZero();
  m.solver.settlingDamping = 0.0;
  return m;
}

struct Impact {
  bool ended = false;
  std::string status = "ok";
  double restitution = 0.0; // delivered
  double maxForce = 0.0;    // N
  long stepsInContact = 0;
  double timestep = 0.0;
};

/// A 1 mm sphere hits the low Z wall head-on at 1 m/s.
Impact sphereWallImpact(double safety, double e)
{
  Impact out;
  dem::Model m = emptyBox(e, 0.02);
  const double r = 0.001;
  const double speed = 1.0;
  m.particles.append(dem::Vec3(0.0, 0.0, m.domain.origin.z() + r + 1.0e-7), r, m.nextId++);
  m.particles.velocity[0] = dem::Vec3(0.0, 0.0, -speed);
  dem::updateMassProperties(m);
  setSafety(m, safety);
  try {
    dem::Simulation sim(m);
    out.timestep = sim.timestep();
    const double floorZ = m.domain.origin.z();
    auto overlap = [&] { return r - (m.particles.position[0].z() - floorZ); };
    bool started = false;
    for (long k = 0; k < 1000000; ++k) {
      sim.advance(1);
      const double d = overlap();
      if (d > 0.0) {
        started = true;
        ++out.stepsInContact;
        out.maxForce = std::max(out.maxForce, m.walls[4].force.norm());
      } else if (started) {
        out.ended = true;
        break;
      }
    }
    out.restitution = m.particles.velocity[0].z() / speed;
    if (!out.ended) {
      out.status = "no-rebound";
    }
  } catch (const dem::InstabilityError& ex) {
    out.status = statusOf(ex);
  }
  return out;
}

struct EnergyRun {
  std::string status = "ok";
  double drift = 0.0; // worst |E - E0| / E0
  long steps = 0;
  double seconds = 0.0;
};

/// 40 elastic frictionless spheres (2 mm) at random speeds up to 1 m/s per axis in a
/// 4 cm box, no gravity, no damping (as Testing/Solver/TestDynamics.cpp, Energy test).
EnergyRun elasticEnergy(double safety, const SweepScale& scale)
{
  EnergyRun out;
  dem::Model m = emptyBox(1.0, 0.04);
  dem::Random rng(5);
  for (int k = 0; k < 40; ++k) {
    const dem::Vec3 x(rng.uniform(-0.015, 0.015), rng.uniform(-0.015, 0.015),
                      rng.uniform(-0.015, 0.015));
    bool clear = true;
    for (std::size_t j = 0; j < m.particles.size(); ++j) {
      clear = clear && (m.particles.position[j] - x).norm() > 0.0045;
    }
    if (clear) {
      const std::size_t s = m.particles.size();
      m.particles.append(x, 0.002, m.nextId++);
      m.particles.velocity[s] =
        dem::Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    }
  }
  dem::updateMassProperties(m);
  setSafety(m, safety);
  const double critical = dem::criticalTimestep(m, m.solver.contactLaw);
  const long total = std::max(1L, std::lround(scale.energyModelSteps / safety));
  const long batch = std::max(1L, total / 100);
  (void)critical;
  const auto start = std::chrono::steady_clock::now();
  try {
    dem::Simulation sim(m);
    const double e0 = sim.totalEnergy();
    while (out.steps < total) {
      const long now = std::min(batch, total - out.steps);
      sim.advance(now);
      out.steps += now;
      out.drift = std::max(out.drift, std::abs(sim.totalEnergy() - e0) / e0);
    }
  } catch (const dem::InstabilityError& ex) {
    out.status = statusOf(ex);
  }
  out.seconds = secondsSince(start);
  return out;
}

struct SettleRun {
  std::string status = "ok";
  long steps = 0;
  double seconds = 0.0;
  double kinetic = 0.0;  // J
  double porosity = 0.0;
  double unbalanced = 0.0;
};

SettleRun settle(double safety, const SweepScale& scale)
{
  SettleRun out;
  // A flat pack (height W/8) so that it lands and settles within the model time.
  dem::Model m = makeBenchModel("poly", scale.settleParticles, nullptr, 0.125);
  m.solver.threads = 1; // a few thousand particles: the serial path is the faster one
  setSafety(m, safety);
  const auto start = std::chrono::steady_clock::now();
  try {
    dem::Simulation sim(m);
    const long total = std::max(1L, std::lround(scale.settleTime / sim.timestep()));
    const long batch = std::max(1L, total / 20);
    while (out.steps < total) {
      const long now = std::min(batch, total - out.steps);
      sim.advance(now);
      out.steps += now;
    }
    const dem::Diagnostics d = sim.diagnostics();
    out.kinetic = d.kineticEnergy;
    out.unbalanced = d.unbalancedForceRatio;
    out.porosity = dem::currentPorosity(m);
  } catch (const dem::InstabilityError& ex) {
    out.status = statusOf(ex);
  }
  out.seconds = secondsSince(start);
  return out;
}

int runSweep(const Options& o)
{
  CsvOut csv(o.csv);
  SweepScale scale;
  std::vector<double> safeties = o.safeties;
  scale.settleParticles = o.sweepParticles;
  if (o.quick) {
    scale.energyModelSteps = 200.0;
    scale.settleParticles = std::min(o.sweepParticles, 300L);
    scale.settleTime = 0.005;
    safeties = { 0.1, 3.0 };
  }
  // Hertz closed form for the elastic impact (PHYSICS.md s.1), rigid wall.
  const double r = 0.001;
  const double mass = kDensity * 4.0 / 3.0 * kPi * r * r * r;
  const double estar = kYoung / (1.0 - kPoisson * kPoisson);
  const double dmax = std::pow(15.0 * mass / (16.0 * estar * std::sqrt(r)), 0.4);
  const double fmax = 4.0 / 3.0 * estar * std::sqrt(r) * std::pow(dmax, 1.5);
  const double tc = 2.94328 * dmax;
  std::fprintf(stderr, "sweep: impact reference Fmax %.6g N, contact time %.6g s; settle %ld particles "
               "for %.3g s; %d cores\n", fmax, tc, scale.settleParticles, scale.settleTime, coreCount());
  csv.line("safety,unsafe_switch,impact_timestep_s,restitution_requested,restitution_delivered,"
           "restitution_error,restitution_elastic,peak_force_N,peak_force_reference_N,peak_force_error,"
           "steps_per_collision,collision_time_steps_reference,impact_seconds,impact_status,"
           "energy_drift,energy_steps,energy_seconds,energy_status,settle_particles,"
           "settle_steps,settle_seconds,settle_kinetic_J,settle_porosity,settle_unbalanced_ratio,"
           "settle_status,stable",
           true);
  for (double s : safeties) {
    const auto t0 = std::chrono::steady_clock::now();
    const Impact damped = sphereWallImpact(s, kRestitution);
    const Impact elastic = sphereWallImpact(s, 1.0);
    const double impactSeconds = secondsSince(t0);
    std::string impactStatus = damped.status == "ok" ? elastic.status : damped.status;
    if (impactStatus == "ok" && (damped.restitution > 1.0 || elastic.restitution > 1.001)) {
      impactStatus = "energy-gain"; // bounced back faster than it came: the step is too long
    }
    const EnergyRun energy = elasticEnergy(s, scale);
    const SettleRun settled = settle(s, scale);
    const bool stable = impactStatus.rfind("unstable", 0) != 0 &&
      energy.status == "ok" && settled.status == "ok";
    char line[1024];
    std::snprintf(line, sizeof(line),
                  "%.4g,%d,%.6g,%.3g,%.6g,%.4g,%.6g,%.6g,%.6g,%.4g,%ld,%.4g,%.4f,%s,%.4g,%ld,%.4f,%s,"
                  "%ld,%ld,%.4f,%.6g,%.5f,%.4g,%s,%d",
                  s, s > 1.0 ? 1 : 0, elastic.timestep, kRestitution, damped.restitution,
                  std::abs(damped.restitution - kRestitution), elastic.restitution, elastic.maxForce, fmax,
                  std::abs(elastic.maxForce - fmax) / fmax, elastic.stepsInContact,
                  elastic.timestep > 0.0 ? tc / elastic.timestep : 0.0, impactSeconds,
                  impactStatus.c_str(), energy.drift, energy.steps, energy.seconds,
                  energy.status.c_str(), scale.settleParticles, settled.steps, settled.seconds,
                  settled.kinetic, settled.porosity, settled.unbalanced, settled.status.c_str(),
                  stable ? 1 : 0);
    csv.line(line, true);
  }
  return 0;
}

} // namespace

/// The memory bandwidth bound of this machine: a STREAM-like triad a = b + s c over three
/// arrays of 32 Mi doubles (768 MiB, far above any cache), counted as 3 x 8 bytes per
/// element (the write-allocate read of a is not counted, as in STREAM). Fastest of --repeat.
int runStream(const Options& o)
{
  const std::size_t n = std::size_t{ 1 } << 25;
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  std::vector<int> threadList = o.threads;
  if (threadList.empty()) {
    threadList.push_back(1);
    if (coreCount() > 1) {
      threadList.push_back(coreCount());
    }
  }
  std::printf("STREAM-like triad, %zu doubles per array; GB/s = 24 bytes x elements / s (fastest of %d)\n", n,
              std::max(1, o.repeat));
  const long count = static_cast<long>(n);
  for (int threads : threadList) {
    double best = 0.0;
    for (int rep = 0; rep < std::max(1, o.repeat); ++rep) {
      const auto start = std::chrono::steady_clock::now();
#pragma omp parallel for schedule(static) num_threads(threads)
      for (long i = 0; i < count; ++i) {
        a[i] = b[i] + 3.0 * c[i];
      }
      const double seconds = secondsSince(start);
      best = std::max(best, 24.0 * static_cast<double>(n) / seconds / 1e9);
    }
    std::printf("threads %d: %.2f GB/s (check %g)\n", threads, best, a[n / 2]);
  }
  return 0;
}

// ---------------------------------------------------------------------------------------
// A pack file (--read-pack), with the settings of scripts/time_pack_pvpython.py

dem::Model readPackModel(const std::string& path, double& timestep)
{
  std::ifstream in(path);
  if (!in) {
    throw std::runtime_error("cannot read " + path);
  }
  dem::Model m;
  setMaterial(m);
  std::vector<double> box;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty()) {
      continue;
    }
    std::istringstream words(line);
    if (line[0] == '#') {
      std::string hash, key;
      words >> hash >> key;
      double v = 0.0;
      std::vector<double> values;
      while (words >> v) {
        values.push_back(v);
      }
      if (values.empty()) {
        continue;
      }
      if (key == "box") {
        box = values;
      } else if (key == "timestep") {
        timestep = values[0];
      } else if (key == "density") {
        m.material.density = values[0];
      } else if (key == "youngs_modulus") {
        m.material.youngsModulus = values[0];
      } else if (key == "poissons_ratio") {
        m.material.poissonsRatio = values[0];
      } else if (key == "restitution") {
        m.material.restitution = values[0];
      } else if (key == "friction") {
        m.material.friction = values[0];
      } else if (key == "gravity") {
        m.gravity = dem::Vec3(0.0, 0.0, -values[0]);
      }
      continue;
    }
    double id = 0.0, type = 0.0, diameter = 0.0, density = 0.0, x = 0.0, y = 0.0, z = 0.0;
    if (words >> id >> type >> diameter >> density >> x >> y >> z) {
      m.particles.append(dem::Vec3(x, y, z), 0.5 * diameter, m.nextId++);
    }
  }
  if (box.size() != 6 || m.particles.size() == 0) {
    throw std::runtime_error(path + ": no '# box' line or no particles");
  }
  m.domain.origin = dem::Vec3(box[0], box[2], box[4]);
  m.domain.size = dem::Vec3(box[1] - box[0], box[3] - box[2], box[5] - box[4]);
  dem::updateMassProperties(m);
  return m;
}

/// The timed steps of --read-pack, in batches (out of line: callgrind's --toggle-collect=timedAdvance*
/// counts these steps and not the untimed ones before them).
__attribute__((noinline)) void timedAdvance(dem::Simulation& sim, long total, long batch)
{
  const long b = batch > 0 ? batch : total;
  for (long done = 0; done < total; done += b) {
    sim.advance(std::min(b, total - done));
  }
}

/// FNV-1a over the bits of the particles' positions, velocities, spins and forces: equal
/// hashes say two runs ended bit for bit the same.
std::uint64_t stateHash(const dem::Particles& p)
{
  std::uint64_t h = 1469598103934665603ull;
  auto add = [&](const std::vector<dem::Vec3>& v) {
    for (const dem::Vec3& x : v) {
      for (int c = 0; c < 3; ++c) {
        std::uint64_t bits = 0;
        const double value = x[c];
        std::memcpy(&bits, &value, sizeof bits);
        h = (h ^ bits) * 1099511628211ull;
      }
    }
  };
  add(p.position);
  add(p.velocity);
  add(p.angularVelocity);
  add(p.force);
  add(p.torque);
  return h;
}

int runReadPack(const Options& o)
{
  std::vector<int> threadList = o.threads;
  if (threadList.empty()) {
    threadList = { 1, coreCount() };
  }
  const long steps = o.steps > 0 ? o.steps : 2000;
  const long pre = o.pre >= 0 ? o.pre : steps;
  std::printf("RockDEM solver on %s: %ld untimed steps, then %ld timed, advance() in batches of %ld; "
              "damping %.2f; %d cores\n", o.readPack.c_str(), pre, steps, o.batch,
              o.dampingGiven ? o.damping : 0.0, coreCount());
  std::printf("%-8s %7s %-22s %6s %10s %8s %12s %9s %12s %7s\n", "N", "threads", "path", "steps",
              "dt(s)", "time(s)", "p-steps/s", "contacts", "KE(J)", "others");
  for (int threads : threadList) {
    double best = 0.0, others = 0.0, timestep = 0.0, kinetic = 0.0, n = 0.0;
    std::size_t contacts = 0;
    std::string path;
    std::uint64_t hash = 0;
    for (int rep = 0; rep < o.repeat; ++rep) {
      double packTimestep = 0.0;
      dem::Model model = readPackModel(o.readPack, packTimestep);
      model.solver.settlingDamping = o.dampingGiven ? o.damping : 0.0;
      model.solver.timestepSafety = 0.2;
      model.solver.requestedTimestep = packTimestep;
      model.solver.threads = threads;
      if (o.threshold >= 0) {
        model.solver.parallelThreshold = o.threshold;
      }
      n = static_cast<double>(model.particles.size());
      dem::Simulation sim(model, dem::SolverDevice::CPU);
      const long b = o.batch > 0 ? o.batch : pre;
      for (long done = 0; done < pre; done += b) {
        sim.advance(std::min(b, pre - done));
      }
      const auto cpu0 = cpuSeconds();
      const auto start = std::chrono::steady_clock::now();
      timedAdvance(sim, steps, o.batch);
      const double elapsed = secondsSince(start);
      const auto cpu1 = cpuSeconds();
      if (rep == 0 || elapsed < best) {
        best = elapsed;
        others = othersBusy(cpu0, cpu1, elapsed);
      }
      contacts = sim.diagnostics().contacts;
      kinetic = sim.diagnostics().kineticEnergy;
      path = sim.path();
      timestep = sim.timestep();
      hash = stateHash(model.particles);
    }
    std::printf("%-8.0f %7d %-22s %6ld %10.4g %8.3f %12.4g %9zu %12.6g %7.2f\n", n, threads,
                path.substr(0, 22).c_str(), steps, timestep, best, n * static_cast<double>(steps) / best,
                contacts, kinetic, others);
    std::printf("  state hash %016llx; path: %s\n", static_cast<unsigned long long>(hash), path.c_str());
    std::fflush(stdout);
  }
  return 0;
}

int main(int argc, char** argv)
{
  Options o = parse(argc, argv);
  try {
    if (o.stream) {
      return runStream(o);
    }
    if (!o.writePack.empty()) {
      return writePack(o);
    }
    if (!o.readPack.empty()) {
      return runReadPack(o);
    }
    if (o.sweep) {
      return runSweep(o);
    }
    if (o.quick) {
      o.sizes = { 2000 };
      const int rc = runThroughput(o);
      Options s = o;
      s.csv.clear();
      return rc != 0 ? rc : runSweep(s);
    }
    return runThroughput(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rockdem_bench_solver: %s\n", e.what());
    return 1;
  }
}
