// Bad input and faults (issue 18), in the engine: each case ends in a clear error naming
// the parameter, its value and the valid range, or in the documented behaviour
// (Documentation/Faults.md lists every case and the test that covers it).
#include "Specimens.h"
#include "StateFixtures.h"
#include "TempDir.h"

#include "dem/Bonds.h"
#include "dem/Errors.h"
#include "dem/Overlaps.h"
#include "dem/Pack.h"
#include "dem/Porosity.h"
#include "dem/Random.h"
#include "dem/Simulation.h"
#include "dem/StateFile.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

using namespace dem;
using dem::testing::TempDir;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// The message of the InputError that `action` raises ("" when it raises none).
std::string inputError(const std::function<void()>& action)
{
  try {
    action();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

std::string readText(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The pid of a process that has exited (and been reaped): no process has it now.
pid_t deadPid()
{
  const pid_t child = ::fork();
  if (child == 0) {
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  return child;
}

} // namespace

// Item 3: gravity along a periodic axis. A periodic column has no floor, so the energy
// check counts gravity's work since the start (m g . displacement, which does not wrap):
// a free-falling periodic pack runs, and a genuinely unstable one is still stopped.
TEST(Faults, GravityAlongAPeriodicAxisIsASourceOfEnergyNotAnInstability)
{
  Model m;
  m.domain.size = Vec3(0.02, 0.02, 0.02);
  m.domain.periodic = { { false, false, true } };
  m.material.youngsModulus = 1e8;
  PackParameters params;
  params.initialElements = 60;
  params.minimumSize = 0.001;
  params.maximumSize = 0.0015;
  buildPack(m, params);
  ASSERT_EQ(m.gravity.z(), -9.81);
  Simulation sim(m);
  // 3000 steps of free fall (~0.024 s): the column gains kinetic energy from gravity alone.
  ASSERT_NO_THROW(sim.advance(3000));
  EXPECT_GT(sim.diagnostics().kineticEnergy, 0.0);
  double fall = 0.0;
  for (const Vec3& u : m.particles.displacement) {
    fall += u.z();
  }
  EXPECT_LT(fall / static_cast<double>(m.particles.size()), -1e-5) << "the column falls";

  // The same periodic column with a timestep 5 x critical still goes unstable.
  Model bad = m;
  bad.solver.allowUnsafeTimestep = true;
  bad.solver.settlingDamping = 0.0;
  bad.solver.requestedTimestep = 5.0 * criticalTimestep(bad, bad.solver.contactLaw);
  growElements(bad); // touching neighbours, moving against one another: contacts
  Random shake(7);
  for (Vec3& v : bad.particles.velocity) {
    v += 0.2 * Vec3(shake.uniform() - 0.5, shake.uniform() - 0.5, shake.uniform() - 0.5);
  }
  Simulation unstable(bad);
  EXPECT_THROW(
    {
      for (int k = 0; k < 100; ++k) {
        unstable.advance(100);
      }
    },
    InstabilityError);
}

// Item 4: grains beyond the walls a new stage stands up (escaped during an unconfined
// test) are removed, with their bonds and contacts, when it starts; the count is returned.
TEST(Faults, EscapedGrainsAreRemovedWithACountWhenTheNextStageStarts)
{
  Model m = dem::testing::specimen(200, 0.012, 0.0008, 0.0012, 3);
  cement(m, dem::testing::testCement());
  ASSERT_GT(m.bonds.size(), 0u);
  {
    m.gravity = Vec3(0.0, 0.0, -9.81);
    Simulation settle(m); // contacts with history
    settle.advance(500);
  }
  ASSERT_GT(m.contacts.size(), 0u);
  // Fling two grains out through the side faces, as a failing specimen does (an unconfined
  // test has no side walls, so nothing stops them), and one out through the top.
  const std::int64_t flungX = m.particles.id[5];
  m.particles.position[5].x() = m.domain.upper().x() + 0.01;
  m.particles.position[6].y() = m.domain.origin.y() - 0.003;
  m.particles.position[7].z() = m.domain.upper().z() + 0.002;
  const std::size_t n = m.particles.size();
  std::size_t bondsOfThem = 0;
  for (std::size_t k = 0; k < m.bonds.size(); ++k) {
    for (int i : { 5, 6, 7 }) {
      if (m.bonds.idA[k] == m.particles.id[i] || m.bonds.idB[k] == m.particles.id[i]) {
        ++bondsOfThem;
        break;
      }
    }
  }
  std::size_t contactsOfThem = 0;
  for (std::size_t k = 0; k < m.contacts.size(); ++k) {
    for (int i : { 5, 6, 7 }) {
      if (m.contacts.idA[k] == m.particles.id[i] || m.contacts.idB[k] == m.particles.id[i]) {
        ++contactsOfThem;
        break;
      }
    }
  }
  ASSERT_GT(bondsOfThem, 0u);
  const std::size_t bonds = m.bonds.size();
  const std::size_t contacts = m.contacts.size();
  LoadTestSettings off; // Mode Off: the six walls come back on the box faces
  const RemovedParticles removed = startLoadTest(m, off);
  EXPECT_EQ(removed.particles, 3u);
  EXPECT_EQ(removed.bonds, bondsOfThem);
  EXPECT_EQ(removed.contacts, contactsOfThem);
  EXPECT_EQ(m.contacts.size(), contacts - contactsOfThem);
  EXPECT_EQ(m.particles.size(), n - 3);
  EXPECT_EQ(m.bonds.size(), bonds - bondsOfThem);
  for (std::int64_t id : m.particles.id) {
    ASSERT_NE(id, flungX);
  }
  for (std::size_t k = 0; k < m.contacts.size(); ++k) {
    ASSERT_NE(m.contacts.idA[k], flungX);
    ASSERT_NE(m.contacts.idB[k], flungX);
  }
  const std::string line = removed.summary("outside the box");
  EXPECT_TRUE(contains(line, "Removed 3 particle(s) outside the box")) << line;
  // The model runs, and is a valid state file.
  m.gravity.setZero();
  Simulation sim(m);
  EXPECT_NO_THROW(sim.advance(500));
  EXPECT_EQ(sim.diagnostics().escaped, 0u);
  EXPECT_NO_THROW(readStateFromMemory(writeStateToMemory(m).data(), writeStateToMemory(m).size()));
  // Nothing outside: nothing removed.
  EXPECT_EQ(startLoadTest(m, off).particles, 0u);
}

// Item 5: two particles at exactly the same point (no contact direction) are an input
// error naming both, also across a periodic seam and in a 2D section.
TEST(Faults, CoincidentCentresAreRejectedNamingBothParticles)
{
  Model m = dem::testing::specimen(80, 0.02, 0.001, 0.002, 3);
  m.particles.position[7] = m.particles.position[3];
  std::string error = inputError([&] { Simulation sim(m); });
  EXPECT_TRUE(contains(error, "Particles " + std::to_string(m.particles.id[3]) + " and " +
                                std::to_string(m.particles.id[7]) + " have the same centre"))
    << error;
  // x = 0 and x = L are one point on a periodic axis.
  Model p;
  p.domain.size = Vec3(0.1, 0.1, 0.1);
  p.domain.periodic[0] = true;
  p.particles.append(Vec3(0.0, 0.05, 0.05), 0.01, 0);
  p.particles.append(Vec3(0.1, 0.05, 0.05), 0.01, 1);
  updateMassProperties(p);
  error = inputError([&] { requireDistinctCentres(p.domain, p.particles); });
  EXPECT_TRUE(contains(error, "Particles 0 and 1 have the same centre")) << error;
  // A hair apart is not coincident (it is an overlap: item 7).
  p.particles.position[1].x() = 0.0999999;
  EXPECT_EQ(inputError([&] { requireDistinctCentres(p.domain, p.particles); }), "");
}

// Item 7: overlaps are measured (pairs, largest, shared volume) and Current Porosity is
// never negative. Shared volume checked against the closed forms for equal radii
// (MathWorld, "Sphere-Sphere Intersection": V = pi (4r + d)(2r - d)^2 / 12; "Circle-Circle
// Intersection": A = 2 r^2 acos(d / 2r) - (d / 2) sqrt(4 r^2 - d^2)).
TEST(Faults, OverlapsAreMeasuredAndPorosityIsNeverNegative)
{
  Domain box;
  for (double d : { 0.001, 0.005, 0.01, 0.019 }) {
    const double r = 0.01;
    EXPECT_NEAR(sharedVolume(box, r, r, d), kPi * (4 * r + d) * (2 * r - d) * (2 * r - d) / 12.0, 1e-18) << d;
  }
  Domain section;
  section.section2D = true;
  section.size.z() = 0.003;
  for (double d : { 0.001, 0.01, 0.019 }) {
    const double r = 0.01;
    const double area = 2 * r * r * std::acos(d / (2 * r)) - 0.5 * d * std::sqrt(4 * r * r - d * d);
    EXPECT_NEAR(sharedVolume(section, r, r, d), area * 0.003, 1e-15 * 0.003) << d;
  }
  EXPECT_EQ(sharedVolume(box, 0.01, 0.02, 0.031), 0.0);
  EXPECT_NEAR(sharedVolume(box, 0.01, 0.03, 0.005), 4.0 / 3.0 * kPi * 1e-6, 1e-20) << "contained";

  // Heavily overlapping spheres in a small box: the sum of their volumes exceeds the box.
  Model m;
  m.domain.size = Vec3(0.022, 0.022, 0.022);
  m.gravity.setZero();
  int id = 0;
  for (double x : { 0.005, 0.011, 0.017 }) {
    for (double y : { 0.005, 0.011, 0.017 }) {
      for (double z : { 0.005, 0.011, 0.017 }) {
        m.particles.append(Vec3(x, y, z), 0.005, id++);
      }
    }
  }
  updateMassProperties(m);
  const OverlapReport o = measureOverlaps(m);
  // Every pair closer than 10 mm: 54 along the axes (6 mm apart), 72 across the faces of the
  // cells (8.5 mm); across the cells (10.4 mm) they do not touch.
  EXPECT_EQ(o.pairs, 54u + 72u);
  EXPECT_NEAR(o.largest, 0.004, 1e-15);
  EXPECT_NEAR(o.largestRelative, 0.8, 1e-12);
  EXPECT_LT(PorosityMeter(m).porosity(), -0.3) << "summed volumes exceed the box";
  EXPECT_GE(currentPorosity(m), 0.0);
  EXPECT_LE(currentPorosity(m), 1.0);
  // Two spheres sharing a lens: porosity counts the lens once.
  Model two;
  two.domain.size = Vec3(0.1, 0.1, 0.1);
  two.gravity.setZero();
  two.particles.append(Vec3(0.04, 0.05, 0.05), 0.01, 0);
  two.particles.append(Vec3(0.055, 0.05, 0.05), 0.01, 1);
  updateMassProperties(two);
  const double lens = kPi * (0.04 + 0.015) * 0.005 * 0.005 / 12.0;
  EXPECT_NEAR(currentPorosity(two), 1.0 - (2 * 4.0 / 3.0 * kPi * 1e-6 - lens) / 1e-3, 1e-14);
  // A pack from DEM Pack Source has no overlap: exactly the porosity it always had.
  Model pack = dem::testing::specimen(300, 0.03, 0.001, 0.002, 5);
  EXPECT_EQ(measureOverlaps(pack).pairs, 0u);
}

// Item 10: Mode Tension on a model without intact bonds pulls on nothing.
TEST(Faults, TensionOnAnUncementedModelIsRefused)
{
  Model m = dem::testing::specimen(200, 0.012, 0.0008, 0.0012, 3);
  LoadTestSettings tension;
  tension.mode = TestMode::Tension;
  const std::string error = inputError([&] { startLoadTest(m, tension); });
  EXPECT_TRUE(contains(error, "Mode = Tension needs a cemented model")) << error;
  EXPECT_TRUE(contains(error, "no bonds")) << error;
  cement(m, dem::testing::testCement());
  ASSERT_GT(m.bonds.size(), 0u);
  EXPECT_EQ(inputError([&] { startLoadTest(m, tension); }), "");
}

// Item 11: the threads that run, and why; a thread count the machine cannot sensibly run is
// refused (thousands of threads can abort the process).
TEST(Faults, ThreadsSayWhatRunsAndAbsurdCountsAreRefused)
{
  Model m = dem::testing::specimen(300, 0.03, 0.001, 0.002, 2);
  m.solver.threads = 8;
  Simulation sim(m);
  // The switch weighs the work per step (particles + 5 neighbour pairs + 6 bonds).
  const std::string serial = "CPU serial (work ";
  EXPECT_TRUE(contains(sim.path(), serial)) << sim.path();
  EXPECT_TRUE(contains(sim.path(), ", below the parallel threshold of 8000; threads are used from there on)"))
    << sim.path();
  m.solver.threads = 1;
  const std::string one = Simulation(m).path();
  EXPECT_TRUE(contains(one, serial) && contains(one, ", below the parallel threshold of 8000)")) << one;
  m.solver.parallelThreshold = 0;
  EXPECT_EQ(Simulation(m).path(), "CPU serial (Threads = 1)");
  m.solver.threads = 2;
  EXPECT_TRUE(contains(Simulation(m).path(), "CPU OpenMP (2 threads)"));
  m.solver.threads = 100000;
  const std::string error = inputError([&] { Simulation s(m); });
  EXPECT_TRUE(contains(error, "Threads = 100000 is out of range on this machine: valid range is 0")) << error;
}

// Item 14: a Strain Rate whose platen would outrun the timestep is refused by name, with
// the largest rate this model can follow; that rate itself is accepted.
TEST(Faults, StrainRateTooFastForTheTimestepIsRefusedByName)
{
  Model m = dem::testing::specimen(200, 0.012, 0.0008, 0.0012, 3);
  LoadTestSettings s;
  s.mode = TestMode::Compression;
  s.strainRate = 1e9;
  Model fast = m;
  startLoadTest(fast, s);
  const std::string error = inputError([&] { Simulation sim(fast); });
  EXPECT_TRUE(contains(error, "Strain Rate = 1e+09 1/s is too fast for this model")) << error;
  const std::size_t at = error.find("Valid range is (0, ");
  ASSERT_NE(at, std::string::npos) << error;
  const double largest = std::stod(error.substr(at + 19));
  EXPECT_GT(largest, 1.0) << "ordinary rates pass";
  Model ok = m;
  s.strainRate = 0.999 * largest;
  startLoadTest(ok, s);
  Simulation sim(ok);
  EXPECT_NO_THROW(sim.advance(200)) << "at the largest rate the run is stable";
  // The bound keeps a margin (Press.md, "How fast the platen may move"): past it (allowed
  // here by the test-only flag), on the cemented specimen of the press tests, the platen
  // still holds at 3 x, and at 10 x (10 % of the smallest radius per step) grains pass
  // through it.
  Model cemented = dem::testing::specimen(400, 0.016, 0.0008, 0.0012, 3);
  dem::testing::consolidate(cemented, 2e4);
  cement(cemented, dem::testing::testCement());
  auto runAt = [&](double factor) {
    Model k = cemented;
    LoadTestSettings fastS = s;
    fastS.strainRate = 1.0;
    fastS.maxStrain = 0.5;
    startLoadTest(k, fastS);
    k.solver.allowUnsafeTimestep = true;
    const double dt = Simulation(k).timestep();
    const double rmin = *std::min_element(k.particles.radius.begin(), k.particles.radius.end());
    k.test.settings.strainRate = factor * MaxPlatenTravelPerStep * rmin / (k.test.initialLength[2] * dt);
    fastS.strainRate = k.test.settings.strainRate;
    Simulation run(k);
    try {
      run.advance(std::llround(0.3 / (fastS.strainRate * run.timestep()))); // to 30 % strain
    } catch (const InstabilityError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(runAt(3.0), "");
  EXPECT_TRUE(contains(runAt(10.0), "escaped the box"));
}

// Item 16: one flipped bit in the version field is damage (the checksum is checked before
// the version is read); a resealed newer version is still "from a newer RockDEM".
TEST(Faults, AFlippedBitInTheVersionIsReportedAsDamage)
{
  const std::vector<unsigned char> image = writeStateToMemory(dem::testing::specimen(40, 0.01, 0.001, 0.0015, 4));
  std::vector<unsigned char> flipped = image;
  flipped[16] ^= 0x10; // version 1 -> 17
  std::string error;
  try {
    readStateFromMemory(flipped.data(), flipped.size(), {}, "flipped.rdem");
  } catch (const FileError& e) {
    error = e.what();
  }
  EXPECT_TRUE(contains(error, "is corrupt: its checksum")) << error;
  EXPECT_FALSE(contains(error, "newer")) << error;
  resealStateImage(flipped);
  try {
    readStateFromMemory(flipped.data(), flipped.size(), {}, "newer.rdem");
  } catch (const FileError& e) {
    error = e.what();
  }
  EXPECT_TRUE(contains(error, "format version 17")) << error;
  EXPECT_TRUE(contains(error, "from a newer RockDEM")) << error;
}

// Other findings: temporaries "<file>.tmp-<pid>-<n>" of a writer that was killed are removed
// by the next write of that file; those of a live process (a write in progress) are not.
TEST(Faults, StaleTemporariesOfAKilledWriterAreRemovedByTheNextWrite)
{
  TempDir dir;
  const std::string path = dir.file("run.rdem");
  const pid_t dead = deadPid();
  const std::string live = "run.rdem.tmp-" + std::to_string(::getppid()) + "-1"; // a live process
  for (const std::string& name : { "run.rdem.tmp-" + std::to_string(dead) + "-0",
                                   "run.rdem.tmp-" + std::to_string(dead) + "-17",
                                   "run.history.csv.tmp-" + std::to_string(dead) + "-3", live,
                                   std::string("other.rdem.tmp-") + std::to_string(dead) + "-0" }) {
    std::ofstream(dir.file(name)) << "half a file";
  }
  Model m = dem::testing::specimen(40, 0.01, 0.001, 0.0015, 4);
  m.test.history.push_back({});
  writeStateAndHistory(m, path);
  EXPECT_EQ(dir.files(), (std::vector<std::string>{ "other.rdem.tmp-" + std::to_string(dead) + "-0",
                                                    "run.history.csv", "run.rdem", live }))
    << "the killed writer's temporaries of run.rdem and its CSV are gone; another file's and a "
       "live process's are kept";
}

// Other findings: a crash between the state file's rename and the CSV's leaves the CSV one
// write behind. The state file is the truth: syncHistoryCSV rewrites the CSV from it (what
// DEM State Reader does on open), and a state without history removes a CSV beside it.
TEST(Faults, AHistoryCSVOutOfStepWithItsStateFileIsRewrittenFromIt)
{
  TempDir dir;
  const std::string path = dir.file("run.rdem");
  Model m = dem::testing::specimen(40, 0.01, 0.001, 0.0015, 4);
  for (int k = 0; k < 9; ++k) {
    m.test.history.push_back({ static_cast<double>(k) });
  }
  writeStateAndHistory(m, path);
  m.test.history.push_back({ 9.0 });
  writeState(m, path); // the state renamed, then the kill: the CSV still has 9 rows
  const HistorySyncReport sync = syncHistoryCSV(readState(path).test, path);
  EXPECT_EQ(sync.action, HistorySync::Rewritten);
  EXPECT_EQ(sync.fileRows, 9u);
  EXPECT_EQ(sync.stateRows, 10u);
  EXPECT_EQ(readText(historyPathFor(path)), historyCSVText(m.test));
  EXPECT_EQ(syncHistoryCSV(m.test, path).action, HistorySync::InStep);
  // A state without history: its pair has no CSV.
  m.test.history.clear();
  writeStateAndHistory(m, path);
  EXPECT_EQ(dir.files(), std::vector<std::string>{ "run.rdem" });
  std::ofstream(historyPathFor(path)) << "\"Time (s)\"\n1\n";
  EXPECT_EQ(syncHistoryCSV(m.test, path).action, HistorySync::Removed);
  EXPECT_EQ(dir.files(), std::vector<std::string>{ "run.rdem" });
}

// Other findings, as the issue found them: a process saving a model and its history again
// and again is killed with SIGKILL at an arbitrary moment. The state file is always whole;
// after syncHistoryCSV the pair agrees; the next write leaves no temporary behind.
TEST(Faults, KillDuringSavesLeavesAWholeStateFileAndARepairablePair)
{
  TempDir dir;
  const std::string path = dir.file("run.rdem");
  for (int round = 0; round < 3; ++round) {
    const std::string out = dir.file("writer.out");
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const std::string particles = "3000";
    char* argv[] = { const_cast<char*>(ROCKDEM_FAULT_WRITER), const_cast<char*>(path.c_str()),
                     const_cast<char*>(particles.c_str()), nullptr };
    pid_t child = 0;
    ASSERT_EQ(posix_spawn(&child, ROCKDEM_FAULT_WRITER, &actions, nullptr, argv, environ), 0);
    posix_spawn_file_actions_destroy(&actions);
    // Let it save a few times, then kill it at a moment that differs each round.
    const auto start = std::chrono::steady_clock::now();
    auto saves = [&] {
      const std::string text = readText(out);
      return std::count(text.begin(), text.end(), '\n');
    };
    while (saves() < 3 + round && std::chrono::steady_clock::now() - start < std::chrono::seconds(60)) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(7 * round));
    ::kill(child, SIGKILL);
    int status = 0;
    ::waitpid(child, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status));
    const Model saved = readState(path); // whole: never half-written
    ASSERT_GE(saved.test.history.size(), 1u);
    syncHistoryCSV(saved.test, path);
    EXPECT_EQ(readText(historyPathFor(path)), historyCSVText(saved.test)) << "round " << round;
    writeStateAndHistory(saved, path);
    std::remove(out.c_str());
    EXPECT_EQ(dir.files(), (std::vector<std::string>{ "run.history.csv", "run.rdem" })) << "round " << round;
  }
}
