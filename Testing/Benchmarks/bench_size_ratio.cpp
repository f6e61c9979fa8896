// Benchmark: does the cost of a step grow with the radius ratio beyond the extra
// contacts? (issue "CPU solver": one grid per size class, each searched with the reach
// it needs.) For radius ratios 1, 2, 4, 8 and 16 (smallest radius fixed), a pack of N
// particles is built, grown so that particles touch, consolidated isotropically to
// 100 kPa by the servo walls, and then stepped (timed); the
// benchmark prints microseconds per particle-step, neighbour-list pairs and touching
// contacts per particle, and the cost per contact. Prints figures; asserts nothing.
//
//   rockdem_bench_size_ratio [--particles N] [--steps S]
#include "dem/LoadTest.h"
#include "dem/Pack.h"
#include "dem/Simulation.h"

#include <ctime>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

using namespace dem;

namespace {
double threadSeconds()
{
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
} // namespace

int main(int argc, char** argv)
{
  long particles = 20000;
  long steps = 200;
  for (int a = 1; a + 1 < argc; a += 2) {
    if (!std::strcmp(argv[a], "--particles")) particles = std::atol(argv[a + 1]);
    if (!std::strcmp(argv[a], "--steps")) steps = std::atol(argv[a + 1]);
  }
  std::printf("# size-ratio benchmark: %ld particles, %ld steps, 1 thread (thread CPU time), Hertz-Mindlin, E 1e8 Pa\n",
              particles, steps);
  std::printf("%6s %12s %14s %16s\n", "ratio", "us/p-step", "contacts/part", "ns per contact");
  for (double ratio : { 1.0, 2.0, 4.0, 8.0, 16.0 }) {
    const double rmin = 0.001;
    const double rmax = ratio * rmin;
    // Box for the requested count at a placement porosity of about 0.75.
    const double meanR3 = ratio == 1.0 ? rmin * rmin * rmin
                                       : (std::pow(rmax, 4) - std::pow(rmin, 4)) / (4.0 * (rmax - rmin));
    const double solid = particles * 4.0 / 3.0 * M_PI * meanR3;
    const double side = std::cbrt(solid / 0.25 / 2.0);
    Model m;
    m.domain.size = Vec3(side, side, 2.0 * side);
    m.material.youngsModulus = 1e8;
    m.solver.threads = 1;
    PackParameters p;
    p.initialElements = particles;
    p.minimumSize = rmin;
    p.maximumSize = rmax;
    buildPack(m, p);
    growElements(m);
    // Consolidate isotropically (servo walls, 100 kPa, no gravity) so that the contacts
    // are real and persist while the steps are timed.
    m.gravity.setZero();
    LoadTestSettings iso;
    iso.mode = TestMode::Isotropic;
    iso.confiningStress = 1e5;
    iso.sampleInterval = 200;
    startLoadTest(m, iso);
    Simulation sim(m);
    for (int k = 0; k < 100 && m.test.stage != TestStage::Done; ++k) {
      sim.advance(200);
    }
    // Thread CPU time: unaffected by other processes taking turns on the cores.
    const double t0 = threadSeconds();
    sim.advance(steps);
    const double seconds = threadSeconds() - t0;
    const Diagnostics d = sim.diagnostics();
    const double n = static_cast<double>(m.particles.size());
    const double perStep = seconds / (n * steps) * 1e6;
    const double contactsPer = 2.0 * d.contacts / n;
    std::printf("%6.0f %12.3f %14.2f %16.1f\n", ratio, perStep, contactsPer,
                contactsPer > 0 ? perStep * 1e3 / contactsPer : 0.0);
    std::fflush(stdout);
  }
  return 0;
}
