// DEM State Writer / DEM State Reader and the load test's checkpoints (reference guide
// "Saving and reopening"; Documentation/StateFile.md): the model survives writer ->
// file -> reader unchanged; writing is atomic; a reader error gives a message and no
// output; a run checkpointed at frame N, reopened and continued by a new load test ends
// bitwise where the uninterrupted run does.
#include "ErrorCatcher.h"

#include "vtkDEMLoadTest.h"
#include "vtkDEMModelConversion.h"
#include "vtkDEMPackSource.h"
#include "vtkDEMStateReader.h"
#include "vtkDEMStateWriter.h"

#include "../Solver/StateFixtures.h"
#include "dem/StateFile.h"

#include <vtkCommand.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <dirent.h>
#include <fstream>
#include <unistd.h>

namespace
{
class TempDir
{
public:
  TempDir()
  {
    char pattern[] = "/tmp/rockdem-statefilters-XXXXXX";
    this->Path = ::mkdtemp(pattern);
  }
  ~TempDir()
  {
    for (const std::string& f : this->Files())
    {
      std::remove((this->Path + "/" + f).c_str());
    }
    ::rmdir(this->Path.c_str());
  }
  std::string File(const std::string& name) const { return this->Path + "/" + name; }
  std::vector<std::string> Files() const
  {
    std::vector<std::string> names;
    if (DIR* d = ::opendir(this->Path.c_str()))
    {
      while (dirent* e = ::readdir(d))
      {
        const std::string n = e->d_name;
        if (n != "." && n != "..")
        {
          names.push_back(n);
        }
      }
      ::closedir(d);
    }
    std::sort(names.begin(), names.end());
    return names;
  }
  std::string Path;
};

void MakePack(vtkDEMPackSource* pack)
{
  pack->SetXDimension(0.02);
  pack->SetYDimension(0.02);
  pack->SetZDimension(0.02);
  pack->SetInitialElements(400);
  pack->SetMinimumSize(0.001);
  pack->SetMaximumSize(0.0015);
  pack->SetYoungsModulus(1.0e8);
  pack->SetRandomSeed(4);
  pack->GrowElements();
}

void MakeTriaxial(vtkDEMLoadTest* test, int frames)
{
  test->SetMode(vtkDEMLoadTest::MODE_TRIAXIAL);
  test->SetConfiningStress(1.0e5);
  test->SetStrainRate(0.5);
  test->SetSampleInterval(100);
  test->SetGravity(0.0, 0.0, 0.0);
  test->SetFrameInterval(0.0005);
  test->SetNumberOfFrames(frames);
}

dem::Model ModelOf(vtkAlgorithm* algorithm)
{
  return rockdem::MultiBlockToModel(
    vtkMultiBlockDataSet::SafeDownCast(algorithm->GetOutputDataObject(0)));
}

std::vector<unsigned char> Bytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::vector<unsigned char>(std::istreambuf_iterator<char>(in), {});
}
}

TEST(StateFileFilters, WriterAndReaderRoundTripTheModel)
{
  TempDir dir;
  vtkNew<vtkDEMPackSource> pack;
  MakePack(pack);
  vtkNew<vtkDEMLoadTest> test;
  test->SetInputConnection(pack->GetOutputPort(0));
  MakeTriaxial(test, 4);
  test->UpdateTimeStep(4 * 0.0005);
  ASSERT_EQ(test->GetCurrentFrame(), 4);
  const dem::Model saved = ModelOf(test);
  ASSERT_FALSE(saved.test.history.empty());

  vtkNew<vtkDEMStateWriter> writer;
  writer->SetInputConnection(test->GetOutputPort(0));
  const std::string path = dir.File("run.rdem");
  writer->SetFileName(path.c_str());
  ASSERT_EQ(writer->Write(), 1);
  EXPECT_EQ(writer->GetLastWriteSucceeded(), 1);
  EXPECT_EQ(dir.Files(), (std::vector<std::string>{ "run.history.csv", "run.rdem" }))
    << "the state file and its history, no temporary file";
  EXPECT_EQ(vtkDEMStateReader::CanReadFile(path.c_str()), 1);

  vtkNew<vtkDEMStateReader> reader;
  reader->SetFileName(path.c_str());
  ASSERT_TRUE(UpdateSucceeded(reader));
  const dem::Model back = ModelOf(reader);
  EXPECT_EQ(dem::statetest::firstDifference(saved, back), "");
  EXPECT_EQ(reader->GetNumberOfParticles(), static_cast<vtkIdType>(saved.particles.size()));
  EXPECT_EQ(reader->GetModelTime(), saved.clock.time);
  EXPECT_EQ(std::string(reader->GetTestMode()), "Triaxial");
  // The engine reads exactly what the writer wrote.
  EXPECT_EQ(dem::statetest::firstDifference(dem::readState(path), saved), "");
}

TEST(StateFileFilters, AFailedWriteKeepsTheOldFile)
{
  TempDir dir;
  vtkNew<vtkDEMPackSource> pack;
  MakePack(pack);
  vtkNew<vtkDEMStateWriter> writer;
  writer->SetInputConnection(pack->GetOutputPort(0));
  const std::string path = dir.File("keep.rdem");
  writer->SetFileName(path.c_str());
  ASSERT_EQ(writer->Write(), 1);
  const std::vector<unsigned char> before = Bytes(path);

  pack->SetRandomSeed(5); // a different model
  vtkNew<ErrorCatcher> catcher;
  writer->AddObserver(vtkCommand::ErrorEvent, catcher);
  dem::test_hooks::failAtomicWriteAfterBytes = 4096; // as a full disk would
  writer->Write();
  dem::test_hooks::failAtomicWriteAfterBytes = -1;
  EXPECT_EQ(writer->GetLastWriteSucceeded(), 0);
  EXPECT_NE(catcher->All().find("the previous file, if any, is unchanged"), std::string::npos)
    << catcher->All();
  EXPECT_EQ(Bytes(path), before) << "the old file is intact";
  EXPECT_EQ(dir.Files(), std::vector<std::string>{ "keep.rdem" }) << "no temporary file is left";
}

TEST(StateFileFilters, ReaderErrorsGiveAMessageAndNoOutput)
{
  TempDir dir;
  vtkNew<vtkDEMStateReader> reader;
  vtkNew<ErrorCatcher> catcher;
  reader->AddObserver(vtkCommand::ErrorEvent, catcher);
  auto expectFailure = [&](const std::string& file, const std::string& expected) {
    catcher->Messages.clear();
    reader->SetFileName(file.c_str());
    EXPECT_FALSE(UpdateSucceeded(reader)) << file;
    EXPECT_NE(catcher->All().find(expected), std::string::npos) << catcher->All();
    auto* mb = vtkMultiBlockDataSet::SafeDownCast(reader->GetOutputDataObject(0));
    EXPECT_EQ(mb->GetNumberOfBlocks(), 0u) << "no output after an error";
  };
  expectFailure(dir.File("missing.rdem"), "cannot be opened");
  // A truncated file.
  const std::vector<unsigned char> image = dem::writeStateToMemory(dem::Model());
  const std::string cut = dir.File("cut.rdem");
  {
    std::ofstream out(cut, std::ios::binary);
    out.write(reinterpret_cast<const char*>(image.data()), static_cast<std::streamsize>(image.size() / 2));
  }
  expectFailure(cut, "truncated");
  // A damaged byte.
  std::vector<unsigned char> damaged = image;
  damaged[image.size() - 10] ^= 1;
  const std::string bad = dir.File("bad.rdem");
  {
    std::ofstream out(bad, std::ios::binary);
    out.write(reinterpret_cast<const char*>(damaged.data()), static_cast<std::streamsize>(damaged.size()));
  }
  expectFailure(bad, "corrupt");
  EXPECT_EQ(vtkDEMStateReader::CanReadFile(dir.File("missing.rdem").c_str()), 0);
}

// Run A: 2N frames in one load test. Run B: N frames with a checkpoint at the end, the
// checkpoint read by DEM State Reader, and a new load test with the same settings for N
// more frames. B ends bitwise where A does (servo state and history included).
TEST(StateFileFilters, CheckpointThenReaderAndLoadTestContinueExactly)
{
  TempDir dir;
  const int n = 6;
  vtkNew<vtkDEMPackSource> pack;
  MakePack(pack);
  vtkNew<vtkDEMLoadTest> a;
  a->SetInputConnection(pack->GetOutputPort(0));
  MakeTriaxial(a, 2 * n);
  a->UpdateTimeStep(2 * n * 0.0005);
  ASSERT_EQ(a->GetCurrentFrame(), 2 * n);
  const dem::Model modelA = ModelOf(a);

  vtkNew<vtkDEMLoadTest> b;
  b->SetInputConnection(pack->GetOutputPort(0));
  MakeTriaxial(b, n);
  const std::string checkpoint = dir.File("b.rdem");
  b->SetCheckpointFile(checkpoint.c_str());
  b->SetCheckpointEvery(4);
  b->UpdateTimeStep(3 * 0.0005);
  EXPECT_EQ(dir.Files(), std::vector<std::string>{}) << "no checkpoint before frame 4";
  b->UpdateTimeStep(4 * 0.0005);
  EXPECT_EQ(dem::readState(checkpoint).clock.step, ModelOf(b).clock.step) << "frame 4 saved";
  b->UpdateTimeStep(n * 0.0005);
  ASSERT_EQ(b->GetCurrentFrame(), n);
  const dem::Model atN = ModelOf(b);
  ASSERT_NE(atN.test.stage, dem::TestStage::Idle);
  EXPECT_EQ(dem::statetest::firstDifference(dem::readState(checkpoint), atN), "")
    << "the last frame is saved";
  // The state, its history and the run record beside them (which run wrote the
  // checkpoint: Resume From Checkpoint reads it, vtkDEMCheckpoint.h).
  EXPECT_EQ(dir.Files(), (std::vector<std::string>{ "b.history.csv", "b.rdem", "b.rdem.stage" }));
  // Changing where checkpoints go does not discard the run.
  b->SetCheckpointFile(dir.File("b2.rdem").c_str());
  b->UpdateTimeStep(n * 0.0005);
  EXPECT_EQ(ModelOf(b).clock.step, atN.clock.step);
  EXPECT_EQ(dem::statetest::firstDifference(dem::readState(dir.File("b2.rdem")), atN), "");

  vtkNew<vtkDEMStateReader> reader;
  reader->SetFileName(checkpoint.c_str());
  vtkNew<vtkDEMLoadTest> resumed;
  resumed->SetInputConnection(reader->GetOutputPort(0));
  MakeTriaxial(resumed, n);
  resumed->UpdateTimeStep(n * 0.0005);
  ASSERT_EQ(resumed->GetCurrentFrame(), n);
  const dem::Model modelB = ModelOf(resumed);
  EXPECT_EQ(modelB.clock.step, modelA.clock.step);
  EXPECT_EQ(dem::statetest::firstDifference(modelA, modelB), "")
    << "the reopened run continues exactly";

  // With Continue Test off the reopened model starts a new test instead.
  resumed->SetContinueTest(0);
  resumed->UpdateTimeStep(0.0);
  EXPECT_EQ(ModelOf(resumed).test.history.size(), 0u) << "a new test starts with no history";
}

// A test that finishes before the last frame (Stage done) is checkpointed then: a script
// that stops at done (rockdem.run_test) still gets the end of its run saved.
TEST(StateFileFilters, AFinishedTestIsCheckpointedBeforeTheLastFrame)
{
  TempDir dir;
  vtkNew<vtkDEMPackSource> pack;
  MakePack(pack);
  vtkNew<vtkDEMLoadTest> test;
  test->SetInputConnection(pack->GetOutputPort(0));
  test->SetMode(vtkDEMLoadTest::MODE_COMPRESSION);
  test->SetStrainRate(2.0);
  test->SetMaxStrain(0.002);
  test->SetSampleInterval(50);
  test->SetGravity(0.0, 0.0, 0.0);
  test->SetFrameInterval(0.0005);
  test->SetNumberOfFrames(20);
  const std::string checkpoint = dir.File("done.rdem");
  test->SetCheckpointFile(checkpoint.c_str());
  int frame = 1;
  for (; frame < 20; ++frame)
  {
    test->UpdateTimeStep(frame * 0.0005);
    if (ModelOf(test).test.stage == dem::TestStage::Done)
    {
      break;
    }
    EXPECT_EQ(dir.Files(), std::vector<std::string>{}) << "no checkpoint while the test runs";
  }
  ASSERT_LT(frame, 20) << "Max Strain is reached before the last frame";
  const dem::Model done = ModelOf(test);
  EXPECT_EQ(dem::statetest::firstDifference(dem::readState(checkpoint), done), "")
    << "the frame at which the test finished is saved";
}
