// The memory a model will take, known before it is built (dem/MemoryEstimate.h; DEM Pack
// Source's Estimated Memory). References: the measured bytes per particle of
// Documentation/Benchmarks-Solver.md (model 180 B, solver 545-549 B on a contact-rich
// lattice), measured again here as the growth of the resident memory (VmRSS after
// malloc_trim, as bench_solver measures it) of a dense lattice model and its stepping
// solver: within 30 %. The particle count a pack will make: Initial Elements, or the count
// that fills the box to Target Porosity (checked against Add Elements within 10 %: Add
// Elements measures the porosity up to the top of the pack, and made 8 % more).
#include "dem/MemoryEstimate.h"
#include "dem/Model.h"
#include "dem/Pack.h"
#include "dem/Simulation.h"

#include <gtest/gtest.h>

#include <malloc.h>

#include <cstdio>
#include <fstream>
#include <string>

using namespace dem;

namespace {

/// Resident memory of this process, bytes (VmRSS of /proc/self/status).
double residentBytes()
{
  malloc_trim(0);
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == "VmRSS:") {
      double kb = 0.0;
      status >> kb;
      return kb * 1024.0;
    }
    std::getline(status, key);
  }
  return 0.0;
}

} // namespace

TEST(MemoryEstimate, ModelAndSolverOfADenseLatticeWithin30PercentOfTheMeasuredGrowth)
{
  const int n = 30; // 27,000 touching spheres on a simple cubic lattice (6 contacts each)
  const double r = 0.001;
  const double before = residentBytes();
  double grown = 0.0;
  {
    Model m;
    m.domain.size = Vec3(n * 2 * r, n * 2 * r, n * 2 * r);
    m.gravity.setZero();
    m.solver.threads = 1;
    std::int64_t id = 0;
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        for (int k = 0; k < n; ++k) {
          m.particles.append(Vec3((2 * i + 1) * r, (2 * j + 1) * r, (2 * k + 1) * r * 0.999), r, id++);
        }
      }
    }
    updateMassProperties(m);
    Simulation sim(m);
    sim.advance(3);
    grown = residentBytes() - before;
  }
  const double estimate = estimateMemory(n * n * n);
  std::printf("[memory] %d particles: resident growth %.4g B (%.0f B/particle), estimate %.4g B (%.0f B/particle)\n",
    n * n * n, grown, grown / (n * n * n), estimate, estimate / (n * n * n));
  EXPECT_GT(grown, 0.7 * estimate);
  EXPECT_LT(grown, 1.3 * estimate);
  EXPECT_DOUBLE_EQ(estimateMemory(1000, 500), 1000 * (ModelBytesPerParticle + SolverBytesPerParticle) + 500 * BytesPerBond);
}

TEST(MemoryEstimate, ParticleCountOfAPackThatAddsElementsToTheTargetPorosity)
{
  Model m;
  m.domain.size = Vec3(0.03, 0.03, 0.03);
  PackParameters p;
  p.initialElements = 100;
  p.minimumSize = 0.001;
  p.maximumSize = 0.0015;
  p.targetPorosity = 0.8; // reachable by random placement
  EXPECT_EQ(expectedParticleCount(p, m.domain, false), 100.0);
  const double expected = expectedParticleCount(p, m.domain, true);
  buildPack(m, p);
  addElements(m, p);
  const double made = static_cast<double>(m.particles.size());
  std::printf("[count] expected %.0f particles, Add Elements made %.0f\n", expected, made);
  EXPECT_NEAR(made, expected, 0.10 * expected);
}
