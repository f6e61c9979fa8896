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
#include <cstdio>
#include <vector>

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

// Spatial Order (default on): the particles come out along the Morton curve of
// dem::spatialOrder, each with its input point index as its Id and that point's centre,
// radius and velocity; Off keeps the input order. Input: a 6 x 6 x 6 lattice of 1 mm
// spheres, 2.5 mm apart, listed in a scrambled order (index p at lattice site 97 p mod 216).
TEST(ModelFromPoints, SpatialOrderStoresTheParticlesAlongACurveAndKeepsTheirIds)
{
  constexpr int side = 6;
  constexpr int count = side * side * side;
  vtkNew<vtkPolyData> pd;
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  vtkNew<vtkDoubleArray> r;
  r->SetName("Radius");
  vtkNew<vtkDoubleArray> v;
  v->SetName("Velocity");
  v->SetNumberOfComponents(3);
  for (int p = 0; p < count; ++p)
  {
    const int site = (97 * p) % count; // 97 and 216 are coprime: every site once
    pts->InsertNextPoint(0.0025 * (site % side), 0.0025 * ((site / side) % side), 0.0025 * (site / (side * side)));
    r->InsertNextValue(0.001 + 1e-6 * p);
    v->InsertNextTuple3(p, -p, 0.5 * p);
  }
  pd->SetPoints(pts);
  pd->GetPointData()->AddArray(r);
  pd->GetPointData()->AddArray(v);

  auto modelOf = [&](bool spatial) {
    vtkNew<vtkDEMModelFromPoints> f;
    f->SetInputData(pd);
    f->SetSpatialOrder(spatial);
    EXPECT_TRUE(UpdateSucceeded(f));
    return rockdem::MultiBlockToModel(vtkMultiBlockDataSet::SafeDownCast(f->GetOutputDataObject(0)));
  };
  const dem::Model inputOrder = modelOf(false);
  const dem::Model spatial = modelOf(true);
  ASSERT_EQ(inputOrder.particles.size(), static_cast<std::size_t>(count));
  ASSERT_EQ(spatial.particles.size(), static_cast<std::size_t>(count));

  // Off: slot s is input point s.
  std::vector<std::size_t> identity(count);
  for (std::size_t s = 0; s < identity.size(); ++s)
  {
    identity[s] = s;
    EXPECT_EQ(inputOrder.particles.id[s], static_cast<std::int64_t>(s));
  }
  // On: slot s holds the particle that dem::spatialOrder puts there, with all its data,
  // and the order is not the input's.
  const std::vector<std::size_t> order = dem::spatialOrder(inputOrder);
  ASSERT_NE(order, identity);
  for (std::size_t s = 0; s < order.size(); ++s)
  {
    const std::size_t input = order[s];
    EXPECT_EQ(spatial.particles.id[s], static_cast<std::int64_t>(input));
    EXPECT_EQ(spatial.particles.position[s], inputOrder.particles.position[input]);
    EXPECT_EQ(spatial.particles.radius[s], inputOrder.particles.radius[input]);
    EXPECT_EQ(spatial.particles.velocity[s], inputOrder.particles.velocity[input]);
    EXPECT_EQ(spatial.particles.mass[s], inputOrder.particles.mass[input]);
  }
  // Neighbours in space are near in the list: the mean distance between consecutive
  // slots, in lattice spacings, is small along the curve and large in the scrambled input.
  auto meanStep = [](const dem::Model& m) {
    double sum = 0.0;
    for (std::size_t s = 1; s < m.particles.size(); ++s)
    {
      sum += (m.particles.position[s] - m.particles.position[s - 1]).norm() / 0.0025;
    }
    return sum / static_cast<double>(m.particles.size() - 1);
  };
  std::printf("[spatial order] mean step between consecutive slots: %.2f spacings along the curve, %.2f in "
              "the input's order\n", meanStep(spatial), meanStep(inputOrder));
  EXPECT_LT(meanStep(spatial), 2.0);
  EXPECT_GT(meanStep(inputOrder), 4.0);
  EXPECT_EQ(spatial.domain.origin, inputOrder.domain.origin);
  EXPECT_EQ(spatial.domain.size, inputOrder.domain.size);
}
