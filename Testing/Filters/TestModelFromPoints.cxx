// vtkDEMModelFromPoints: any point set with a Radius array becomes a model.
#include "ErrorCatcher.h"

#include "vtkDEMModelConversion.h"
#include "vtkDEMModelFromPoints.h"

#include "dem/Model.h"

#include <vtkDoubleArray.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <cmath>

namespace
{
/// Two spheres of radius 1 cm, 3 cm apart along X, approaching at 1 m/s each.
vtkSmartPointer<vtkPolyData> TwoSpheres()
{
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->InsertNextPoint(0.0, 0.0, 0.0);
  pts->InsertNextPoint(0.03, 0.0, 0.0);
  pd->SetPoints(pts);
  vtkNew<vtkDoubleArray> r;
  r->SetName("Radius");
  r->InsertNextValue(0.01);
  r->InsertNextValue(0.01);
  pd->GetPointData()->AddArray(r);
  vtkNew<vtkDoubleArray> v;
  v->SetName("Velocity");
  v->SetNumberOfComponents(3);
  v->InsertNextTuple3(1.0, 0.0, 0.0);
  v->InsertNextTuple3(-1.0, 0.0, 0.0);
  pd->GetPointData()->AddArray(v);
  vtkNew<vtkDoubleArray> fixed;
  fixed->SetName("Fixed");
  fixed->InsertNextValue(0.0);
  fixed->InsertNextValue(1.0);
  pd->GetPointData()->AddArray(fixed);
  return pd;
}

std::string Failure(vtkPolyData* input)
{
  vtkNew<vtkDEMModelFromPoints> f;
  f->SetInputData(input);
  vtkNew<ErrorCatcher> catcher;
  f->AddObserver(vtkCommand::ErrorEvent, catcher);
  EXPECT_FALSE(UpdateSucceeded(f));
  EXPECT_EQ(vtkMultiBlockDataSet::SafeDownCast(f->GetOutputDataObject(0))->GetNumberOfBlocks(), 0u);
  return catcher->All();
}
}

TEST(ModelFromPoints, TwoSpheresAboutToCollide)
{
  vtkNew<vtkDEMModelFromPoints> f;
  f->SetInputData(TwoSpheres());
  f->SetDensity(2800.0);
  ASSERT_TRUE(UpdateSucceeded(f));
  const dem::Model m =
    rockdem::MultiBlockToModel(vtkMultiBlockDataSet::SafeDownCast(f->GetOutputDataObject(0)));
  ASSERT_EQ(m.particles.size(), 2u);
  EXPECT_EQ(m.particles.velocity[0], dem::Vec3(1.0, 0.0, 0.0));
  EXPECT_EQ(m.particles.velocity[1], dem::Vec3(-1.0, 0.0, 0.0));
  EXPECT_FALSE(m.particles.flags[0] & dem::FlagFixed);
  EXPECT_TRUE(m.particles.flags[1] & dem::FlagFixed);
  // Sphere mass rho 4/3 pi r^3.
  EXPECT_NEAR(m.particles.mass[0], 2800.0 * 4.0 / 3.0 * M_PI * 1e-6, 1e-15);
  EXPECT_EQ(m.material.density, 2800.0);
  // Fit To Input: the box is the bounding box of the spheres.
  EXPECT_NEAR(m.domain.origin.x(), -0.01, 1e-15);
  EXPECT_NEAR(m.domain.size.x(), 0.05, 1e-15);
  EXPECT_NEAR(m.domain.size.y(), 0.02, 1e-15);
}

TEST(ModelFromPoints, TwoDimensionalDiscsSitAtMidPlane)
{
  vtkNew<vtkDEMModelFromPoints> f;
  f->SetInputData(TwoSpheres());
  f->SetSection2D(1);
  f->SetZDimension(0.005);
  ASSERT_TRUE(UpdateSucceeded(f));
  const dem::Model m =
    rockdem::MultiBlockToModel(vtkMultiBlockDataSet::SafeDownCast(f->GetOutputDataObject(0)));
  EXPECT_TRUE(m.domain.section2D);
  EXPECT_NEAR(m.domain.size.z(), 0.005, 1e-15);
  EXPECT_EQ(m.particles.position[0].z(), m.domain.midPlaneZ());
  // Disc through the slab: rho pi r^2 t.
  EXPECT_NEAR(m.particles.mass[0], 2650.0 * M_PI * 1e-4 * 0.005, 1e-12);
}

TEST(ModelFromPoints, MissingRadiusIsAnError)
{
  auto pd = TwoSpheres();
  pd->GetPointData()->RemoveArray("Radius");
  EXPECT_NE(Failure(pd).find("Radius"), std::string::npos);
}

TEST(ModelFromPoints, NanCoordinateIsAnError)
{
  auto pd = TwoSpheres();
  pd->GetPoints()->SetPoint(1, std::nan(""), 0.0, 0.0);
  const std::string msg = Failure(pd);
  EXPECT_NE(msg.find("point 1"), std::string::npos) << msg;
  EXPECT_NE(msg.find("finite"), std::string::npos) << msg;
}

TEST(ModelFromPoints, NonPositiveRadiusIsAnError)
{
  auto pd = TwoSpheres();
  vtkDoubleArray::SafeDownCast(pd->GetPointData()->GetArray("Radius"))->SetValue(0, -0.5);
  const std::string msg = Failure(pd);
  EXPECT_NE(msg.find("Radius"), std::string::npos) << msg;
  EXPECT_NE(msg.find("-0.5"), std::string::npos) << msg;
}

TEST(ModelFromPoints, PointOutsideAnExplicitBoxIsAnError)
{
  vtkNew<vtkDEMModelFromPoints> f;
  f->SetInputData(TwoSpheres());
  f->SetFitToInput(0);
  f->SetOriginX(0.0);
  f->SetXDimension(0.02);
  f->SetOriginY(-0.05);
  f->SetOriginZ(-0.05);
  vtkNew<ErrorCatcher> catcher;
  f->AddObserver(vtkCommand::ErrorEvent, catcher);
  EXPECT_FALSE(UpdateSucceeded(f));
  EXPECT_NE(catcher->All().find("outside the model box"), std::string::npos) << catcher->All();
}
