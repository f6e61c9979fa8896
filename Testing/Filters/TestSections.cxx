// vtkDEMSection, vtkDEMVoxelize and the particle stress arrays of the Particles block:
// the outputs and their arrays, the read-only values, messages and bad input, and that a
// model converted back and forth carries the same stresses (Documentation/Sections.md).
// The geometry itself is tested in the engine (Testing/Solver/TestSections.cpp).
#include "ErrorCatcher.h"

#include "vtkDEMModelConversion.h"
#include "vtkDEMSection.h"
#include "vtkDEMVoxelize.h"

#include "dem/Cement.h"
#include "dem/Pack.h"
#include "dem/ParticleStress.h"
#include "dem/Simulation.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkCellArray.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkTrivialProducer.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

namespace
{
/// A cemented pack in a 10 mm cube, stepped a little so that contacts and bonds carry
/// force, with every fifth bond broken by hand (tension, shear, inherited in turn).
dem::Model LoadedPack()
{
  dem::Model m;
  m.domain.size = dem::Vec3(0.01, 0.01, 0.01);
  m.material.youngsModulus = 1e8;
  dem::PackParameters p;
  p.initialElements = 400;
  p.minimumSize = 0.0005;
  p.maximumSize = 0.0008;
  p.randomSeed = 3;
  dem::buildPack(m, p);
  dem::growElements(m);
  dem::CementParameters c;
  c.bondModulus = 1e8;
  c.gapTolerance = 0.2;
  dem::cement(m, c);
  {
    dem::Simulation sim(m);
    sim.advance(100);
  }
  for (std::size_t k = 0; k < m.bonds.size(); k += 5)
  {
    m.bonds.markBroken(k, static_cast<dem::BondFailure>(1 + (k / 5) % 3), m.clock.time, dem::Vec3::Zero(),
      dem::Vec3::UnitZ());
  }
  return m;
}

vtkSmartPointer<vtkMultiBlockDataSet> AsVTK(const dem::Model& m)
{
  auto mb = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  rockdem::ModelToMultiBlock(m, mb);
  return mb;
}
}

// The Particles block carries Stress (6 components), MeanStress and VonMisesStress equal to
// the engine's values; a model read back from VTK (as a filter sees it) and written again
// carries the same arrays bit for bit.
TEST(ParticleStressArrays, ParticlesBlockCarriesTheStressAndAReloadShowsTheSame)
{
  const dem::Model m = LoadedPack();
  auto mb = AsVTK(m);
  auto* particles = vtkPolyData::SafeDownCast(mb->GetBlock(0));
  ASSERT_NE(particles, nullptr);
  vtkDataArray* stress = particles->GetPointData()->GetArray("Stress");
  vtkDataArray* mean = particles->GetPointData()->GetArray("MeanStress");
  vtkDataArray* vm = particles->GetPointData()->GetArray("VonMisesStress");
  ASSERT_TRUE(stress && mean && vm);
  EXPECT_EQ(stress->GetNumberOfComponents(), 6);
  const std::vector<dem::StressTensor> expected = dem::particleStresses(m);
  double largest = 0.0;
  for (vtkIdType i = 0; i < stress->GetNumberOfTuples(); ++i)
  {
    for (int q = 0; q < 6; ++q)
    {
      EXPECT_EQ(stress->GetComponent(i, q), expected[static_cast<std::size_t>(i)][q]);
    }
    EXPECT_EQ(mean->GetTuple1(i), dem::meanStress(expected[static_cast<std::size_t>(i)], false));
    EXPECT_EQ(vm->GetTuple1(i), dem::vonMisesStress(expected[static_cast<std::size_t>(i)], false));
    largest = std::max(largest, std::abs(vm->GetTuple1(i)));
  }
  EXPECT_GT(largest, 0.0) << "the particles carry stress";

  auto again = AsVTK(rockdem::MultiBlockToModel(mb));
  vtkDataArray* reloaded =
    vtkPolyData::SafeDownCast(again->GetBlock(0))->GetPointData()->GetArray("Stress");
  ASSERT_EQ(reloaded->GetNumberOfTuples(), stress->GetNumberOfTuples());
  EXPECT_EQ(std::memcmp(reloaded->GetVoidPointer(0), stress->GetVoidPointer(0),
              static_cast<std::size_t>(stress->GetNumberOfValues()) * sizeof(double)),
    0);
}

// DEM Section through the middle: polygons on the exact circles, the particle's arrays
// on each, crossing points with the bond arrays, traces with FailureMode; counts and the
// message; the plane widget's Custom normal.
TEST(SectionFilter, OutputsCarryTheParticleAndBondArrays)
{
  const dem::Model m = LoadedPack();
  auto mb = AsVTK(m);
  vtkNew<vtkDEMSection> section;
  section->SetInputDataObject(mb);
  section->SetSection(1); // XZ
  section->SetOrigin(0.005, 0.005, 0.005);
  section->SetCircleSides(20);
  ASSERT_TRUE(UpdateSucceeded(section));
  auto* circles = vtkPolyData::SafeDownCast(section->GetOutputDataObject(0));
  auto* crossings = vtkPolyData::SafeDownCast(section->GetOutputDataObject(1));
  auto* traces = vtkPolyData::SafeDownCast(section->GetOutputDataObject(2));
  ASSERT_GT(circles->GetNumberOfPolys(), 10);
  EXPECT_EQ(circles->GetNumberOfPolys(), section->GetNumberOfCutParticles());
  EXPECT_EQ(circles->GetNumberOfPoints(), 20 * circles->GetNumberOfPolys());
  for (const char* name : { "Id", "Radius", "Displacement", "Stress", "MeanStress", "VonMisesStress", "SizeClass",
         "SectionRadius", "Distance" })
  {
    EXPECT_NE(circles->GetCellData()->GetArray(name), nullptr) << name;
  }
  // Every vertex lies on its circle in the plane y = 0.005.
  vtkDataArray* radius = circles->GetCellData()->GetArray("Radius");
  vtkDataArray* sectionRadius = circles->GetCellData()->GetArray("SectionRadius");
  vtkDataArray* distance = circles->GetCellData()->GetArray("Distance");
  for (vtkIdType c = 0; c < circles->GetNumberOfPolys(); ++c)
  {
    const double r = radius->GetTuple1(c);
    const double d = distance->GetTuple1(c);
    EXPECT_NEAR(sectionRadius->GetTuple1(c), std::sqrt(r * r - d * d), 1e-15);
    double centre[3] = { 0, 0, 0 };
    for (int k = 0; k < 20; ++k)
    {
      double x[3];
      circles->GetPoint(20 * c + k, x);
      EXPECT_NEAR(x[1], 0.005, 1e-15);
      for (int a = 0; a < 3; ++a)
      {
        centre[a] += x[a] / 20.0;
      }
    }
    double x[3];
    circles->GetPoint(20 * c, x);
    EXPECT_NEAR(std::hypot(x[0] - centre[0], x[2] - centre[2]), sectionRadius->GetTuple1(c), 1e-12);
  }
  EXPECT_EQ(crossings->GetNumberOfPoints(), section->GetNumberOfCrossingBonds());
  EXPECT_GT(crossings->GetNumberOfVerts(), 0);
  EXPECT_NE(crossings->GetPointData()->GetArray("NormalForce"), nullptr);
  EXPECT_GT(traces->GetNumberOfLines(), 0);
  EXPECT_EQ(traces->GetNumberOfLines(), section->GetNumberOfTraces());
  vtkDataArray* mode = traces->GetCellData()->GetArray("FailureMode");
  ASSERT_NE(mode, nullptr);
  for (vtkIdType c = 0; c < traces->GetNumberOfLines(); ++c)
  {
    EXPECT_GE(mode->GetTuple1(c), 1.0) << "only broken bonds leave traces";
  }
  EXPECT_NE(std::string(section->GetLastMessage()).find("particles cut"), std::string::npos)
    << section->GetLastMessage();

  section->SetSection(3);
  section->SetNormal(0.0, 1.0, 0.0); // Custom with Y: the same section
  ASSERT_TRUE(UpdateSucceeded(section));
  EXPECT_EQ(vtkPolyData::SafeDownCast(section->GetOutputDataObject(0))->GetNumberOfPolys(),
    circles->GetNumberOfPolys());
}

// A plane that misses the model: empty outputs and a warning that says so, not an error;
// a bad Normal or Section: an error naming it and no output.
TEST(SectionFilter, MissingPlaneIsEmptyAndBadPlaneIsNamed)
{
  auto mb = AsVTK(LoadedPack());
  vtkNew<vtkDEMSection> section;
  section->SetInputDataObject(mb);
  section->SetOrigin(0.0, 0.0, 0.5);
  vtkNew<ErrorCatcher> warnings;
  vtkNew<ErrorCatcher> errors;
  section->AddObserver(vtkCommand::WarningEvent, warnings);
  section->AddObserver(vtkCommand::ErrorEvent, errors);
  EXPECT_TRUE(UpdateSucceeded(section));
  EXPECT_EQ(vtkPolyData::SafeDownCast(section->GetOutputDataObject(0))->GetNumberOfCells(), 0);
  EXPECT_NE(warnings->All().find("misses the model"), std::string::npos) << warnings->All();
  EXPECT_TRUE(errors->Messages.empty()) << errors->All();

  section->SetSection(3);
  section->SetNormal(0.0, 0.0, 0.0);
  EXPECT_FALSE(UpdateSucceeded(section));
  EXPECT_NE(errors->All().find("Normal = (0, 0, 0)"), std::string::npos) << errors->All();
  section->SetSection(7);
  EXPECT_FALSE(UpdateSucceeded(section));
  EXPECT_NE(errors->All().find("Section = 7"), std::string::npos) << errors->All();
  EXPECT_EQ(vtkPolyData::SafeDownCast(section->GetOutputDataObject(0))->GetNumberOfCells(), 0);
}

// DEM Voxelize: the image's grid, its arrays (one value per voxel at the voxel centres),
// solid volume = particle volume, damage consistent with the counts, and a DFN input.
TEST(VoxelizeFilter, ImageCarriesTheVoxelFields)
{
  const dem::Model m = LoadedPack();
  auto mb = AsVTK(m);
  vtkNew<vtkDEMVoxelize> voxelize;
  voxelize->SetInputDataObject(0, mb);
  voxelize->SetSizeBy(1);
  voxelize->SetNumberOfVoxels(8);
  voxelize->SetMargin(0.0);
  ASSERT_TRUE(UpdateSucceeded(voxelize));
  auto* image = vtkImageData::SafeDownCast(voxelize->GetOutputDataObject(0));
  ASSERT_NE(image, nullptr);
  int dims[3];
  image->GetDimensions(dims);
  EXPECT_EQ(std::max({ dims[0], dims[1], dims[2] }), 8);
  EXPECT_EQ(dims[0], voxelize->GetGridDimensions()[0]);
  for (const char* name : { "SolidFraction", "Bonds", "BrokenBonds", "Damage", "BrokenBondDensity", "Stress",
         "MeanStress", "DeviatoricStress", "Displacement" })
  {
    vtkDataArray* a = image->GetPointData()->GetArray(name);
    ASSERT_NE(a, nullptr) << name;
    EXPECT_EQ(a->GetNumberOfTuples(), image->GetNumberOfPoints()) << name;
  }
  EXPECT_EQ(image->GetPointData()->GetArray("Stress")->GetNumberOfComponents(), 6);
  const double* h = image->GetSpacing();
  double solid = 0.0;
  vtkDataArray* fraction = image->GetPointData()->GetArray("SolidFraction");
  for (vtkIdType v = 0; v < fraction->GetNumberOfTuples(); ++v)
  {
    solid += fraction->GetTuple1(v) * h[0] * h[1] * h[2];
  }
  double particles = 0.0;
  for (double r : m.particles.radius)
  {
    particles += dem::particleVolume(m.domain, r);
  }
  EXPECT_NEAR(solid, particles, 1e-10 * particles);
  EXPECT_NEAR(voxelize->GetSolidVolume(), particles, 1e-10 * particles);
  EXPECT_EQ(image->GetPointData()->GetArray("FractureIntensity"), nullptr) << "no DFN, no fracture arrays";

  // A DFN: one square quad through the middle, Set 1.
  vtkNew<vtkPolyData> dfn;
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(-1.0, -1.0, 0.0051);
  points->InsertNextPoint(1.0, -1.0, 0.0051);
  points->InsertNextPoint(1.0, 1.0, 0.0051);
  points->InsertNextPoint(-1.0, 1.0, 0.0051);
  vtkNew<vtkCellArray> polys;
  const vtkIdType quad[4] = { 0, 1, 2, 3 };
  polys->InsertNextCell(4, quad);
  dfn->SetPoints(points);
  dfn->SetPolys(polys);
  vtkNew<vtkIntArray> set;
  set->SetName("Set");
  set->InsertNextValue(1);
  dfn->GetCellData()->AddArray(set);
  voxelize->SetInputDataObject(1, dfn);
  ASSERT_TRUE(UpdateSucceeded(voxelize));
  image = vtkImageData::SafeDownCast(voxelize->GetOutputDataObject(0));
  vtkDataArray* p32 = image->GetPointData()->GetArray("FractureIntensity");
  vtkDataArray* fset = image->GetPointData()->GetArray("FractureSet");
  ASSERT_TRUE(p32 && fset);
  double area = 0.0;
  int tagged = 0;
  for (vtkIdType v = 0; v < p32->GetNumberOfTuples(); ++v)
  {
    area += p32->GetTuple1(v) * h[0] * h[1] * h[2];
    tagged += fset->GetTuple1(v) == 1.0 ? 1 : 0;
  }
  const double width = dims[0] * h[0];
  const double depth = dims[1] * h[1];
  EXPECT_NEAR(area, width * depth, 1e-12 * width * depth) << "the square's part inside the grid";
  EXPECT_NEAR(voxelize->GetFractureArea(), width * depth, 1e-12 * width * depth);
  EXPECT_EQ(tagged, dims[0] * dims[1]) << "one layer of voxels holds the fracture, Set 1";
}

// Voxel Size <= 0 and a grid over the Memory Limit: errors naming value and limit, no
// output.
TEST(VoxelizeFilter, BadSizeAndMemoryLimitAreNamed)
{
  auto mb = AsVTK(LoadedPack());
  vtkNew<vtkDEMVoxelize> voxelize;
  voxelize->SetInputDataObject(0, mb);
  vtkNew<ErrorCatcher> errors;
  voxelize->AddObserver(vtkCommand::ErrorEvent, errors);
  voxelize->SetSizeBy(0);
  voxelize->SetVoxelSize(0.0);
  EXPECT_FALSE(UpdateSucceeded(voxelize));
  EXPECT_NE(errors->All().find("Voxel Size = 0 m"), std::string::npos) << errors->All();
  EXPECT_EQ(vtkImageData::SafeDownCast(voxelize->GetOutputDataObject(0))->GetNumberOfPoints(), 0);
  voxelize->SetVoxelSize(1e-6);
  EXPECT_FALSE(UpdateSucceeded(voxelize));
  EXPECT_NE(errors->All().find("the Memory Limit is 2048 MiB"), std::string::npos) << errors->All();
  EXPECT_NE(std::string(voxelize->GetLastMessage()).find("Voxel Size = 1e-06 m"), std::string::npos);
  EXPECT_EQ(voxelize->GetGridDimensions()[0], 0);
}

// A 2D section model is its own section: every disc in the model plane, whatever the
// Section settings, the intact bonds at their contact points, the broken ones as segments.
TEST(SectionFilter, TwoDimensionalModelIsDrawnAsItsDiscs)
{
  dem::Model m;
  m.domain.section2D = true;
  m.domain.size = dem::Vec3(0.02, 0.01, 0.001);
  m.gravity = dem::Vec3(0.0, -9.81, 0.0);
  for (int i = 0; i < 6; ++i)
  {
    m.particles.append(dem::Vec3(0.002 + 0.0029 * i, 0.005, m.domain.midPlaneZ()), 0.0015, i);
  }
  m.nextId = 6;
  dem::updateMassProperties(m);
  dem::CementParameters c;
  c.gapTolerance = 0.1;
  dem::cement(m, c);
  ASSERT_EQ(m.bonds.size(), 5u);
  m.bonds.markBroken(2, dem::BondFailure::Shear, 0.0, dem::Vec3::Zero(), dem::Vec3::UnitX());
  auto mb = AsVTK(m);
  vtkNew<vtkDEMSection> section;
  section->SetInputDataObject(mb);
  section->SetSection(2); // YZ: not used in 2D
  section->SetCircleSides(16);
  ASSERT_TRUE(UpdateSucceeded(section));
  auto* circles = vtkPolyData::SafeDownCast(section->GetOutputDataObject(0));
  EXPECT_EQ(circles->GetNumberOfPolys(), 6);
  double bounds[6];
  circles->GetBounds(bounds);
  EXPECT_NEAR(bounds[4], m.domain.midPlaneZ(), 1e-15);
  EXPECT_NEAR(bounds[5], m.domain.midPlaneZ(), 1e-15);
  EXPECT_NEAR(bounds[0], 0.002 - 0.0015, 1e-12);
  EXPECT_EQ(vtkPolyData::SafeDownCast(section->GetOutputDataObject(1))->GetNumberOfPoints(), 4);
  auto* traces = vtkPolyData::SafeDownCast(section->GetOutputDataObject(2));
  ASSERT_EQ(traces->GetNumberOfLines(), 1);
  traces->GetBounds(bounds); // a segment across the bond (along Y), of the bond's diameter
  EXPECT_NEAR(bounds[1] - bounds[0], 0.0, 1e-12);
  EXPECT_NEAR(bounds[3] - bounds[2], 2.0 * m.bonds.radius[2], 1e-12);
  EXPECT_NE(std::string(section->GetLastMessage()).find("2D section model is its own section"), std::string::npos);
}
