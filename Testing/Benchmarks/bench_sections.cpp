// Section and voxel-model figures (Documentation/Sections.md, "Speed and memory"): time and
// peak memory of the particle stresses, a plane section and voxel models of a cemented
// model with broken bonds.
//   rockdem_bench_sections [--particles N] [--voxels 64,128,...] [--threads T]
// The model: N particles on a jittered cubic lattice (spacing 2 mm, radii 1.0-1.1 mm, so
// each touches its neighbours), cemented (gap tolerance 0.5), every tenth bond broken.
// Memory is the growth of the peak resident set over the stage (VmHWM, reset before each
// stage through /proc/self/clear_refs); CPU is user + system time of all threads.
#include "dem/Bonds.h"
#include "dem/Cement.h"
#include "dem/Model.h"
#include "dem/ParticleStress.h"
#include "dem/Random.h"
#include "dem/Section.h"
#include "dem/Voxelize.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/resource.h>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace {

double seconds(std::chrono::steady_clock::time_point since)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

/// CPU seconds of the process so far (user + system, all threads).
double cpuSeconds()
{
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + 1e-6 * u.ru_utime.tv_usec + u.ru_stime.tv_sec + 1e-6 * u.ru_stime.tv_usec;
}

/// A line of /proc/self/status in MiB (VmRSS, VmHWM).
double statusMiB(const char* key)
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind(key, 0) == 0) {
      return std::atof(line.c_str() + std::strlen(key) + 1) / 1024.0;
    }
  }
  return 0.0;
}

/// Resets the peak resident set to the current one; returns the current one (MiB).
double resetPeak()
{
  std::ofstream("/proc/self/clear_refs") << "5";
  return statusMiB("VmRSS");
}

struct Stage {
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  double cpu = cpuSeconds();
  double base = resetPeak();
  void report(const char* what, const std::string& detail) const
  {
    std::printf("%-34s %7.2f s wall %7.2f s CPU  peak +%6.0f MiB  %s\n", what, seconds(start),
                cpuSeconds() - cpu, statusMiB("VmHWM") - base, detail.c_str());
    std::fflush(stdout);
  }
};

} // namespace

int main(int argc, char** argv)
{
  long particles = 1000000;
  std::vector<int> voxels = { 64, 128 };
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--particles")) {
      particles = std::atol(argv[i + 1]);
    } else if (!std::strcmp(argv[i], "--voxels")) {
      voxels.clear();
      std::stringstream list(argv[i + 1]);
      std::string item;
      while (std::getline(list, item, ',')) {
        voxels.push_back(std::atoi(item.c_str()));
      }
    } else if (!std::strcmp(argv[i], "--threads")) {
#ifdef _OPENMP
      omp_set_num_threads(std::atoi(argv[i + 1]));
#endif
    }
  }
  int threads = 1;
#ifdef _OPENMP
  threads = omp_get_max_threads();
#endif

  // The model.
  Stage build;
  const int side = static_cast<int>(std::lround(std::cbrt(static_cast<double>(particles))));
  const double spacing = 0.002; // m
  dem::Model m;
  m.domain.size = dem::Vec3::Constant(side * spacing);
  m.material.youngsModulus = 1e8;
  m.gravity.setZero();
  dem::Random rng(17);
  m.particles.reserve(static_cast<std::size_t>(side) * side * side);
  for (int k = 0; k < side; ++k) {
    for (int j = 0; j < side; ++j) {
      for (int i = 0; i < side; ++i) {
        const dem::Vec3 x = spacing * (dem::Vec3(i, j, k) + dem::Vec3::Constant(0.5) +
                                       0.02 * dem::Vec3(rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5));
        m.particles.append(x, spacing * (0.5 + 0.05 * rng.uniform()), m.nextId++);
      }
    }
  }
  dem::updateMassProperties(m);
  dem::CementParameters c;
  c.gapTolerance = 0.5;
  dem::cement(m, c);
  for (std::size_t b = 0; b < m.bonds.size(); b += 10) {
    m.bonds.markBroken(b, dem::BondFailure::Tension, 0.0, dem::Vec3::Zero(), dem::Vec3::UnitZ());
  }
  char detail[256];
  std::snprintf(detail, sizeof detail, "%zu particles (%d^3), %zu bonds, %zu broken, %d threads", m.particles.size(),
                side, m.bonds.size(), dem::countBonds(m.bonds).broken, threads);
  build.report("model (lattice, cement)", detail);

  // Particle stresses (a Simulation built on a copy evaluates the forces).
  Stage stress;
  const std::vector<dem::StressTensor> s = dem::particleStresses(m);
  double largest = 0.0;
  for (const dem::StressTensor& t : s) {
    largest = std::max(largest, dem::vonMisesStress(t, false));
  }
  std::snprintf(detail, sizeof detail, "largest von Mises %.3g Pa", largest);
  stress.report("particle stresses", detail);

  // A section through the middle.
  Stage cut;
  dem::SectionParameters p;
  p.orientation = dem::SectionOrientation::XZ;
  p.origin = 0.5 * m.domain.size + dem::Vec3(0.0, 0.3 * spacing, 0.0);
  const dem::ModelSection section = dem::sectionModel(m, p);
  std::snprintf(detail, sizeof detail, "%zu circles, %zu crossings, %zu traces", section.circles.size(),
                section.crossings.size(), section.traces.size());
  cut.report("section XZ", detail);

  // Voxel models.
  for (int n : voxels) {
    Stage vox;
    dem::VoxelParameters v;
    v.numberOfVoxels = n;
    v.margin = 0.0;
    v.memoryLimit = 16384;
    try {
      const dem::VoxelModel model = dem::voxelize(m, v, s, nullptr);
      const double error = (model.solidVolume - model.particleVolume) / model.particleVolume;
      std::snprintf(detail, sizeof detail, "%d x %d x %d voxels, solid volume error %.1e", model.grid.dimensions[0],
                    model.grid.dimensions[1], model.grid.dimensions[2], error);
      char what[64];
      std::snprintf(what, sizeof what, "voxel model, %d along the longest", n);
      vox.report(what, detail);
    } catch (const std::exception& e) {
      std::printf("voxel model, %d along the longest: %s\n", n, e.what());
    }
  }
  return 0;
}
