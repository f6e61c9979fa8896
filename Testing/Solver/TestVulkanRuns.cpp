// Whole runs on the Vulkan device (lavapipe in CI) against the CPU backend: the same
// particles, contacts, bonds, walls, history rows and clock, bit for bit (DESIGN.md
// "Determinism": results depend on inputs only). Reference: the CPU backend, whose physics
// the other suites check against analytic solutions and published benchmarks. Also: the
// device lists grow without losing a step, a state saved from a GPU run resumes on either
// path, and every reason not to use the GPU falls back to the CPU with a message.
#include "RequireVulkan.h"
#include "StateFixtures.h"
#include "backends/cpu/CpuBackend.h"
#include "backends/vulkan/VulkanBackend.h"
#include "dem/Cement.h"
#include "dem/Overlaps.h"
#include "dem/ParticleStress.h"
#include "dem/Specimen.h"
#include "dem/StateFile.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <cmath>
#include <string>

namespace {

using namespace dem;

/// Runs `model` for the given advance() calls on the CPU and on the GPU and returns the
/// first difference of the two end states (empty: bitwise identical).
std::string cpuGpuDifference(const Model& start, const std::vector<std::int64_t>& batches,
                             Model* cpuEnd = nullptr, Model* gpuEnd = nullptr)
{
  Model cpu = start;
  Model gpu = start;
  {
    Simulation a(cpu, SolverDevice::CPU);
    Simulation b(gpu, SolverDevice::GPU);
    EXPECT_EQ(b.path().rfind("GPU Vulkan: ", 0), 0u) << b.path();
    auto seconds = [](auto start) {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    double cpuSeconds = 0.0, gpuSeconds = 0.0;
    for (std::int64_t steps : batches) {
      const auto t0 = std::chrono::steady_clock::now();
      a.advance(steps);
      cpuSeconds += seconds(t0);
      const auto t1 = std::chrono::steady_clock::now();
      b.advance(steps);
      gpuSeconds += seconds(t1);
    }
    std::printf("%zu particles, %lld steps: CPU (%s) %.2f s, GPU (%s) %.2f s\n", start.particles.size(),
                static_cast<long long>(cpu.clock.step - start.clock.step), a.path().c_str(), cpuSeconds,
                b.path().c_str(), gpuSeconds);
    const Diagnostics da = a.diagnostics();
    const Diagnostics db = b.diagnostics();
    EXPECT_EQ(da.contacts, db.contacts);
    EXPECT_EQ(da.kineticEnergy, db.kineticEnergy);
    EXPECT_EQ(da.unbalancedForceRatio, db.unbalancedForceRatio);
    using statetest::sameForces;
    // The per-particle stress (issue 16) reads the interaction forces from the backend.
    const InteractionForces fa = a.interactionForces();
    EXPECT_GT(fa.size(), 0u);
    EXPECT_TRUE(sameForces(fa, b.interactionForces())) << "interaction forces (the per-particle stress) differ";
    // A frame's stresses and porosity (DEM Load Test): the GPU run's, from a solver made
    // from its state, are the CPU run's, from its own lists; the overlaps from the
    // device's neighbour list are the search's.
    EXPECT_TRUE(sameForces(a.freshInteractionForces(), b.freshInteractionForces()))
      << "the forces of a solver made from the state differ";
    const OverlapReport oa = a.overlaps();
    const OverlapReport ob = b.overlaps();
    const OverlapReport searched = measureOverlaps(gpu);
    EXPECT_EQ(oa.pairs, searched.pairs);
    EXPECT_EQ(ob.pairs, searched.pairs);
    EXPECT_EQ(std::memcmp(&ob.volume, &searched.volume, sizeof(double)), 0);
    EXPECT_EQ(std::memcmp(&oa.volume, &searched.volume, sizeof(double)), 0);
  }
  if (cpuEnd) {
    *cpuEnd = cpu;
  }
  if (gpuEnd) {
    *gpuEnd = gpu;
  }
  return statetest::firstDifference(cpu, gpu);
}

/// A cemented specimen of n grains in a cube (grown, no gravity), ready for a press test.
Model cementedSpecimen(int n, double side, std::uint64_t seed)
{
  Model m = dem::testing::specimen(n, side, 0.0008, 0.0012, seed);
  cement(m, dem::testing::testCement());
  return m;
}

LoadTestSettings compression(double strainRate, std::int64_t sampleInterval)
{
  LoadTestSettings s;
  s.mode = TestMode::Compression;
  s.strainRate = strainRate;
  s.maxStrain = 0.2;
  s.sampleInterval = sampleInterval;
  return s;
}

} // namespace

TEST(VulkanRuns, CementedSpecimenUnderUnconfinedCompressionGivesTheCpuBits)
{
  ROCKDEM_REQUIRE_VULKAN_DEVICE();
  Model m = cementedSpecimen(2200, 0.033, 5);
  ASSERT_GE(m.particles.size(), 2000u);
  ASSERT_GT(m.bonds.size(), 2000u);
  startLoadTest(m, compression(25.0, 50));
  Model cpu, gpu;
  const std::string difference = cpuGpuDifference(m, { 1200, 900 }, &cpu, &gpu);
  EXPECT_EQ(difference, "") << "first difference";
  EXPECT_EQ(cpu.clock.step, 2100);
  EXPECT_GE(cpu.test.history.size(), 40u);
  EXPECT_GT(countBonds(cpu.bonds).broken, 0u) << "the test breaks bonds";
  EXPECT_EQ(countBonds(cpu.bonds).broken, countBonds(gpu.bonds).broken);
}

// The energy check (Simulation::checkStability) gives the same decision on both paths: a
// cemented specimen at 3 x the critical timestep (test-only switch), which breaks its bonds
// while every value stays finite, is stopped at the same check with the same message, and
// both keep the same last good state.
TEST(VulkanRuns, UnstableCementedCompressionIsStoppedAsOnTheCpu)
{
  ROCKDEM_REQUIRE_VULKAN_DEVICE();
  Model m = cementedSpecimen(150, 0.012, 2);
  ASSERT_GT(m.bonds.size(), 50u);
  startLoadTest(m, compression(1.0, 10));
  m.solver.allowUnsafeTimestep = true;
  m.solver.requestedTimestep = 3.0 * Simulation(m).criticalTimestep();
  std::string messages[2];
  Model ends[2] = { m, m };
  for (int k = 0; k < 2; ++k) {
    Simulation sim(ends[k], k == 0 ? SolverDevice::CPU : SolverDevice::GPU);
    try {
      sim.advance(2000);
    } catch (const InstabilityError& e) {
      messages[k] = e.what();
    }
  }
  EXPECT_NE(messages[0].find("x the energy available"), std::string::npos) << messages[0];
  EXPECT_NE(messages[0].find("Timestep Safety 3"), std::string::npos) << messages[0];
  EXPECT_EQ(messages[1], messages[0]);
  EXPECT_EQ(ends[1].clock.step, m.clock.step);
  EXPECT_EQ(ends[1].particles.position, ends[0].particles.position);
  EXPECT_EQ(ends[1].bonds.failure, ends[0].bonds.failure);
}

// The dissipation the energy check counts in a test's first steps (Cundall damping work
// per grain, the energy of each bond as it breaks: cundallDampingWork and bondStoredEnergy
// in C++ and GLSL) has the same bits on both paths: a shaken cemented specimen whose
// bonds break in its first 16 steps.
TEST(VulkanRuns, DissipationCountedInTheFirstStepsIsTheCpus)
{
  ROCKDEM_REQUIRE_VULKAN_DEVICE();
  Model m = cementedSpecimen(150, 0.012, 2);
  startLoadTest(m, compression(1.0, 10));
  dem::testing::shake(m, 3.0);
  double dissipated[2] = { 0.0, 0.0 };
  Model ends[2] = { m, m };
  for (int k = 0; k < 2; ++k) {
    Simulation sim(ends[k], k == 0 ? SolverDevice::CPU : SolverDevice::GPU);
    ASSERT_NO_THROW(sim.advance(16));
    dissipated[k] = sim.dissipatedEnergy();
  }
  EXPECT_GT(countBonds(ends[0].bonds).broken, 0u) << "bonds break";
  EXPECT_GT(dissipated[0], 0.0);
  EXPECT_EQ(dissipated[1], dissipated[0]);
  EXPECT_EQ(ends[1].particles.velocity, ends[0].particles.velocity);
}

TEST(VulkanRuns, CarvedSpecimensUnderBrazilianAndGrippedTensionGiveTheCpuBits)
{
  // Issue 13's modes on the device: the Brazilian platens are the Compression platens, the
  // grips the Tension attachments (Grip Length only chooses which grains), so both run the
  // same device code; this checks it, on specimens carved by DEM Specimen.
  ROCKDEM_REQUIRE_VULKAN_DEVICE();
  Model pack = dem::testing::specimen(900, 0.024, 0.0008, 0.0012, 3);
  SpecimenSettings shape;
  shape.shape = SpecimenShape::Disc;
  shape.diameter = 0.022;
  shape.length = 0.011;
  Model disc = pack;
  carveSpecimen(disc, shape);
  cement(disc, dem::testing::testCement());
  LoadTestSettings brazilian = compression(25.0, 50);
  brazilian.mode = TestMode::Brazilian;
  brazilian.axis = 1;
  startLoadTest(disc, brazilian);
  Model cpu, gpu;
  EXPECT_EQ(cpuGpuDifference(disc, { 500, 400 }, &cpu, &gpu), "") << "first difference (Brazilian)";
  EXPECT_GT(cpu.test.peakStress, 0.0);

  shape.shape = SpecimenShape::Cylinder;
  shape.diameter = 0.014;
  shape.length = 0.022;
  Model cylinder = pack;
  carveSpecimen(cylinder, shape);
  cement(cylinder, dem::testing::testCement());
  LoadTestSettings tension = compression(25.0, 50);
  tension.mode = TestMode::Tension;
  tension.gripLength = 2.0;
  startLoadTest(cylinder, tension);
  EXPECT_EQ(cpuGpuDifference(cylinder, { 500, 400 }, &cpu, &gpu), "") << "first difference (gripped tension)";
}

TEST(VulkanRuns, MomentContributionBelowOneUnderUnconfinedCompressionGivesTheCpuBits)
{
  // Issue 12's Moment Contribution factor beta (PHYSICS.md section 3), mirrored in
  // bond_laws.glsl: 0.5 on most bonds, 0.25 on every third, so a per-bond array is read.
  ROCKDEM_REQUIRE_VULKAN_DEVICE();
  Model m = cementedSpecimen(600, 0.021, 2);
  ASSERT_GT(m.bonds.size(), 500u);
  for (std::size_t k = 0; k < m.bonds.size(); ++k) {
    m.bonds.momentContribution[k] = k % 3 == 2 ? 0.25 : 0.5;
  }
  startLoadTest(m, compression(50.0, 50)); // fast enough that bonds break within the 1,200 steps
  Model full = m; // the same run with the full moments (beta = 1) breaks other bonds
  full.bonds.momentContribution.assign(full.bonds.size(), 1.0);
  Model cpu, gpu;
  const std::string difference = cpuGpuDifference(m, { 700, 500 }, &cpu, &gpu);
  EXPECT_EQ(difference, "") << "first difference";
  EXPECT_GT(countBonds(cpu.bonds).broken, 0u) << "the test breaks bonds";
  EXPECT_EQ(countBonds(cpu.bonds).broken, countBonds(gpu.bonds).broken);
  {
    Simulation reference(full, SolverDevice::CPU);
    reference.advance(1200);
  }
  EXPECT_NE(countBonds(full.bonds).broken, countBonds(cpu.bonds).broken) << "beta changes which bonds break";
}

TEST(VulkanRuns, SofteningBondsUnderUnconfinedCompressionGiveTheCpuBits)
{
  // Tension softening (Softening Ratio, Cement.md), mirrored in bond_laws.glsl and
  // bond_forces.comp: ratio 2 on most bonds, 0 (brittle) on every third.
  ROCKDEM_REQUIRE_VULKAN_DEVICE();
  Model m = cementedSpecimen(600, 0.021, 2);
  ASSERT_GT(m.bonds.size(), 500u);
  for (std::size_t k = 0; k < m.bonds.size(); ++k) {
    m.bonds.softening[k] = k % 3 == 2 ? 0.0 : 2.0;
  }
  startLoadTest(m, compression(25.0, 50));
  Model cpu, gpu;
  const std::string difference = cpuGpuDifference(m, { 700, 500 }, &cpu, &gpu);
  EXPECT_EQ(difference, "") << "first difference";
  EXPECT_GT(statetest::softeningBonds(cpu.bonds), 0u) << "bonds are softening at the end";
  EXPECT_GT(countBonds(cpu.bonds).broken, 0u) << "the test breaks bonds";
}

TEST(VulkanRuns, PlatenFrictionUnderUnconfinedCompressionGivesTheCpuBits)
{
  // Issue 12's Platen Friction (LoadTest.md): the walls on the test axis take it, in
  // geometry.glsl's contactModel as in CpuBackend::computeForces.
  ROCKDEM_REQUIRE_VULKAN_DEVICE();
  Model m = cementedSpecimen(600, 0.021, 2);
  LoadTestSettings s = compression(25.0, 50);
  s.platenFriction = 0.5;
  Model lubricated = m;
  startLoadTest(m, s);
  startLoadTest(lubricated, compression(25.0, 50));
  Model cpu, gpu;
  EXPECT_EQ(cpuGpuDifference(m, { 700, 500 }, &cpu, &gpu), "") << "first difference";
  {
    Simulation reference(lubricated, SolverDevice::CPU);
    reference.advance(1200);
  }
  EXPECT_NE(statetest::firstDifference(lubricated, cpu), "") << "the platens' friction changes the run";
}

TEST(VulkanRuns, TriaxialConsolidatingDampedAndShearingUndampedGivesTheCpuBits)
{
  // Consolidation Damping (LoadTest.md): the GPU takes the damping of the stage, as the CPU
  // does, across the switch from the consolidation (0.7) to the undamped shear.
  ROCKDEM_REQUIRE_VULKAN_DEVICE();
  Model m = cementedSpecimen(600, 0.021, 2);
  m.solver.settlingDamping = 0.0;
  LoadTestSettings s;
  s.mode = TestMode::Triaxial;
  s.confiningStress = 2e5;
  s.strainRate = 25.0;
  s.maxStrain = 0.2;
  s.sampleInterval = 50;
  s.consolidationDamping = 0.7;
  startLoadTest(m, s);
  std::int64_t consolidation = 0; // steps to the shear, on the CPU
  {
    Model probe = m;
    Simulation sim(probe, SolverDevice::CPU);
    while (probe.test.stage == TestStage::Consolidate && consolidation < 100000) {
      sim.advance(50);
      consolidation += 50;
    }
    ASSERT_EQ(probe.test.stage, TestStage::Shear);
  }
  Model cpu, gpu;
  EXPECT_EQ(cpuGpuDifference(m, { consolidation - 100, 600 }, &cpu, &gpu), "") << "first difference";
  EXPECT_EQ(cpu.test.stage, TestStage::Shear);
}

TEST(VulkanRuns, SettlingWithRollingFrictionGivesTheCpuBits)
{
  ROCKDEM_REQUIRE_VULKAN_DEVICE();
  // A grown pack, periodic in X, thrown about (random velocities up to 0.5 m/s) so that
  // neighbour lists are rebuilt often, settling under gravity with rolling resistance.
  Model m;
  m.domain.size = Vec3(0.03, 0.03, 0.06);
  m.domain.periodic[0] = true;
  m.material.youngsModulus = 1e8;
  m.material.friction = 0.5;
  m.material.rollingFriction = 0.1;
  m.gravity = Vec3(0.0, 0.0, -2000.0); // settles within the 2000 steps
  PackParameters params;
  params.initialElements = 2200;
  params.minimumSize = 0.0005;
  params.maximumSize = 0.001;
  params.randomSeed = 4;
  buildPack(m, params);
  growElements(m);
  ASSERT_GE(m.particles.size(), 2000u);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  for (Vec3& v : m.particles.velocity) {
    v = Vec3(u(rng), u(rng), u(rng));
  }
  Model cpu;
  const std::string difference = cpuGpuDifference(m, { 1000, 1000 }, &cpu);
  EXPECT_EQ(difference, "") << "first difference";
  EXPECT_GT(cpu.contacts.rollingSpring.size(), 100u) << "contacts carry rolling history";
}

TEST(VulkanRuns, PressTestToPastThePeakMatches)
{
  ROCKDEM_REQUIRE_VULKAN_DEVICE();
  // The press result on both paths: peak stress, Young's modulus (secant at 50 % of the
  // peak), strain at the peak and broken bonds, from the same bits.
  const Model start = [] {
    Model m = dem::testing::specimen(800, 0.02, 0.0008, 0.0012, 11);
    dem::testing::consolidate(m, 1e5);
    cement(m, dem::testing::testCement());
    startLoadTest(m, compression(2.0, 20));
    return m;
  }();
  auto run = [&](SolverDevice device) {
    Model m = start;
    Simulation sim(m, device);
    for (int k = 0; k < 30; ++k) {
      sim.advance(200);
      const double axial = m.test.history.back()[18];
      if (m.test.peakStress > 0.0 && axial < 0.7 * m.test.peakStress) {
        break; // past the peak
      }
    }
    return m;
  };
  const Model cpu = run(SolverDevice::CPU);
  const Model gpu = run(SolverDevice::GPU);
  auto summary = [](const Model& m) {
    // Strain at the peak, and the secant modulus where the stress first reaches half of it.
    const int axial = 18, strain = 4;
    double peakStrain = 0.0, half = 0.0, halfStrain = 0.0;
    for (const auto& row : m.test.history) {
      if (row[axial] == m.test.peakStress) {
        peakStrain = row[strain];
      }
      if (half == 0.0 && row[axial] >= 0.5 * m.test.peakStress) {
        half = row[axial];
        halfStrain = row[strain];
      }
    }
    return std::array<double, 4>{ { m.test.peakStress, half / halfStrain, peakStrain,
                                    static_cast<double>(countBonds(m.bonds).broken) } };
  };
  const auto a = summary(cpu);
  const auto b = summary(gpu);
  ASSERT_GT(a[0], 0.0);
  EXPECT_EQ(a[0], b[0]) << "peak stress (Pa)";
  EXPECT_EQ(a[1], b[1]) << "Young's modulus at 50 % of the peak (Pa)";
  EXPECT_EQ(a[2], b[2]) << "axial strain at the peak";
  EXPECT_EQ(a[3], b[3]) << "broken bonds";
  EXPECT_GT(a[3], 100.0);
  EXPECT_LT(cpu.test.history.back()[18], 0.7 * a[0]) << "the run went past the peak";
  EXPECT_EQ(statetest::firstDifference(cpu, gpu), "");
  std::printf("press test: peak %.6g Pa, E %.6g Pa, strain at peak %.6g, %g broken bonds, %zu rows\n",
              a[0], a[1], a[2], a[3], cpu.test.history.size());
}

TEST(VulkanRuns, AStateSavedFromAGpuRunResumesOnEitherPath)
{
  ROCKDEM_REQUIRE_VULKAN_DEVICE();
  // Triaxial test (servo on the device): A runs 2 x 600 steps on the CPU; B runs 600 on the
  // GPU, is written to a state file and read back, then runs 600 on the CPU; C the same
  // but continues on the GPU. All three end bitwise identical.
  Model m = dem::testing::specimen(400, 0.02, 0.001, 0.0015, 1);
  LoadTestSettings s;
  s.mode = TestMode::Triaxial;
  s.confiningStress = 1e5;
  s.strainRate = 0.5;
  s.sampleInterval = 50;
  startLoadTest(m, s);
  Model a = m;
  {
    Simulation sim(a, SolverDevice::CPU);
    sim.advance(600);
    sim.advance(600);
  }
  Model b = m;
  {
    Simulation sim(b, SolverDevice::GPU);
    ASSERT_EQ(sim.path().rfind("GPU Vulkan: ", 0), 0u) << sim.path();
    sim.advance(600);
  }
  const std::string file = ::testing::TempDir() + "/rockdem_gpu_resume.rdem";
  writeState(b, file);
  for (SolverDevice device : { SolverDevice::CPU, SolverDevice::GPU }) {
    Model c = readState(file);
    {
      Simulation sim(c, device);
      sim.advance(600);
    }
    EXPECT_EQ(statetest::firstDifference(a, c), "")
      << (device == SolverDevice::GPU ? "continued on the GPU" : "continued on the CPU");
  }
  std::remove(file.c_str());
  EXPECT_GT(a.test.history.size(), 20u);
}

TEST(VulkanRuns, ListsGrowOnTheDeviceWithoutLosingAStep)
{
  ROCKDEM_REQUIRE_VULKAN_DEVICE();
  // A loose pack falling onto the floor: the pair and wall lists grow. With lists that
  // start without headroom, the device halts before a list overflows, the host grows it
  // and the step resumes at its rebuild: the run still gives the CPU's bits.
  Model m;
  m.domain.size = Vec3(0.015, 0.015, 0.03);
  m.material.youngsModulus = 1e7;
  m.material.rollingFriction = 0.05;
  m.gravity = Vec3(0.0, 0.0, -2000.0);
  PackParameters params;
  params.initialElements = 500;
  params.minimumSize = 0.0006;
  params.maximumSize = 0.0009;
  params.randomSeed = 2;
  buildPack(m, params);
  resetWalls(m);
  Model cpuModel = m;
  Model gpuModel = m;
  const ContactModel cm = makeContactModel(m.material, m.solver.contactLaw);
  const double dt = m.solver.timestepSafety * criticalTimestep(m, m.solver.contactLaw);
  cpuModel.clock.timestep = gpuModel.clock.timestep = dt;
  CpuBackend cpu(cpuModel, cm, dt);
  VulkanBackend gpu(gpuModel, cm, dt, true);
  const std::size_t firstPairs = cpu.sync().pairI.size();
  const std::size_t firstWalls = cpu.sync().wallSlot.size();
  for (int k = 0; k < 12; ++k) {
    cpu.run(100);
    gpu.run(100);
  }
  gpu.sync();
  cpu.sync();
  EXPECT_GT(gpu.growths(), 1) << "the lists grew on the device";
  EXPECT_GT(gpu.rebuilds(), 5);
  EXPECT_GT(cpu.sync().pairI.size(), firstPairs);
  EXPECT_GT(cpu.sync().wallSlot.size(), firstWalls);
  // The driver's reductions read the host mirror: the downloaded lists are the CPU's.
  EXPECT_TRUE(statetest::sameBits(cpu.sync().pairI, gpu.sync().pairI));
  EXPECT_TRUE(statetest::sameBits(cpu.sync().pairSpring, gpu.sync().pairSpring));
  EXPECT_TRUE(statetest::sameBits(cpu.sync().wallSpring, gpu.sync().wallSpring));
  EXPECT_EQ(statetest::firstDifference(cpuModel, gpuModel), "");
}

namespace {

/// Sets an environment variable for the life of the object.
class ScopedEnvironment {
public:
  ScopedEnvironment(const char* name, const char* value) : name_(name) { setenv(name, value, 1); }
  ~ScopedEnvironment() { unsetenv(name_); }

private:
  const char* name_;
};

/// A GPU request under the given condition falls back to the CPU, says why in path(),
/// and steps exactly as the CPU does.
void expectFallback(const char* reasonPart)
{
  Model m = dem::testing::specimen(300, 0.016, 0.0008, 0.0012, 2);
  Model reference = m;
  {
    Simulation gpu(m, SolverDevice::GPU);
    const std::string path = gpu.path();
    std::printf("Solver Path: %s\n", path.c_str());
    EXPECT_EQ(path.rfind("CPU ", 0), 0u) << path;
    EXPECT_NE(path.find(": GPU requested, fell back because "), std::string::npos) << path;
    EXPECT_NE(gpu.gpuFallbackReason().find(reasonPart), std::string::npos) << gpu.gpuFallbackReason();
    gpu.advance(300);
  }
  {
    Simulation cpu(reference, SolverDevice::CPU);
    cpu.advance(300);
  }
  EXPECT_EQ(statetest::firstDifference(m, reference), "");
}

} // namespace

TEST(VulkanFallback, DisabledByTheEnvironment)
{
  ScopedEnvironment e("ROCKDEM_VULKAN_DISABLE", "1");
  expectFallback("disabled by ROCKDEM_VULKAN_DISABLE");
}

TEST(VulkanFallback, NoVulkanDriver)
{
  ScopedEnvironment e("VK_ICD_FILENAMES", "/nonexistent/rockdem_no_such_icd.json");
  ScopedEnvironment f("VK_DRIVER_FILES", "/nonexistent/rockdem_no_such_icd.json");
  expectFallback("no Vulkan");
}

TEST(VulkanFallback, DeviceWithoutDoublePrecision)
{
  ROCKDEM_REQUIRE_VULKAN_DEVICE();
  ScopedEnvironment e("ROCKDEM_VULKAN_SIMULATE_NO_FP64", "1");
  expectFallback("has no double precision in shaders (shaderFloat64)");
}

TEST(VulkanFallback, TooLittleDeviceMemory)
{
  ROCKDEM_REQUIRE_VULKAN_DEVICE();
  ScopedEnvironment e("ROCKDEM_VULKAN_SIMULATE_MEMORY", "10000");
  expectFallback("too little device memory");
}

TEST(VulkanFallback, FailedAllocation)
{
  ROCKDEM_REQUIRE_VULKAN_DEVICE();
  ScopedEnvironment e("ROCKDEM_VULKAN_FAIL_ALLOCATION", "17");
  expectFallback("failed (out of device memory)");
}
