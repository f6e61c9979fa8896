// The state file (reference guide "Saving and reopening"; Documentation/StateFile.md):
// every field survives a write and read bit for bit; a reloaded run steps exactly like
// the uninterrupted one (settling pack, cemented specimen mid-test with broken bonds,
// triaxial mid-shear); truncated, damaged, unknown-version and inconsistent files are
// rejected with a message naming the file and the problem; writes are atomic.
#include "StateFixtures.h"
#include "TempDir.h"

#include "dem/Errors.h"
#include "dem/StateFile.h"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <array>
#include <cstdio>
#include <dirent.h>
#include <fstream>
#include <functional>
#include <sstream>
#include <unistd.h>

using namespace dem;
using dem::statetest::firstDifference;
using dem::statetest::sameBits;
using dem::testing::TempDir;

namespace {

std::vector<unsigned char> readBytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::vector<unsigned char>(std::istreambuf_iterator<char>(in), {});
}

void writeBytes(const std::string& path, const std::vector<unsigned char>& bytes, std::size_t count)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(count));
}

/// The message of the FileError that reading `path` raises ("" when it reads).
std::string readError(const std::string& path)
{
  try {
    readState(path);
  } catch (const FileError& e) {
    return e.what();
  }
  return "";
}

std::string memoryError(const std::vector<unsigned char>& image)
{
  try {
    readStateFromMemory(image.data(), image.size(), {}, "edited.rdem");
  } catch (const FileError& e) {
    return e.what();
  }
  return "";
}

/// A small model with a value in every field that differs from the default, run far
/// enough to have contacts, bonds (some broken) and test history.
Model everyFieldModel()
{
  Model m = dem::testing::specimen(150, 0.012, 0.0008, 0.0012, 5);
  m.domain.origin = Vec3(0.001, -0.002, 0.003);
  m.domain.periodic = { { false, true, false } };
  m.domain.cylinderAxis = 1; // not the test's axis: a cylinder compressed across its axis
  m.material.poissonsRatio = 0.21;
  m.material.restitution = 0.37;
  m.material.friction = 0.61;
  m.material.rollingFriction = 0.07;
  m.gravity = Vec3(0.1, -0.2, -9.7);
  m.solver.contactLaw = ContactLaw::Linear;
  m.solver.timestepSafety = 0.15;
  m.solver.settlingDamping = 0.3;
  m.solver.skin = 0.25;
  m.solver.threads = 3;
  m.solver.parallelThreshold = 12345;
  m.solver.allowUnsafeTimestep = true;
  updateMassProperties(m);
  CementParameters c;
  c.bondModulus = 2e7;
  c.tensileStrength = 1e4;
  c.cohesion = 2e4;
  c.strengthScatter = 0.3;
  c.gapTolerance = 0.2;
  cement(m, c);
  LoadTestSettings s;
  s.mode = TestMode::Compression;
  s.axis = 2;
  s.strainRate = 2.0;
  s.maxStrain = 0.04;
  s.servoAlpha = 0.4;
  s.consolidationDamping = 0.45;
  s.sampleInterval = 50;
  s.settleTolerance = 0.02;
  startLoadTest(m, s);
  {
    Simulation sim(m);
    sim.advance(1500);
  }
  // Values that only a bit-exact format keeps.
  m.particles.displacement[0].x() = -0.0;
  m.particles.force[1].y() = 4.9406564584124654e-324; // the smallest denormal
  m.particles.velocity[2].z() = 0.1 + 0.2;
  m.particles.flags[3] |= FlagFixed | FlagFineZone;
  m.nextId += 17;
  m.random.next();
  m.test.settings.platenFriction = 0.3; // a setting (not run with: the fixture's physics stays)
  m.bonds.softening[1] = 2.5;            // bond state fields (not run with)
  m.bonds.damage[1] = 0.1 + 0.2;
  return m;
}

void expectAllFieldsEqual(const Model& a, const Model& b)
{
  EXPECT_EQ(firstDifference(a, b), "");
  EXPECT_TRUE(sameBits(a.bonds.radius, b.bonds.radius));
  EXPECT_TRUE(sameBits(a.bonds.normalStiffness, b.bonds.normalStiffness));
  EXPECT_TRUE(sameBits(a.bonds.shearStiffness, b.bonds.shearStiffness));
  EXPECT_TRUE(sameBits(a.bonds.tensileStrength, b.bonds.tensileStrength));
  EXPECT_TRUE(sameBits(a.bonds.cohesion, b.bonds.cohesion));
  EXPECT_TRUE(sameBits(a.bonds.frictionAngle, b.bonds.frictionAngle));
  EXPECT_TRUE(sameBits(a.bonds.momentContribution, b.bonds.momentContribution));
  EXPECT_TRUE(sameBits(a.bonds.softening, b.bonds.softening));
  EXPECT_EQ(std::memcmp(a.domain.origin.data(), b.domain.origin.data(), 24), 0);
  EXPECT_EQ(std::memcmp(a.domain.size.data(), b.domain.size.data(), 24), 0);
  EXPECT_EQ(a.domain.periodic, b.domain.periodic);
  EXPECT_EQ(a.domain.section2D, b.domain.section2D);
  EXPECT_EQ(a.domain.cylinderAxis, b.domain.cylinderAxis);
  EXPECT_EQ(std::memcmp(&a.material, &b.material, sizeof(Material)), 0);
  EXPECT_EQ(std::memcmp(a.gravity.data(), b.gravity.data(), 24), 0);
  EXPECT_EQ(a.solver.contactLaw, b.solver.contactLaw);
  EXPECT_EQ(a.solver.timestepSafety, b.solver.timestepSafety);
  EXPECT_EQ(a.solver.requestedTimestep, b.solver.requestedTimestep);
  EXPECT_EQ(a.solver.settlingDamping, b.solver.settlingDamping);
  EXPECT_EQ(a.solver.skin, b.solver.skin);
  EXPECT_EQ(a.solver.threads, b.solver.threads);
  EXPECT_EQ(a.solver.parallelThreshold, b.solver.parallelThreshold);
  EXPECT_EQ(a.solver.allowUnsafeTimestep, b.solver.allowUnsafeTimestep);
  const LoadTestSettings& s = a.test.settings;
  const LoadTestSettings& t = b.test.settings;
  EXPECT_EQ(s.mode, t.mode);
  EXPECT_EQ(s.axis, t.axis);
  EXPECT_EQ(s.confiningStress, t.confiningStress);
  EXPECT_EQ(s.strainRate, t.strainRate);
  EXPECT_EQ(s.maxStrain, t.maxStrain);
  EXPECT_EQ(s.servoAlpha, t.servoAlpha);
  EXPECT_EQ(s.sampleInterval, t.sampleInterval);
  EXPECT_EQ(s.settleTolerance, t.settleTolerance);
  EXPECT_EQ(s.gripLength, t.gripLength);
  EXPECT_EQ(s.platenFriction, t.platenFriction);
  EXPECT_EQ(s.consolidationDamping, t.consolidationDamping);
  EXPECT_EQ(a.test.initialLength, b.test.initialLength);
  EXPECT_EQ(a.test.initialVolume, b.test.initialVolume);
  EXPECT_EQ(a.test.initialSpread, b.test.initialSpread);
  for (std::size_t w = 0; w < a.walls.size(); ++w) {
    EXPECT_EQ(a.walls[w].axis, b.walls[w].axis);
    EXPECT_EQ(a.walls[w].side, b.walls[w].side);
  }
}

/// Edits the HDF5 part of a state image with `edit` (given the open file), then reseals
/// it (new checksum), so the error must come from the checks behind the checksum.
std::vector<unsigned char> editImage(const std::vector<unsigned char>& image, const std::function<void(hid_t)>& edit)
{
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_fapl_core(fapl, 1 << 20, 0);
  H5Pset_file_image(fapl, const_cast<unsigned char*>(image.data()) + 512, image.size() - 512);
  static int counter = 0;
  const std::string name = "edit-" + std::to_string(counter++) + ".h5";
  hid_t file = H5Fopen(name.c_str(), H5F_ACC_RDWR, fapl);
  EXPECT_GE(file, 0);
  edit(file);
  H5Fflush(file, H5F_SCOPE_GLOBAL);
  const ssize_t size = H5Fget_file_image(file, nullptr, 0);
  std::vector<unsigned char> out(512 + static_cast<std::size_t>(size));
  std::copy(image.begin(), image.begin() + 512, out.begin()); // the RockDEM header
  H5Fget_file_image(file, out.data() + 512, static_cast<std::size_t>(size));
  H5Fclose(file);
  H5Pclose(fapl);
  resealStateImage(out);
  return out;
}

template <class T>
void replaceDataset(hid_t file, const char* path, hid_t fileType, hid_t memType, const std::vector<hsize_t>& dims,
                    const std::vector<T>& values)
{
  ASSERT_GE(H5Ldelete(file, path, H5P_DEFAULT), 0) << path;
  hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  hid_t d = H5Dcreate2(file, path, fileType, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(d, 0);
  if (!values.empty()) {
    H5Dwrite(d, memType, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  }
  H5Dclose(d);
  H5Sclose(space);
}

/// A: one simulation for 2N steps. B: N steps, written to a file, read back (a new
/// model, a new simulation), N more. The two are bitwise identical.
void expectExactResume(Model start, std::int64_t n, const TempDir& dir, const std::string& name)
{
  Model a = start;
  {
    Simulation sa(a);
    sa.advance(2 * n);
  }
  Model b = start;
  {
    Simulation sb(b);
    sb.advance(n);
  }
  const std::string path = dir.file(name + ".rdem");
  writeState(b, path);
  Model resumed = readState(path);
  EXPECT_EQ(firstDifference(b, resumed), "") << "the file holds exactly the saved model";
  {
    Simulation sr(resumed);
    sr.advance(n);
  }
  EXPECT_EQ(a.clock.step, resumed.clock.step);
  EXPECT_EQ(firstDifference(a, resumed), "") << name << ": the resumed run differs from the uninterrupted one";
  EXPECT_GT(a.contacts.size(), 0u);
}

} // namespace

// A field added to a struct of the model without a line in the state file would be
// silently lost: these sizes are recorded, and changing a struct fails here on purpose.
// (A small field that fits into existing padding escapes this check; the round-trip test
// below compares every field by name. Sizes are those of x86-64 Linux.)
TEST(StateFile, ModelStructsHaveTheRecordedLayout)
{
  const char* fix = " changed: a field was added or removed. Update the state file schema "
                    "(Solver/src/StateSchema.h, one line per field), Documentation/StateFile.md, "
                    "then the number recorded here.";
  EXPECT_EQ(sizeof(Domain), 56u) << "Domain" << fix;
  EXPECT_EQ(sizeof(Material), 48u) << "Material" << fix;
  EXPECT_EQ(sizeof(Particles), 11 * sizeof(std::vector<double>)) << "Particles" << fix;
  EXPECT_EQ(sizeof(Clock), 24u) << "Clock" << fix;
  EXPECT_EQ(sizeof(SolverSettings), 64u) << "SolverSettings" << fix;
  EXPECT_EQ(sizeof(Wall), 80u) << "Wall" << fix;
  EXPECT_EQ(sizeof(ContactHistory), 4 * sizeof(std::vector<double>)) << "ContactHistory" << fix;
  EXPECT_EQ(sizeof(Bonds), 19 * sizeof(std::vector<double>)) << "Bonds" << fix;
  EXPECT_EQ(sizeof(LoadTestSettings), 80u) << "LoadTestSettings" << fix;
  EXPECT_EQ(sizeof(LoadTestState), sizeof(LoadTestSettings) + 96 + sizeof(std::vector<double>)) << "LoadTestState" << fix;
  EXPECT_EQ(sizeof(Random), 32u) << "Random" << fix;
  EXPECT_EQ(sizeof(Model), 1296u) << "Model" << fix;
}

TEST(StateFile, EveryFieldSurvivesBitForBit)
{
  TempDir dir;
  const Model m = everyFieldModel();
  ASSERT_GT(m.bonds.size(), 0u);
  ASSERT_GT(countBonds(m.bonds).broken, 0u) << "the fixture has broken bonds";
  ASSERT_FALSE(m.contacts.rollingSpring.empty());
  ASSERT_FALSE(m.test.history.empty());
  const std::string path = dir.file("every.rdem");
  writeState(m, path);
  const Model back = readState(path);
  expectAllFieldsEqual(m, back);
  EXPECT_TRUE(std::signbit(back.particles.displacement[0].x())) << "-0 stays -0";
  // Writing the read model gives the same bytes: nothing is lost or added.
  EXPECT_EQ(writeStateToMemory(back), readBytes(path));
  EXPECT_EQ(dir.files(), std::vector<std::string>{ "every.rdem" }) << "no temporary file is left";
}

TEST(StateFile, EmptyModelRoundTrips)
{
  const Model m;
  const std::vector<unsigned char> image = writeStateToMemory(m);
  const Model back = readStateFromMemory(image.data(), image.size());
  EXPECT_EQ(back.particles.size(), 0u);
  EXPECT_TRUE(back.walls.empty());
  EXPECT_EQ(firstDifference(m, back), "");
}

TEST(StateFile, TheFileIsPlainHDF5AfterTheHeader)
{
  const Model m = dem::testing::specimen(50, 0.01, 0.001, 0.0015, 2);
  const std::vector<unsigned char> image = writeStateToMemory(m);
  EXPECT_EQ(std::memcmp(image.data(), "RockDEM state", 14), 0);
  EXPECT_EQ(std::memcmp(image.data() + 512, "\x89HDF\r\n\x1a\n", 8), 0) << "HDF5 superblock after the user block";
  TempDir dir;
  writeBytes(dir.file("s.rdem"), image, image.size());
  EXPECT_GT(H5Fis_hdf5(dir.file("s.rdem").c_str()), 0) << "any HDF5 tool opens it";
}

TEST(StateFile, SettlingPackResumesExactly)
{
  TempDir dir;
  expectExactResume(statetest::settlingPack(), 1000, dir, "settling");
}

TEST(StateFile, CementedSpecimenMidTestWithBrokenBondsResumesExactly)
{
  TempDir dir;
  const Model start = statetest::cementedMidCompression();
  ASSERT_GE(countBonds(start.bonds).broken, 10u);
  expectExactResume(start, 1000, dir, "cemented");
}

TEST(StateFile, TriaxialMidShearResumesExactly)
{
  TempDir dir;
  const Model start = statetest::triaxialMidShear();
  ASSERT_EQ(start.test.stage, TestStage::Shear);
  expectExactResume(start, 800, dir, "triaxial");
}

TEST(StateFile, MembraneTriaxialMidShearResumesExactly)
{
  TempDir dir;
  const Model start = statetest::membraneTriaxialMidShear();
  ASSERT_EQ(start.test.stage, TestStage::Shear);
  ASSERT_EQ(start.test.settings.confinement, Confinement::Membrane);
  expectExactResume(start, 800, dir, "membrane");
}

TEST(StateFile, TruncatedFilesAreRejected)
{
  TempDir dir;
  const std::vector<unsigned char> image = writeStateToMemory(dem::testing::specimen(80, 0.01, 0.001, 0.0015, 4));
  const std::string path = dir.file("cut.rdem");
  for (std::size_t at : { std::size_t(0), std::size_t(10), std::size_t(100), std::size_t(511), std::size_t(512),
                          std::size_t(600), image.size() / 2, image.size() - 1 }) {
    writeBytes(path, image, at);
    const std::string error = readError(path);
    EXPECT_NE(error.find(path), std::string::npos) << "names the file: " << error;
    if (at == 0) {
      EXPECT_NE(error.find("is empty"), std::string::npos) << error;
    } else {
      EXPECT_NE(error.find("truncated"), std::string::npos) << "cut at " << at << ": " << error;
    }
  }
}

TEST(StateFile, DamagedBytesAreRejected)
{
  const std::vector<unsigned char> image = writeStateToMemory(dem::testing::specimen(80, 0.01, 0.001, 0.0015, 4));
  struct Case {
    std::size_t offset;
    const char* expected;
  };
  for (const Case& c : { Case{ 0, "not a RockDEM state file" }, Case{ 5, "not a RockDEM state file" },
                         Case{ 16, "corrupt" }, Case{ 20, "header size" }, Case{ 24, "bytes" },
                         Case{ 32, "corrupt" }, Case{ 100, "corrupt" }, Case{ 512, "corrupt" },
                         Case{ 520, "corrupt" }, Case{ image.size() / 3, "corrupt" },
                         Case{ image.size() / 2, "corrupt" }, Case{ image.size() - 1, "corrupt" } }) {
    std::vector<unsigned char> damaged = image;
    damaged[c.offset] ^= 0x5a;
    const std::string error = memoryError(damaged);
    EXPECT_NE(error.find(c.expected), std::string::npos) << "byte " << c.offset << ": " << error;
    EXPECT_NE(error.find("edited.rdem"), std::string::npos) << error;
  }
}

TEST(StateFile, UnknownVersionIsRejectedNamingTheSupportedOnes)
{
  std::vector<unsigned char> image = writeStateToMemory(Model());
  image[16] = 7; // version 7, resealed: only the version is wrong
  resealStateImage(image);
  const std::string error = memoryError(image);
  EXPECT_NE(error.find("format version 7"), std::string::npos) << error;
  EXPECT_NE(error.find("supported versions are 1"), std::string::npos) << error;
}

TEST(StateFile, PlatenFrictionIsSavedAndOlderFilesReadAsFrictionless)
{
  Model m = dem::testing::specimen(60, 0.01, 0.001, 0.0015, 6);
  LoadTestSettings s;
  s.mode = TestMode::Compression;
  s.platenFriction = 0.35;
  startLoadTest(m, s);
  const std::vector<unsigned char> image = writeStateToMemory(m);
  EXPECT_EQ(readStateFromMemory(image.data(), image.size()).test.settings.platenFriction, 0.35);
  // A file written before Platen Friction existed: the platens were frictionless.
  const auto older = editImage(image, [&](hid_t f) { H5Ldelete(f, "test/settings/platen_friction", H5P_DEFAULT); });
  EXPECT_EQ(readStateFromMemory(older.data(), older.size()).test.settings.platenFriction, 0.0);
}

TEST(StateFile, ConsolidationDampingIsSavedAndOlderFilesReadItAsTheirSettlingDamping)
{
  Model m = dem::testing::specimen(60, 0.01, 0.001, 0.0015, 6);
  m.solver.settlingDamping = 0.2;
  LoadTestSettings s;
  s.mode = TestMode::Triaxial;
  s.consolidationDamping = 0.55;
  startLoadTest(m, s);
  const std::vector<unsigned char> image = writeStateToMemory(m);
  EXPECT_EQ(readStateFromMemory(image.data(), image.size()).test.settings.consolidationDamping, 0.55);
  // A file written before Consolidation Damping existed ran its whole test at Settling Damping.
  const auto older =
    editImage(image, [&](hid_t f) { H5Ldelete(f, "test/settings/consolidation_damping", H5P_DEFAULT); });
  EXPECT_EQ(readStateFromMemory(older.data(), older.size()).test.settings.consolidationDamping, 0.2);
}

TEST(StateFile, TheCylinderOutlineIsSavedOlderFilesReadAsABoxAndBadAxesAreRefused)
{
  Model m = dem::testing::specimen(60, 0.01, 0.001, 0.0015, 6);
  m.domain.cylinderAxis = 2;
  const std::vector<unsigned char> image = writeStateToMemory(m);
  EXPECT_EQ(readStateFromMemory(image.data(), image.size()).domain.cylinderAxis, 2);
  // A file written before the outline existed: every specimen was measured as a box.
  const auto older = editImage(image, [&](hid_t f) { H5Ldelete(f, "settings/domain/cylinder_axis", H5P_DEFAULT); });
  EXPECT_EQ(readStateFromMemory(older.data(), older.size()).domain.cylinderAxis, -1);
  // An axis that is none: refused, naming it and the valid values.
  m.domain.cylinderAxis = 3;
  const std::vector<unsigned char> bad = writeStateToMemory(m);
  try {
    readStateFromMemory(bad.data(), bad.size());
    ADD_FAILURE() << "Cylinder Axis 3 was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("Cylinder Axis = 3 is out of range"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("-1 (a box), 0 (X), 1 (Y) and 2 (Z)"), std::string::npos) << e.what();
  }
}

TEST(StateFile, BondsWithoutTheMomentContributionReadAsFullMoments)
{
  Model m = dem::testing::specimen(60, 0.01, 0.001, 0.0015, 6);
  CementParameters c = dem::testing::testCement();
  c.momentContribution = 0.25;
  cement(m, c);
  ASSERT_GT(m.bonds.size(), 0u);
  const std::vector<unsigned char> image = writeStateToMemory(m);
  EXPECT_EQ(readStateFromMemory(image.data(), image.size()).bonds.momentContribution,
            std::vector<double>(m.bonds.size(), 0.25));
  // A file written before the factor existed: the full moments (Potyondy & Cundall).
  const auto older = editImage(image, [&](hid_t f) { H5Ldelete(f, "bonds/moment_contribution", H5P_DEFAULT); });
  EXPECT_EQ(readStateFromMemory(older.data(), older.size()).bonds.momentContribution,
            std::vector<double>(m.bonds.size(), 1.0));
}

TEST(StateFile, SofteningBondsMidSofteningResumeExactly)
{
  TempDir dir;
  const Model start = statetest::softeningMidCompression();
  expectExactResume(start, 1000, dir, "softening");
}

TEST(StateFile, BondsWithoutSofteningReadAsBrittleAndUndamaged)
{
  Model m = dem::testing::specimen(60, 0.01, 0.001, 0.0015, 6);
  CementParameters c = dem::testing::testCement();
  c.softeningRatio = 3.0;
  cement(m, c);
  ASSERT_GT(m.bonds.size(), 0u);
  m.bonds.damage[0] = 0.5;
  const std::vector<unsigned char> image = writeStateToMemory(m);
  const Model back = readStateFromMemory(image.data(), image.size());
  EXPECT_EQ(back.bonds.softening, std::vector<double>(m.bonds.size(), 3.0));
  EXPECT_EQ(back.bonds.damage, m.bonds.damage);
  // A file written before tension softening existed: brittle, undamaged bonds.
  const auto older = editImage(image, [&](hid_t f) {
    H5Ldelete(f, "bonds/softening_ratio", H5P_DEFAULT);
    H5Ldelete(f, "bonds/damage", H5P_DEFAULT);
  });
  const Model old = readStateFromMemory(older.data(), older.size());
  EXPECT_EQ(old.bonds.softening, std::vector<double>(m.bonds.size(), 0.0));
  EXPECT_EQ(old.bonds.damage, std::vector<double>(m.bonds.size(), 0.0));
}

// A state file written before the Gauge Strain column holds 27 history columns: it reads,
// with the first 27 columns as written and the gauge strain unknown (NaN); another width
// is refused, naming the dataset and the width expected.
TEST(StateFile, HistoryWithoutTheGaugeStrainReadsItAsUnknown)
{
  Model m = dem::testing::specimen(60, 0.01, 0.001, 0.0015, 6);
  for (int r = 0; r < 3; ++r) {
    std::array<double, HistoryColumnCount> row{};
    for (std::size_t k = 0; k < HistoryColumnCount; ++k) {
      row[k] = 100.0 * r + static_cast<double>(k) + 0.25;
    }
    m.test.history.push_back(row);
  }
  const std::vector<unsigned char> image = writeStateToMemory(m);
  const Model back = readStateFromMemory(image.data(), image.size());
  EXPECT_TRUE(dem::statetest::sameBits(back.test.history, m.test.history));
  auto withColumns = [&](std::size_t columns) {
    return editImage(image, [&](hid_t f) {
      std::vector<double> flat;
      for (const auto& row : m.test.history) {
        flat.insert(flat.end(), row.begin(), row.begin() + static_cast<std::ptrdiff_t>(columns));
      }
      replaceDataset(f, "test/history", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, { m.test.history.size(), columns }, flat);
    });
  };
  const auto older = withColumns(HistoryColumnCountBeforeGaugeStrain);
  const Model old = readStateFromMemory(older.data(), older.size());
  ASSERT_EQ(old.test.history.size(), m.test.history.size());
  for (std::size_t r = 0; r < old.test.history.size(); ++r) {
    for (std::size_t k = 0; k < HistoryColumnCountBeforeGaugeStrain; ++k) {
      EXPECT_EQ(old.test.history[r][k], m.test.history[r][k]) << r << " " << k;
    }
    EXPECT_TRUE(std::isnan(old.test.history[r][HistoryColumnCount - 1])) << "the gauge strain is unknown";
  }
  const auto narrower = withColumns(HistoryColumnCountBeforeGaugeStrain - 1);
  const std::string error = memoryError(narrower);
  EXPECT_NE(error.find("'/test/history' has size 3 x 26; expected 3 x 28"), std::string::npos) << error;
}

TEST(StateFile, InconsistentArraySizesAreRejected)
{
  const Model m = dem::testing::specimen(60, 0.01, 0.001, 0.0015, 6);
  const std::size_t n = m.particles.size();
  const std::vector<unsigned char> image = writeStateToMemory(m);
  // One velocity too few: the size check names the dataset, its size and the expected one.
  const auto shortVelocity = editImage(image, [&](hid_t f) {
    std::vector<double> v(3 * (n - 1), 0.0);
    replaceDataset(f, "particles/velocity", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, { n - 1, 3 }, v);
  });
  std::string error = memoryError(shortVelocity);
  EXPECT_NE(error.find("'/particles/velocity' has size " + std::to_string(n - 1) + " x 3; expected " +
                       std::to_string(n) + " x 3 (one per particle)"),
            std::string::npos)
    << error;
  // Radii stored as integers: the type check.
  const auto intRadius = editImage(image, [&](hid_t f) {
    replaceDataset(f, "particles/radius", H5T_STD_I32LE, H5T_NATIVE_INT32, { n }, std::vector<std::int32_t>(n, 1));
  });
  error = memoryError(intRadius);
  EXPECT_NE(error.find("'/particles/radius' holds 32-bit signed integer values; expected 64-bit float"),
            std::string::npos)
    << error;
  // A dataset missing.
  const auto noTorque = editImage(image, [&](hid_t f) { H5Ldelete(f, "particles/torque", H5P_DEFAULT); });
  error = memoryError(noTorque);
  EXPECT_NE(error.find("'/particles/torque' is missing"), std::string::npos) << error;
  // A whole group missing.
  const auto noTest = editImage(image, [&](hid_t f) { H5Ldelete(f, "test", H5P_DEFAULT); });
  error = memoryError(noTest);
  EXPECT_NE(error.find("'/test' is missing"), std::string::npos) << error;
  // An enumeration out of range.
  const auto badMode = editImage(image, [&](hid_t f) {
    H5Ldelete(f, "test/settings/mode", H5P_DEFAULT);
    hid_t space = H5Screate(H5S_SCALAR);
    hid_t d = H5Dcreate2(f, "test/settings/mode", H5T_STD_I32LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    const std::int32_t mode = 9;
    H5Dwrite(d, H5T_NATIVE_INT32, H5S_ALL, H5S_ALL, H5P_DEFAULT, &mode);
    H5Dclose(d);
    H5Sclose(space);
  });
  error = memoryError(badMode);
  EXPECT_NE(error.find("'/test/settings/mode' = 9 is out of range: valid values are 0 to 5"), std::string::npos)
    << error;
  // A value the engine rejects (a negative radius) is reported as user input is.
  const auto negativeRadius = editImage(image, [&](hid_t f) {
    std::vector<double> r = m.particles.radius;
    r[3] = -r[3];
    replaceDataset(f, "particles/radius", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, { n }, r);
  });
  error = memoryError(negativeRadius);
  EXPECT_NE(error.find("invalid value: Radius of particle"), std::string::npos) << error;
}

TEST(StateFile, BondsOfUnknownParticlesAndUnknownFailureModesAreRejected)
{
  const Model m = statetest::cementedMidCompression();
  const std::size_t nb = m.bonds.size();
  const std::vector<unsigned char> image = writeStateToMemory(m);
  const auto badFailure = editImage(image, [&](hid_t f) {
    std::vector<std::uint8_t> failure = m.bonds.failure;
    failure[1] = 9;
    replaceDataset(f, "bonds/failure", H5T_STD_U8LE, H5T_NATIVE_UINT8, { nb }, failure);
  });
  std::string error = memoryError(badFailure);
  EXPECT_NE(error.find("bond 1 has failure mode 9; valid values are 0 to 3"), std::string::npos) << error;
  const auto strangerBond = editImage(image, [&](hid_t f) {
    std::vector<std::int64_t> idB = m.bonds.idB;
    idB.back() = 1000000;
    replaceDataset(f, "bonds/id_b", H5T_STD_I64LE, H5T_NATIVE_INT64, { nb }, idB);
  });
  error = memoryError(strangerBond);
  EXPECT_NE(error.find("no particle with id 1000000"), std::string::npos) << error;
}

TEST(StateFile, MissingAndForeignFilesAreRejected)
{
  TempDir dir;
  EXPECT_NE(readError(dir.file("nothing.rdem")).find("cannot be opened"), std::string::npos);
  EXPECT_NE(readError("/tmp").find("is not a regular file (it is a directory)"), std::string::npos) << readError("/tmp");
  const std::string text = dir.file("notes.rdem");
  {
    std::ofstream(text) << "these are not the particles you are looking for\n";
  }
  EXPECT_NE(readError(text).find("is not a RockDEM state file"), std::string::npos);
  // A plain HDF5 file (the payload without the RockDEM header) is recognised as such.
  const std::vector<unsigned char> image = writeStateToMemory(Model());
  const std::vector<unsigned char> plain(image.begin() + 512, image.end());
  const std::string h5 = dir.file("plain.h5");
  writeBytes(h5, plain, plain.size());
  EXPECT_NE(readError(h5).find("plain HDF5 file"), std::string::npos) << readError(h5);
}

TEST(StateFile, AFailedWriteLeavesTheOldFileAndNoTemporary)
{
  TempDir dir;
  const std::string path = dir.file("keep.rdem");
  const Model first = dem::testing::specimen(40, 0.01, 0.001, 0.0015, 7);
  writeState(first, path);
  const std::vector<unsigned char> before = readBytes(path);
  Model second = first;
  second.clock.time = 1.0;
  test_hooks::failAtomicWriteAfterBytes = 1000; // as a full disk would
  std::string error;
  try {
    writeState(second, path);
  } catch (const FileError& e) {
    error = e.what();
  }
  test_hooks::failAtomicWriteAfterBytes = -1;
  EXPECT_NE(error.find("the previous file, if any, is unchanged"), std::string::npos) << error;
  EXPECT_EQ(readBytes(path), before) << "the old file is intact";
  EXPECT_EQ(dir.files(), std::vector<std::string>{ "keep.rdem" }) << "no temporary file is left";
  EXPECT_EQ(readState(path).clock.time, 0.0);
  // An inconsistent model is refused before anything is written.
  Model broken = first;
  broken.particles.velocity.pop_back();
  EXPECT_THROW(writeState(broken, path), InputError);
  EXPECT_EQ(readBytes(path), before);
  // A directory that does not exist.
  EXPECT_THROW(writeState(first, dir.file("no/such/dir.rdem")), FileError);
}

TEST(StateFile, HistoryGoesBesideAsCSV)
{
  EXPECT_EQ(historyPathFor("/a/run.rdem"), "/a/run.history.csv");
  EXPECT_EQ(historyPathFor("/a.b/run"), "/a.b/run.history.csv");
  EXPECT_EQ(historyPathFor("run.x.rdem"), "run.x.history.csv");
  TempDir dir;
  const Model m = statetest::triaxialMidShear();
  const std::string csv = dir.file("t.history.csv");
  writeHistoryCSV(m.test, csv);
  std::ifstream in(csv);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("\"Time (s)\",\"Step\",", 0), 0u) << header;
  std::size_t rows = 0;
  std::string line;
  double lastTime = 0.0;
  while (std::getline(in, line)) {
    ++rows;
    lastTime = std::stod(line.substr(0, line.find(',')));
  }
  EXPECT_EQ(rows, m.test.history.size());
  EXPECT_EQ(lastTime, m.test.history.back()[0]) << "full precision";
}

// Files that crash HDF5 1.10's own parser (found by fuzzing with the checksum check off,
// Testing/Fuzz/hdf5_crashers): with the check on they are rejected before HDF5 sees them.
TEST(StateFile, FilesThatCrashHDF5AreStoppedByTheChecksum)
{
  for (const char* name : { "alloc_too_big_H5C_protect.rdem", "segv_H5D__chunk_set_sizes.rdem" }) {
    const std::string path = std::string(ROCKDEM_SOURCE_DIR) + "/Testing/Fuzz/hdf5_crashers/" + name;
    const std::string error = readError(path);
    EXPECT_NE(error.find("is corrupt"), std::string::npos) << name << ": " << error;
  }
}

// The file holds no time stamps: the same model gives the same bytes (checkpoints can be
// compared with cmp; the round-trip test above relies on it too).
TEST(StateFile, TheSameModelGivesTheSameBytes)
{
  const Model m = dem::testing::specimen(40, 0.01, 0.001, 0.0015, 8);
  const std::vector<unsigned char> first = writeStateToMemory(m);
  ::usleep(1100 * 1000); // past a second boundary: HDF5's object times would differ
  EXPECT_EQ(writeStateToMemory(m), first);
}
