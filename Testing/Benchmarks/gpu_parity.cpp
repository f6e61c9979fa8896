// GPU parity check: one press test (a consolidated, cemented specimen under unconfined
// compression, run to past its peak) on the CPU backend and on the GPU backend, and how
// the two curves compare. On a device that rounds double precision as IEEE 754 (lavapipe)
// the runs are bitwise identical; on others (NVIDIA: division and square root may differ
// in the last bit) the bar is the curve within 1 %: peak stress, Young's modulus at 50 %
// of the peak, axial strain at the peak (Documentation/Benchmarks-GPU.md).
//
//   rockdem_gpu_parity [--particles 3000] [--rate 2] [--max-steps 20000]
//
// Prints one line per path and a verdict; exit status 0 when the curves agree within 1 %
// (or are bitwise identical), 1 otherwise (a GPU request that fell back included), 2 on a
// usage error, 77 (ctest's skip) when this machine has no usable Vulkan device.
#include "Specimens.h"

#include "dem/Cement.h"
#include "dem/Simulation.h"

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {

using namespace dem;

constexpr std::size_t kAxial = 18;  // "Axial Stress (Pa)"
constexpr std::size_t kStrainZ = 4; // "Strain Z"

struct Curve {
  double peak = 0.0;        // Pa
  double modulus = 0.0;     // Pa, secant at 50 % of the peak
  double peakStrain = 0.0;  // -
  std::size_t broken = 0;
  std::size_t rows = 0;
  double seconds = 0.0;
  std::string path;
};

Curve summarise(const Model& m)
{
  Curve c;
  c.peak = m.test.peakStress;
  double half = 0.0, halfStrain = 0.0;
  for (const auto& row : m.test.history) {
    if (row[kAxial] == c.peak) {
      c.peakStrain = row[kStrainZ];
    }
    if (half == 0.0 && row[kAxial] >= 0.5 * c.peak) {
      half = row[kAxial];
      halfStrain = row[kStrainZ];
    }
  }
  c.modulus = halfStrain > 0.0 ? half / halfStrain : 0.0;
  c.broken = countBonds(m.bonds).broken;
  c.rows = m.test.history.size();
  return c;
}

Curve press(Model m, SolverDevice device, long maxSteps, Model* end)
{
  const auto start = std::chrono::steady_clock::now();
  Simulation sim(m, device);
  for (long done = 0; done < maxSteps; done += 500) {
    sim.advance(500);
    const double axial = m.test.history.empty() ? 0.0 : m.test.history.back()[kAxial];
    if (m.test.peakStress > 0.0 && axial < 0.7 * m.test.peakStress) {
      break; // past the peak
    }
  }
  Curve c = summarise(m);
  c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  c.path = sim.path();
  *end = m;
  return c;
}

double relative(double a, double b)
{
  return a == b ? 0.0 : std::abs(a - b) / std::max(std::abs(a), std::abs(b));
}

template <class T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b)
{
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

} // namespace

int main(int argc, char** argv)
{
  int particles = 3000;
  double rate = 2.0;
  long maxSteps = 20000;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--particles") {
      particles = std::atoi(argv[i + 1]);
    } else if (a == "--rate") {
      rate = std::atof(argv[i + 1]);
    } else if (a == "--max-steps") {
      maxSteps = std::atol(argv[i + 1]);
    } else {
      std::fprintf(stderr, "usage: %s [--particles N] [--rate 1/s] [--max-steps N]\n", argv[0]);
      return 2;
    }
  }
  const std::string whyNot = gpuUnavailableReason();
  if (!whyNot.empty()) {
    std::printf("SKIPPED: no usable Vulkan device on this machine: %s\n", whyNot.c_str());
    return 77;
  }
  // The specimen: grown in a cube sized for the requested count, consolidated to 100 kPa,
  // cemented (Testing/Solver/Specimens.h), compressed at `rate` along Z.
  const double side = 0.02 * std::cbrt(particles / 450.0);
  Model m = testing::specimen(2 * particles, side, 0.0008, 0.0012, 11);
  testing::consolidate(m, 1e5);
  cement(m, testing::testCement());
  LoadTestSettings s;
  s.mode = TestMode::Compression;
  s.strainRate = rate;
  s.maxStrain = 0.2;
  s.sampleInterval = 20;
  startLoadTest(m, s);
  std::printf("press test: %zu particles, %zu bonds, strain rate %g 1/s, a history row every %lld steps\n",
              m.particles.size(), m.bonds.size(), rate, static_cast<long long>(s.sampleInterval));
  Model cpuEnd, gpuEnd;
  const Curve cpu = press(m, SolverDevice::CPU, maxSteps, &cpuEnd);
  const Curve gpu = press(m, SolverDevice::GPU, maxSteps, &gpuEnd);
  for (const Curve* c : { &cpu, &gpu }) {
    std::printf("%-45s peak %.6e Pa, E(50%%) %.6e Pa, strain at peak %.6e, broken bonds %zu, rows %zu, %.1f s\n",
                c->path.c_str(), c->peak, c->modulus, c->peakStrain, c->broken, c->rows, c->seconds);
  }
  if (gpu.path.rfind("GPU", 0) != 0) {
    std::printf("verdict: FAIL (the GPU request fell back: %s)\n", gpu.path.c_str());
    return 1;
  }
  const bool bitwise = sameBits(cpuEnd.test.history, gpuEnd.test.history) &&
    sameBits(cpuEnd.particles.position, gpuEnd.particles.position) &&
    sameBits(cpuEnd.bonds.failure, gpuEnd.bonds.failure);
  const double dPeak = relative(cpu.peak, gpu.peak);
  const double dModulus = relative(cpu.modulus, gpu.modulus);
  const double dStrain = relative(cpu.peakStrain, gpu.peakStrain);
  const bool within = dPeak <= 0.01 && dModulus <= 0.01 && dStrain <= 0.01;
  std::printf("relative differences: peak %.3g, E(50%%) %.3g, strain at peak %.3g; history, positions and "
              "bond failures %s\n",
              dPeak, dModulus, dStrain, bitwise ? "bitwise identical" : "not bitwise identical");
  std::printf("verdict: %s\n", bitwise ? "PASS (bitwise identical)"
                                       : (within ? "PASS (curve within 1 %)" : "FAIL (curve differs by more than 1 %)"));
  return (bitwise || within) ? 0 : 1;
}
