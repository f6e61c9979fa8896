// vtkDEMPackSource: outputs, commands, Fit To Input and bad input (issue: foundation and
// the particle pack). Geometry references: sphere volume 4/3 pi r^3; porosity =
// 1 - solid volume / occupied volume (occupied up to the top of the pack).
#include "ErrorCatcher.h"

#include "vtkDEMPackSource.h"

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkTrivialProducer.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace
{
vtkPolyData* Particles(vtkDEMPackSource* src)
{
  auto* mb = vtkMultiBlockDataSet::SafeDownCast(src->GetOutputDataObject(0));
  return mb && mb->GetNumberOfBlocks() > 0 ? vtkPolyData::SafeDownCast(mb->GetBlock(0)) : nullptr;
}

/// Porosity computed from the output arrays alone: 3D spheres, gravity along -Z, box
/// without periodic Z, occupied height up to the highest sphere top.
double IndependentPorosity(vtkPolyData* pd, const double origin[3], const double size[3])
{
  vtkDataArray* r = pd->GetPointData()->GetArray("Radius");
  double solid = 0.0;
  double top = origin[2];
  for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); ++i)
  {
    const double ri = r->GetComponent(i, 0);
    solid += 4.0 / 3.0 * M_PI * ri * ri * ri;
    top = std::max(top, pd->GetPoint(i)[2] + ri);
  }
  top = std::min(top, origin[2] + size[2]);
  return 1.0 - solid / (size[0] * size[1] * (top - origin[2]));
}

std::string FailureMessage(vtkDEMPackSource* src)
{
  vtkNew<ErrorCatcher> catcher;
  src->AddObserver(vtkCommand::ErrorEvent, catcher);
  const bool ok = UpdateSucceeded(src);
  EXPECT_FALSE(ok);
  auto* mb = vtkMultiBlockDataSet::SafeDownCast(src->GetOutputDataObject(0));
  EXPECT_EQ(mb->GetNumberOfBlocks(), 0u) << "no partial output after an error";
  EXPECT_EQ(src->GetNumberOfElements(), 0);
  return catcher->All();
}
}

TEST(PackSource, BuildsTheRequestedPackAndReportsItsPorosity)
{
  vtkNew<vtkDEMPackSource> src;
  src->SetInitialElements(500);
  src->Update();
  vtkPolyData* pd = Particles(src);
  ASSERT_NE(pd, nullptr);
  EXPECT_EQ(pd->GetNumberOfPoints(), 500);
  EXPECT_EQ(src->GetNumberOfElements(), 500);
  const double origin[3] = { 0, 0, 0 };
  const double size[3] = { 0.1, 0.1, 0.1 };
  EXPECT_NEAR(src->GetCurrentPorosity(), IndependentPorosity(pd, origin, size), 1e-12);
  EXPECT_GT(src->GetContactStiffness(), 0.0);
  // kn = A E / L for two particles of the largest radius r: pi r^2 E / (2 r) (PHYSICS.md s.3).
  double rmax = 0.0;
  pd->GetPointData()->GetArray("Radius")->GetRange(0);
  rmax = pd->GetPointData()->GetArray("Radius")->GetRange(0)[1];
  EXPECT_NEAR(src->GetContactStiffness(), M_PI * rmax * 1e9 / 2.0, 1e-6 * src->GetContactStiffness());
  auto* box = vtkPolyData::SafeDownCast(src->GetOutputDataObject(1));
  ASSERT_NE(box, nullptr);
  EXPECT_EQ(box->GetNumberOfLines(), 12);
  src->ShowDomainBoxOff();
  src->Update();
  EXPECT_EQ(vtkPolyData::SafeDownCast(src->GetOutputDataObject(1))->GetNumberOfLines(), 0);
}

TEST(PackSource, SameSeedSamePackAcrossInstances)
{
  vtkNew<vtkDEMPackSource> a;
  vtkNew<vtkDEMPackSource> b;
  for (vtkDEMPackSource* s : { a.GetPointer(), b.GetPointer() })
  {
    s->SetInitialElements(400);
    s->SetRandomSeed(42);
    s->AddElements();
    s->Update();
  }
  vtkPolyData* pa = Particles(a);
  vtkPolyData* pb = Particles(b);
  ASSERT_EQ(pa->GetNumberOfPoints(), pb->GetNumberOfPoints());
  for (vtkIdType i = 0; i < pa->GetNumberOfPoints(); ++i)
  {
    ASSERT_EQ(pa->GetPoint(i)[0], pb->GetPoint(i)[0]);
    ASSERT_EQ(pa->GetPoint(i)[1], pb->GetPoint(i)[1]);
    ASSERT_EQ(pa->GetPoint(i)[2], pb->GetPoint(i)[2]);
  }
}

TEST(PackSource, AddAndGrowDensifyAndResetRebuilds)
{
  vtkNew<vtkDEMPackSource> src;
  src->SetInitialElements(300);
  src->Update();
  const double p0 = src->GetCurrentPorosity();
  const vtkIdType n0 = src->GetNumberOfElements();
  src->AddElements();
  src->Update();
  const double p1 = src->GetCurrentPorosity();
  EXPECT_GT(src->GetNumberOfElements(), n0);
  EXPECT_LT(p1, p0);
  src->GrowElements();
  src->Update();
  const double p2 = src->GetCurrentPorosity();
  EXPECT_LT(p2, p1);
  EXPECT_EQ(src->GetNumberOfCommands(), 2);

  // A material change keeps the pack (no rebuild, no re-placement).
  src->SetDensity(3000.0);
  src->Update();
  EXPECT_EQ(src->GetCurrentPorosity(), p2);

  src->ResetPack();
  src->Update();
  EXPECT_EQ(src->GetNumberOfElements(), n0);
  EXPECT_EQ(src->GetCurrentPorosity(), p0);
}

TEST(PackSource, FitToInputMatchesTheInputBounds)
{
  vtkNew<vtkPolyData> outcrop;
  vtkNew<vtkPoints> pts;
  pts->InsertNextPoint(100.0, 200.0, 10.0);
  pts->InsertNextPoint(100.5, 200.8, 10.3);
  pts->InsertNextPoint(100.2, 200.1, 10.6);
  outcrop->SetPoints(pts);

  vtkNew<vtkDEMPackSource> src;
  src->SetInputData(outcrop);
  src->SetFitToInput(1);
  src->SetInitialElements(100);
  src->SetMinimumSize(0.01);
  src->SetMaximumSize(0.02);
  src->Update();
  auto* box = vtkPolyData::SafeDownCast(src->GetOutputDataObject(1));
  double b[6];
  box->GetBounds(b);
  double in[6];
  outcrop->GetBounds(in);
  for (int k = 0; k < 6; ++k)
  {
    EXPECT_NEAR(b[k], in[k], 1e-12) << k;
  }
  vtkPolyData* pd = Particles(src);
  ASSERT_NE(pd, nullptr);
  double pb[6];
  pd->GetBounds(pb);
  EXPECT_GE(pb[0], in[0]);
  EXPECT_LE(pb[1], in[1]);
  EXPECT_GE(pb[4], in[4]);
  EXPECT_LE(pb[5], in[5]);
}

TEST(PackSource, BadInputIsReportedWithNameValueAndRangeAndNoOutput)
{
  struct Case
  {
    const char* what;
    void (*apply)(vtkDEMPackSource*);
    const char* mustContain;
  };
  const Case cases[] = {
    { "min > max", [](vtkDEMPackSource* s) { s->SetMinimumSize(0.005); s->SetMaximumSize(0.003); },
      "Minimum Size" },
    { "non-positive size", [](vtkDEMPackSource* s) { s->SetMinimumSize(-0.001); }, "Minimum Size" },
    { "zero box", [](vtkDEMPackSource* s) { s->SetYDimension(0.0); }, "Y Dimension" },
    { "porosity 1.2", [](vtkDEMPackSource* s) { s->SetTargetPorosity(1.2); }, "Target Porosity" },
    { "porosity 0", [](vtkDEMPackSource* s) { s->SetTargetPorosity(0.0); }, "Target Porosity" },
    { "box too small", [](vtkDEMPackSource* s) { s->SetXDimension(0.001); }, "X Dimension" },
    { "too many", [](vtkDEMPackSource* s) { s->SetInitialElements(2000000000); }, "Initial Elements" },
    { "NaN origin", [](vtkDEMPackSource* s) { s->SetOriginX(std::nan("")); }, "Origin X" },
    { "bad density", [](vtkDEMPackSource* s) { s->SetDensity(0.0); }, "Density" },
  };
  for (const Case& c : cases)
  {
    vtkNew<vtkDEMPackSource> src;
    c.apply(src);
    const std::string msg = FailureMessage(src);
    EXPECT_NE(msg.find(c.mustContain), std::string::npos) << c.what << ": " << msg;
  }
}

TEST(PackSource, RecoversAfterAnErrorIsFixed)
{
  vtkNew<vtkDEMPackSource> src;
  src->SetInitialElements(50);
  src->SetTargetPorosity(2.0);
  FailureMessage(src);
  src->SetTargetPorosity(0.4);
  EXPECT_TRUE(UpdateSucceeded(src));
  EXPECT_EQ(src->GetNumberOfElements(), 50);
}
