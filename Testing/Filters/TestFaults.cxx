// Bad input and faults (issue 18) through the VTK filters: what the user sees (an error
// naming the parameter and the valid range, a warning, Status and Last Message), and the
// reader -> load test path on every kind of state file the project writes.
// Documentation/Faults.md lists every case and the test that covers it.
#include "ErrorCatcher.h"

#include "vtkDEMLoadTest.h"
#include "vtkDEMModelConversion.h"
#include "vtkDEMModelFromPoints.h"
#include "vtkDEMPackSource.h"
#include "vtkDEMStateReader.h"

#include "../Solver/Specimens.h"
#include "../Solver/StateFixtures.h"
#include "../Solver/TempDir.h"
#include "dem/Bonds.h"
#include "dem/StateFile.h"

#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

using dem::testing::TempDir;

namespace
{
/// Points with radii (m), as any VTK source would give them.
vtkSmartPointer<vtkPolyData> Spheres(const std::vector<std::array<double, 4>>& spheres)
{
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  vtkNew<vtkDoubleArray> r;
  r->SetName("Radius");
  for (const auto& s : spheres)
  {
    pts->InsertNextPoint(s[0], s[1], s[2]);
    r->InsertNextValue(s[3]);
  }
  pd->SetPoints(pts);
  pd->GetPointData()->AddArray(r);
  return pd;
}

bool Contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

/// Errors and warnings of an algorithm.
struct Messages
{
  explicit Messages(vtkAlgorithm* algorithm)
  {
    algorithm->AddObserver(vtkCommand::ErrorEvent, this->Errors);
    algorithm->AddObserver(vtkCommand::WarningEvent, this->Warnings);
  }
  vtkNew<ErrorCatcher> Errors;
  vtkNew<ErrorCatcher> Warnings;
};

void RunFrames(vtkDEMLoadTest* test, int frames, double interval)
{
  test->SetFrameInterval(interval);
  test->SetNumberOfFrames(frames);
  test->UpdateTimeStep(frames * interval);
}
}

// Items 5, 7, 8, 13: DEM Model From Points.
TEST(FaultsFilters, ModelFromPointsRejectsCoincidentCentresAndEmptyInputs)
{
  // Item 5: two points at one place: an error naming both points.
  vtkNew<vtkDEMModelFromPoints> coincident;
  coincident->SetInputData(Spheres({ { 0, 0, 0, 0.01 }, { 0.05, 0, 0, 0.01 }, { 0.05, 0, 0, 0.01 } }));
  Messages m1(coincident);
  EXPECT_FALSE(UpdateSucceeded(coincident));
  EXPECT_TRUE(Contains(m1.Errors->All(), "Particles 1 and 2 have the same centre (0.05, 0, 0) m")) << m1.Errors->All();
  EXPECT_TRUE(Contains(coincident->GetLastMessage(), "Particles 1 and 2")) << coincident->GetLastMessage();

  // Item 8: no points: a clear message, no output; the stage after says its input is empty.
  vtkNew<vtkDEMModelFromPoints> empty;
  empty->SetInputData(Spheres({}));
  Messages m2(empty);
  EXPECT_FALSE(UpdateSucceeded(empty));
  EXPECT_TRUE(Contains(m2.Errors->All(), "the input has no points")) << m2.Errors->All();
  // VTK does not run a stage whose input failed; when ParaView hands it the empty output
  // later (the failed stage left as it is), the stage says what it got.
  vtkNew<vtkMultiBlockDataSet> nothing;
  vtkNew<vtkDEMLoadTest> downstream;
  downstream->SetInputData(nothing);
  Messages m3(downstream);
  downstream->SetFrameInterval(0.001);
  downstream->SetNumberOfFrames(1);
  EXPECT_FALSE(UpdateSucceeded(downstream));
  EXPECT_TRUE(Contains(m3.Errors->All(), "it is empty (no 'Particles' block), so the stage before this one "
                                         "produced no model"))
    << m3.Errors->All();
  EXPECT_TRUE(Contains(downstream->GetLastMessage(), "it is empty"));

  // A model with no particles (a pack of 0 elements) is valid, and the load test says so.
  vtkNew<vtkDEMPackSource> none;
  none->SetInitialElements(0);
  vtkNew<vtkDEMLoadTest> idle;
  idle->SetInputConnection(none->GetOutputPort(0));
  Messages m4(idle);
  RunFrames(idle, 1, 0.001);
  EXPECT_TRUE(Contains(m4.Warnings->All(), "The input model has no particles")) << m4.Warnings->All();
}

TEST(FaultsFilters, ModelFromPointsWarnsAboutOverlapsAndAReplacedBox)
{
  // Item 7: overlapping spheres: a warning with the largest overlap; porosity never < 0.
  vtkNew<vtkDEMModelFromPoints> overlap;
  overlap->SetInputData(Spheres({ { 0, 0, 0, 0.01 }, { 0.015, 0, 0, 0.01 }, { 0.0, 0.012, 0, 0.01 },
    { 0.016, 0.012, 0, 0.01 }, { 0.008, 0.006, 0.001, 0.01 } }));
  Messages m1(overlap);
  EXPECT_TRUE(UpdateSucceeded(overlap));
  EXPECT_TRUE(Contains(m1.Warnings->All(), "pair(s) of input spheres overlap; the largest overlap is")) << m1.Warnings->All();
  EXPECT_TRUE(Contains(overlap->GetLastMessage(), "largest overlap"));
  EXPECT_GE(overlap->GetCurrentPorosity(), 0.0);
  EXPECT_LE(overlap->GetCurrentPorosity(), 1.0);

  // Item 13: Fit To Input on (the default) with a box set: a warning that it was replaced.
  vtkNew<vtkDEMModelFromPoints> fitted;
  fitted->SetInputData(Spheres({ { 0.05, 0.05, 0.05, 0.005 } }));
  fitted->SetOriginZ(-0.1);
  fitted->SetZDimension(0.5);
  Messages m2(fitted);
  EXPECT_TRUE(UpdateSucceeded(fitted));
  EXPECT_TRUE(Contains(m2.Warnings->All(), "Fit To Input is on: the box you set (Origin (0, 0, -0.1) m, "
                                           "Dimensions (0.1, 0.1, 0.5) m) is replaced by the box fitted to the "
                                           "input (origin (0.045, 0.045, 0.045) m"))
    << m2.Warnings->All();
  // With the box left alone, or Fit To Input off, no warning.
  fitted->SetFitToInput(0);
  m2.Warnings->Messages.clear();
  EXPECT_TRUE(UpdateSucceeded(fitted));
  EXPECT_EQ(m2.Warnings->All(), "");
  const dem::Model model =
    rockdem::MultiBlockToModel(vtkMultiBlockDataSet::SafeDownCast(fitted->GetOutputDataObject(0)));
  EXPECT_EQ(model.domain.size.z(), 0.5) << "Fit To Input off: the box set is used";
}

// Item 4: the reader -> load test path on every kind of state file the project writes:
// settled, cemented, mid-test, a finished unconfined test whose grains flew out of the box,
// and triaxial. Each runs in Mode Off without gravity (the path), and a test in
// progress also continues in its own mode.
TEST(FaultsFilters, ReaderThenLoadTestRunsOnEveryKindOfStateFile)
{
  TempDir dir;
  std::vector<std::pair<std::string, dem::Model>> kinds;
  kinds.emplace_back("settled", dem::statetest::settlingPack());
  dem::Model consolidated = dem::testing::specimen(250, 0.012, 0.0008, 0.0012, 3);
  dem::testing::consolidate(consolidated, 2e4);
  dem::Model cemented = consolidated;
  dem::cement(cemented, dem::testing::testCement());
  kinds.emplace_back("cemented", cemented);
  // Unconfined compression: mid-test, then finished.
  dem::Model press = cemented;
  dem::LoadTestSettings ucs;
  ucs.mode = dem::TestMode::Compression;
  ucs.strainRate = 1.0;
  ucs.maxStrain = 0.01;
  ucs.sampleInterval = 100;
  dem::startLoadTest(press, ucs);
  {
    dem::Simulation sim(press);
    sim.advance(1500);
    ASSERT_EQ(press.test.stage, dem::TestStage::Shear);
    kinds.emplace_back("mid-test", press);
    for (int k = 0; k < 200 && press.test.stage != dem::TestStage::Done; ++k)
    {
      sim.advance(500);
    }
    ASSERT_EQ(press.test.stage, dem::TestStage::Done);
  }
  // Grains ejected through the open sides, as in the main job's specimen (issue 18: 180 of
  // 20,166 centres outside the box): two out through the sides, one fallen below the box.
  press.particles.position[0].x() = press.domain.upper().x() + 0.004;
  press.particles.position[1].y() = press.domain.origin.y() - 0.002;
  press.particles.position[2].x() = press.domain.origin.x() - 0.02;
  kinds.emplace_back("finished unconfined test", press);
  dem::Model triaxial = consolidated;
  dem::LoadTestSettings tri;
  tri.mode = dem::TestMode::Triaxial;
  tri.confiningStress = 2e4;
  tri.strainRate = 0.5;
  tri.sampleInterval = 100;
  dem::startLoadTest(triaxial, tri);
  {
    dem::Simulation sim(triaxial);
    for (int k = 0; k < 100 && triaxial.test.stage != dem::TestStage::Shear; ++k)
    {
      sim.advance(100);
    }
    sim.advance(300);
    ASSERT_EQ(triaxial.test.stage, dem::TestStage::Shear);
  }
  kinds.emplace_back("triaxial", triaxial);

  for (const auto& kind : kinds)
  {
    const std::string path = dir.file("state.rdem");
    dem::writeStateAndHistory(kind.second, path);
    vtkNew<vtkDEMStateReader> reader;
    reader->SetFileName(path.c_str());
    vtkNew<vtkDEMLoadTest> off;
    off->SetInputConnection(reader->GetOutputPort(0));
    off->SetGravity(0.0, 0.0, 0.0);
    Messages messages(off);
    RunFrames(off, 2, 2e-4);
    EXPECT_EQ(messages.Errors->All(), "") << kind.first;
    EXPECT_EQ(off->GetCurrentFrame(), 2) << kind.first << ": " << off->GetStatus();
    EXPECT_TRUE(Contains(off->GetStatus(), "t = ")) << kind.first << ": " << off->GetStatus();
    if (kind.first == "finished unconfined test")
    {
      EXPECT_TRUE(Contains(off->GetLastMessage(), "Removed 3 particle(s) whose centres lay beyond the walls of this stage"))
        << off->GetLastMessage();
      EXPECT_EQ(rockdem::MultiBlockToModel(vtkMultiBlockDataSet::SafeDownCast(off->GetOutputDataObject(0)))
                  .particles.size(),
        kind.second.particles.size() - 3);
    }
    if (kind.second.test.stage == dem::TestStage::Shear)
    {
      // The same test, continued where it stopped.
      vtkNew<vtkDEMLoadTest> same;
      same->SetInputConnection(reader->GetOutputPort(0));
      same->SetGravity(0.0, 0.0, 0.0);
      const dem::LoadTestSettings& s = kind.second.test.settings;
      same->SetMode(static_cast<int>(s.mode));
      same->SetConfiningStress(s.confiningStress);
      same->SetStrainRate(s.strainRate);
      same->SetMaxStrain(s.maxStrain);
      same->SetSampleInterval(static_cast<int>(s.sampleInterval));
      Messages continued(same);
      RunFrames(same, 2, 2e-4);
      EXPECT_EQ(continued.Errors->All(), "") << kind.first;
      EXPECT_EQ(same->GetCurrentFrame(), 2) << kind.first << ": " << same->GetStatus();
      EXPECT_GT(rockdem::MultiBlockToModel(vtkMultiBlockDataSet::SafeDownCast(same->GetOutputDataObject(0)))
                  .test.history.size(),
        kind.second.test.history.size())
        << kind.first << ": the test continued (its history grew)";
    }
  }
}

// Item 17: a damaged .rdem is still taken by DEM State Reader (File > Open), whose message
// says what is wrong, instead of ParaView's "No reader found".
TEST(FaultsFilters, ADamagedStateFileReachesTheReaderWhichSaysWhy)
{
  TempDir dir;
  std::vector<unsigned char> image = dem::writeStateToMemory(dem::testing::specimen(40, 0.01, 0.001, 0.0015, 4));
  auto save = [&](const std::string& name, const std::vector<unsigned char>& bytes) {
    std::ofstream out(dir.file(name), std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    return dir.file(name);
  };
  std::vector<unsigned char> magic = image;
  magic[0] ^= 0xff;
  std::vector<unsigned char> cut(image.begin(), image.begin() + 10);
  std::vector<unsigned char> flipped = image;
  flipped[16] ^= 0x10;
  const std::vector<std::pair<std::string, std::string>> cases = {
    { save("magic.rdem", magic), "is not a RockDEM state file" },
    { save("cut.RDEM", cut), "truncated" },
    { save("empty.rdem", {}), "is empty (0 bytes)" },
    { save("flipped.rdem", flipped), "is corrupt" },
  };
  for (const auto& c : cases)
  {
    EXPECT_EQ(vtkDEMStateReader::CanReadFile(c.first.c_str()), 1) << c.first;
    vtkNew<vtkDEMStateReader> reader;
    reader->SetFileName(c.first.c_str());
    Messages messages(reader);
    EXPECT_FALSE(UpdateSucceeded(reader)) << c.first;
    EXPECT_TRUE(Contains(messages.Errors->All(), c.second)) << messages.Errors->All();
    EXPECT_TRUE(Contains(reader->GetLastMessage(), c.second)) << reader->GetLastMessage();
  }
  EXPECT_EQ(vtkDEMStateReader::CanReadFile(dir.file("missing.rdem").c_str()), 0);
  EXPECT_EQ(vtkDEMStateReader::CanReadFile(save("notes.txt", { 'h', 'i' }).c_str()), 0) << "not ours";
  EXPECT_EQ(vtkDEMStateReader::CanReadFile(save("renamed.bin", image).c_str()), 1) << "the magic says ours";
}

// Other findings: a checkpoint that cannot be written shows in Status and Last Message (and
// in Output Messages once, not every frame); a History File that cannot be written says why.
TEST(FaultsFilters, FailedCheckpointsAndHistoryFilesSayWhyInStatusAndLastMessage)
{
  TempDir dir;
  vtkNew<vtkDEMPackSource> pack;
  pack->SetXDimension(0.02);
  pack->SetYDimension(0.02);
  pack->SetZDimension(0.02);
  pack->SetInitialElements(150);
  pack->SetMinimumSize(0.001);
  pack->SetMaximumSize(0.0015);
  pack->SetYoungsModulus(1.0e8);
  vtkNew<vtkDEMLoadTest> test;
  test->SetInputConnection(pack->GetOutputPort(0));
  const std::string nowhere = dir.file("no-such-dir/run.rdem");
  test->SetCheckpointFile(nowhere.c_str());
  test->SetCheckpointEvery(1);
  test->SetHistoryFile(dir.file("no-such-dir/h.csv").c_str());
  test->SetMode(vtkDEMLoadTest::MODE_ISOTROPIC);
  test->SetConfiningStress(1e4);
  test->SetSampleInterval(20);
  test->SetGravity(0.0, 0.0, 0.0);
  Messages messages(test);
  test->SetFrameInterval(1e-4);
  test->SetNumberOfFrames(3);
  for (int frame = 1; frame <= 3; ++frame)
  {
    test->UpdateTimeStep(frame * 1e-4);
  }
  EXPECT_EQ(test->GetCurrentFrame(), 3);
  EXPECT_EQ(messages.Errors->Messages.size(), 1u) << "one error for one failure, not one per frame:\n"
                                                  << messages.Errors->All();
  EXPECT_TRUE(Contains(messages.Errors->All(), "Checkpoint File: Cannot write '" + nowhere + "'"));
  EXPECT_TRUE(Contains(test->GetStatus(), "FAILED Checkpoint File")) << test->GetStatus();
  EXPECT_TRUE(Contains(test->GetStatus(), "No such file or directory")) << test->GetStatus();
  EXPECT_TRUE(Contains(messages.Warnings->All(), "History File: Cannot write")) << messages.Warnings->All();
  EXPECT_TRUE(Contains(messages.Warnings->All(), "(No such file or directory)")) << messages.Warnings->All();
  EXPECT_TRUE(Contains(test->GetLastMessage(), "No such file or directory")) << test->GetLastMessage();
  EXPECT_EQ(dir.files(), std::vector<std::string>{}) << "nothing half-written";
}
