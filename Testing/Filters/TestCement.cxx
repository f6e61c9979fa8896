// vtkDEMCement: the cemented model, its Bonds block, re-cementing, the time contract and
// bad input (reference guide "Cementing the model", "Reading damage"; DESIGN.md). The
// bond physics itself is tested in the engine (Testing/Solver/TestBonds.cpp, TestCement.cpp).
#include "ErrorCatcher.h"

#include "vtkDEMCement.h"
#include "vtkDEMLoadTest.h"
#include "vtkDEMPackSource.h"

#include <vtkCellData.h>
#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace
{
vtkPolyData* Block(vtkAlgorithm* algorithm, const char* name)
{
  auto* mb = vtkMultiBlockDataSet::SafeDownCast(algorithm->GetOutputDataObject(0));
  for (unsigned int k = 0; mb && k < mb->GetNumberOfBlocks(); ++k)
  {
    if (mb->HasMetaData(k) && std::string(mb->GetMetaData(k)->Get(vtkCompositeDataSet::NAME())) == name)
    {
      return vtkPolyData::SafeDownCast(mb->GetBlock(k));
    }
  }
  return nullptr;
}

/// A dense pack: particles grown into contact with their nearest neighbours.
void MakePack(vtkDEMPackSource* pack)
{
  pack->SetXDimension(0.04);
  pack->SetYDimension(0.04);
  pack->SetZDimension(0.04);
  pack->SetInitialElements(400);
  pack->SetMinimumSize(0.0015);
  pack->SetMaximumSize(0.003);
  pack->SetYoungsModulus(1.0e8);
  pack->SetRandomSeed(3);
  pack->GrowElements();
}

std::string FailureMessage(vtkDEMCement* cement)
{
  vtkNew<ErrorCatcher> catcher;
  const unsigned long tag = cement->AddObserver(vtkCommand::ErrorEvent, catcher);
  EXPECT_FALSE(UpdateSucceeded(cement));
  cement->RemoveObserver(tag);
  auto* mb = vtkMultiBlockDataSet::SafeDownCast(cement->GetOutputDataObject(0));
  EXPECT_EQ(mb->GetNumberOfBlocks(), 0u) << "no partial output after an error";
  EXPECT_EQ(cement->GetNumberOfBonds(), 0);
  EXPECT_NE(std::string(cement->GetLastMessage()), "");
  return catcher->All();
}
}

TEST(Cement, BondsTouchingPairsAndDrawsOneLinePerBond)
{
  vtkNew<vtkDEMPackSource> pack;
  MakePack(pack);
  vtkNew<vtkDEMCement> cement;
  cement->SetInputConnection(pack->GetOutputPort(0));
  cement->SetBondModulus(2.0e8);
  ASSERT_TRUE(UpdateSucceeded(cement));

  const vtkIdType n = cement->GetNumberOfBonds();
  EXPECT_GT(n, 200);
  EXPECT_EQ(cement->GetNumberOfBrokenBonds(), 0);
  EXPECT_EQ(cement->GetDamage(), 0.0);
  EXPECT_EQ(cement->GetBrokenInTension(), 0);
  EXPECT_EQ(cement->GetBrokenInShear(), 0);
  EXPECT_NE(std::string(cement->GetLastMessage()).find(std::to_string(n)), std::string::npos)
    << cement->GetLastMessage();

  vtkPolyData* particles = Block(cement, "Particles");
  vtkPolyData* bonds = Block(cement, "Bonds");
  ASSERT_NE(particles, nullptr);
  ASSERT_NE(bonds, nullptr);
  EXPECT_EQ(particles->GetNumberOfPoints(), Block(pack, "Particles")->GetNumberOfPoints());
  ASSERT_EQ(bonds->GetNumberOfLines(), n);
  for (const char* name : { "IdA", "IdB", "BondRadius", "NormalStiffness", "ShearStiffness",
         "TensileStrength", "Cohesion", "FrictionAngle", "NormalForce", "ShearForce",
         "TwistingMoment", "BendingMoment", "Broken", "FailureMode", "FailureTime",
         "FailurePosition", "FailureNormal" })
  {
    vtkDataArray* a = bonds->GetCellData()->GetArray(name);
    ASSERT_NE(a, nullptr) << name;
    EXPECT_EQ(a->GetNumberOfTuples(), n) << name;
  }

  // Bond stiffness from the modulus: kn = E / (rA + rB); the read-only value is for two
  // particles of the largest radius (PHYSICS.md s.3).
  const double rmax = particles->GetPointData()->GetArray("Radius")->GetRange(0)[1];
  EXPECT_NEAR(cement->GetBondStiffness(), 2.0e8 / (2.0 * rmax), 1e-9 * cement->GetBondStiffness());
  vtkDataArray* kn = bonds->GetCellData()->GetArray("NormalStiffness");
  EXPECT_GE(kn->GetRange(0)[0], cement->GetBondStiffness() * (1.0 - 1e-12));
  // Defaults: no scatter, 30 degrees, bond radius = the smaller particle radius.
  const double* sigma = bonds->GetCellData()->GetArray("TensileStrength")->GetRange(0);
  EXPECT_EQ(sigma[0], 10.0e6);
  EXPECT_EQ(sigma[1], 10.0e6);
  EXPECT_NEAR(bonds->GetCellData()->GetArray("FrictionAngle")->GetRange(0)[0], M_PI / 6.0, 1e-15);
  EXPECT_EQ(bonds->GetCellData()->GetArray("Broken")->GetRange(0)[1], 0.0);
  EXPECT_EQ(bonds->GetCellData()->GetArray("FailureMode")->GetRange(0)[1], 0.0);

  // Every line joins two particles that touch or nearly so (gap <= 0.05 x smaller radius),
  // and its length says so.
  vtkDataArray* rb = bonds->GetCellData()->GetArray("BondRadius");
  for (vtkIdType c = 0; c < n; ++c)
  {
    double p0[3], p1[3];
    bonds->GetPoint(2 * c, p0);
    bonds->GetPoint(2 * c + 1, p1);
    const double length = std::sqrt((p1[0] - p0[0]) * (p1[0] - p0[0]) +
      (p1[1] - p0[1]) * (p1[1] - p0[1]) + (p1[2] - p0[2]) * (p1[2] - p0[2]));
    const double rSmall = rb->GetComponent(c, 0); // multiplier 1: the smaller radius
    EXPECT_LE(length, 2.0 * rmax + 0.05 * rSmall + 1e-12) << "bond " << c;
    EXPECT_GT(length, 0.0);
  }

  // The output is an instantaneous stage: no time steps.
  vtkInformation* outInfo = cement->GetOutputInformation(0);
  EXPECT_FALSE(outInfo->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()));
}

TEST(Cement, ReCementingReplacesTheBondSet)
{
  vtkNew<vtkDEMPackSource> pack;
  MakePack(pack);
  vtkNew<vtkDEMCement> cement;
  cement->SetInputConnection(pack->GetOutputPort(0));
  ASSERT_TRUE(UpdateSucceeded(cement));
  const vtkIdType n = cement->GetNumberOfBonds();
  ASSERT_GT(n, 0);

  // A changed property re-cements: the same pairs, the new strength, nothing added.
  cement->SetTensileStrength(3.0e6);
  cement->SetStrengthScatter(0.2);
  ASSERT_TRUE(UpdateSucceeded(cement));
  EXPECT_EQ(cement->GetNumberOfBonds(), n);
  vtkPolyData* bonds = Block(cement, "Bonds");
  ASSERT_EQ(bonds->GetNumberOfLines(), n);
  double mean = 0.0;
  vtkDataArray* sigma = bonds->GetCellData()->GetArray("TensileStrength");
  for (vtkIdType c = 0; c < n; ++c)
  {
    mean += sigma->GetComponent(c, 0) / static_cast<double>(n);
  }
  EXPECT_NEAR(mean, 3.0e6, 0.1 * 3.0e6);
  EXPECT_GT(sigma->GetRange(0)[1] - sigma->GetRange(0)[0], 0.1 * 3.0e6) << "scatter drawn";

  // Cementing a cemented model heals it: the set is replaced, not added to.
  vtkNew<vtkDEMCement> again;
  again->SetInputConnection(cement->GetOutputPort(0));
  again->SetBondRadiusMultiplier(0.5);
  ASSERT_TRUE(UpdateSucceeded(again));
  EXPECT_EQ(again->GetNumberOfBonds(), n);
  EXPECT_EQ(Block(again, "Bonds")->GetNumberOfLines(), n);
  EXPECT_NE(std::string(again->GetLastMessage()).find("replacing"), std::string::npos)
    << again->GetLastMessage();

  // An explicit stiffness overrides the modulus for every bond.
  again->SetBondNormalStiffness(5.0e9);
  ASSERT_TRUE(UpdateSucceeded(again));
  const double* kn = Block(again, "Bonds")->GetCellData()->GetArray("NormalStiffness")->GetRange(0);
  EXPECT_EQ(kn[0], 5.0e9);
  EXPECT_EQ(kn[1], 5.0e9);
  EXPECT_EQ(again->GetBondStiffness(), 5.0e9);
}

TEST(Cement, BadParameterIsNamedAndGivesNoOutput)
{
  vtkNew<vtkDEMPackSource> pack;
  MakePack(pack);
  vtkNew<vtkDEMCement> cement;
  cement->SetInputConnection(pack->GetOutputPort(0));
  ASSERT_TRUE(UpdateSucceeded(cement));

  cement->SetBondRadiusMultiplier(1.5);
  std::string message = FailureMessage(cement);
  EXPECT_NE(message.find("Bond Radius Multiplier"), std::string::npos) << message;
  EXPECT_NE(message.find("1.5"), std::string::npos) << message;
  cement->SetBondRadiusMultiplier(1.0);

  cement->SetFrictionAngle(90.0);
  message = FailureMessage(cement);
  EXPECT_NE(message.find("Friction Angle"), std::string::npos) << message;
  cement->SetFrictionAngle(30.0);

  cement->SetTensileStrength(-1.0);
  message = FailureMessage(cement);
  EXPECT_NE(message.find("Tensile Strength"), std::string::npos) << message;
  cement->SetTensileStrength(1.0e6);

  cement->SetStrengthScatter(2.0);
  message = FailureMessage(cement);
  EXPECT_NE(message.find("Strength Scatter"), std::string::npos) << message;
  cement->SetStrengthScatter(0.0);

  // Back to valid values: it works again.
  ASSERT_TRUE(UpdateSucceeded(cement));
  EXPECT_GT(cement->GetNumberOfBonds(), 0);
}

TEST(Cement, NotAModelIsRejected)
{
  vtkNew<vtkDEMCement> cement;
  vtkNew<vtkMultiBlockDataSet> empty;
  cement->SetInputData(empty);
  const std::string message = FailureMessage(cement);
  EXPECT_NE(message.find("RockDEM model"), std::string::npos) << message;
}

// A stepped upstream model is read at its last time step; a load test downstream of the
// cement sees the bonds and, under gravity alone, breaks none.
TEST(Cement, ReadsASteppedModelAtItsLastTimeAndFeedsALoadTest)
{
  vtkNew<vtkDEMPackSource> pack;
  MakePack(pack);
  vtkNew<vtkDEMLoadTest> settle;
  settle->SetInputConnection(pack->GetOutputPort(0));
  settle->SetFrameInterval(0.002);
  settle->SetNumberOfFrames(3);
  vtkNew<vtkDEMCement> cement;
  cement->SetInputConnection(settle->GetOutputPort(0));
  cement->SetBondModulus(1.0e8);
  ASSERT_TRUE(UpdateSucceeded(cement));
  auto* mb = vtkMultiBlockDataSet::SafeDownCast(cement->GetOutputDataObject(0));
  const double time = mb->GetFieldData()->GetArray("Time")->GetComponent(0, 0);
  EXPECT_NEAR(time, 0.006, 0.0005) << "the settle's last frame";
  EXPECT_EQ(settle->GetCurrentFrame(), 3);
  EXPECT_FALSE(cement->GetOutputInformation(0)->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()));
  const vtkIdType n = cement->GetNumberOfBonds();
  ASSERT_GT(n, 0);

  vtkNew<vtkDEMLoadTest> test;
  test->SetInputConnection(cement->GetOutputPort(0));
  test->SetFrameInterval(0.002);
  test->SetNumberOfFrames(2);
  test->UpdateTimeStep(0.004);
  EXPECT_EQ(test->GetCurrentFrame(), 2);
  EXPECT_EQ(test->GetNumberOfBonds(), n);
  EXPECT_EQ(test->GetNumberOfBrokenBonds(), 0);
  EXPECT_EQ(test->GetDamage(), 0.0);
  EXPECT_EQ(Block(test, "Bonds")->GetNumberOfLines(), n);
  // The settle was not re-run for the downstream test's times.
  EXPECT_EQ(settle->GetCurrentFrame(), 3);
}
