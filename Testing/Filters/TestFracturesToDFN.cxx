// vtkDEMFracturesToDFN and vtkDEMSeedFractures: the disc polydata and its cell arrays,
// the summary table, the read-only counts, the messages, bad input, and seeding through
// the pipeline (reference guide "Exporting fractures to a DFN"; issue "Fractures to DFN").
// The geometry itself is tested in the engine (Testing/Solver/TestFractures.cpp).
#include "ErrorCatcher.h"

#include "vtkDEMFracturesToDFN.h"
#include "vtkDEMModelConversion.h"
#include "vtkDEMSeedFractures.h"

#include "dem/Cement.h"
#include "dem/Fractures.h"
#include "dem/Pack.h"
#include "dem/SeedFractures.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkTable.h>

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <unordered_map>

namespace
{
/// A grown pack in a 24 mm cube, cemented with a generous gap tolerance (geometry only).
dem::Model CementedPack()
{
  dem::Model m;
  m.domain.size = dem::Vec3(0.024, 0.024, 0.024);
  dem::PackParameters p;
  p.initialElements = 6000;
  p.minimumSize = 0.0005;
  p.maximumSize = 0.00075;
  p.randomSeed = 7;
  dem::buildPack(m, p);
  dem::growElements(m);
  dem::CementParameters c;
  c.gapTolerance = 0.6;
  dem::cement(m, c);
  return m;
}

/// Breaks the bonds crossing the plane through the box centre with (dip, azimuth).
std::size_t BreakAcross(dem::Model& m, double dip, double az, dem::BondFailure mode)
{
  std::unordered_map<std::int64_t, std::size_t> slot;
  for (std::size_t i = 0; i < m.particles.size(); ++i)
  {
    slot[m.particles.id[i]] = i;
  }
  const dem::Vec3 n = dem::normalFromDipAzimuth(dip, az);
  const dem::Vec3 x0 = m.domain.origin + 0.5 * m.domain.size;
  std::size_t count = 0;
  for (std::size_t k = 0; k < m.bonds.size(); ++k)
  {
    const dem::Vec3& a = m.particles.position[slot.at(m.bonds.idA[k])];
    const dem::Vec3& b = m.particles.position[slot.at(m.bonds.idB[k])];
    if (m.bonds.broken(k) || (n.dot(a - x0) > 0) == (n.dot(b - x0) > 0))
    {
      continue;
    }
    m.bonds.failure[k] = static_cast<std::uint8_t>(mode);
    m.bonds.failurePosition[k] = 0.5 * (a + b);
    m.bonds.failureNormal[k] = (b - a).normalized();
    ++count;
  }
  return count;
}

vtkPolyData* Bonds(vtkMultiBlockDataSet* mb)
{
  for (unsigned int k = 0; mb && k < mb->GetNumberOfBlocks(); ++k)
  {
    if (mb->HasMetaData(k) && std::string(mb->GetMetaData(k)->Get(vtkCompositeDataSet::NAME())) == "Bonds")
    {
      return vtkPolyData::SafeDownCast(mb->GetBlock(k));
    }
  }
  return nullptr;
}
}

TEST(FracturesToDFN, DiscsSummaryTableAndCounts)
{
  dem::Model m = CementedPack();
  const std::size_t tensile = BreakAcross(m, 40, 130, dem::BondFailure::Tension);
  const std::size_t shear = BreakAcross(m, 75, 300, dem::BondFailure::Shear);
  vtkNew<vtkMultiBlockDataSet> mb;
  rockdem::ModelToMultiBlock(m, mb);

  vtkNew<vtkDEMFracturesToDFN> dfn;
  dfn->SetInputData(mb);
  dfn->SetDiscSides(16);
  ASSERT_TRUE(UpdateSucceeded(dfn));
  auto* discs = vtkPolyData::SafeDownCast(dfn->GetOutputDataObject(0));
  auto* table = vtkTable::SafeDownCast(dfn->GetOutputDataObject(1));
  ASSERT_NE(discs, nullptr);
  ASSERT_NE(table, nullptr) << "port 1 is a vtkTable";
  ASSERT_EQ(discs->GetNumberOfPolys(), 2);
  EXPECT_EQ(discs->GetNumberOfPoints(), 32);
  EXPECT_EQ(dfn->GetNumberOfBrokenBonds(), static_cast<vtkIdType>(tensile + shear));
  EXPECT_EQ(dfn->GetNumberOfClusters(), 2);
  EXPECT_EQ(dfn->GetNumberOfDiscs(), 2);
  EXPECT_EQ(dfn->GetNumberOfTensileDiscs(), 1);
  EXPECT_EQ(dfn->GetNumberOfShearDiscs(), 1);
  EXPECT_EQ(dfn->GetNumberOfInheritedDiscs(), 0);
  EXPECT_EQ(dfn->GetRejectedTooSmall() + dfn->GetRejectedNonPlanar() + dfn->GetRejectedSparse(), 0);
  EXPECT_NEAR(dfn->GetUsedClusterDistance(), 2.0 * dem::meanParticleDiameter(m), 1e-15);
  const std::string message = dfn->GetLastMessage();
  EXPECT_NE(message.find("Tensile set: " + std::to_string(tensile) + " broken bonds"), std::string::npos) << message;
  EXPECT_NE(message.find("Shear set: " + std::to_string(shear) + " broken bonds"), std::string::npos) << message;

  vtkCellData* cd = discs->GetCellData();
  for (const char* name :
    { "Dip", "Azimuth", "Set", "Radius", "Area", "Normal", "Center", "CrackCount", "Planarity", "Fill" })
  {
    ASSERT_NE(cd->GetArray(name), nullptr) << name;
    EXPECT_EQ(cd->GetArray(name)->GetNumberOfTuples(), 2) << name;
  }
  auto* setName = vtkStringArray::SafeDownCast(cd->GetAbstractArray("SetName"));
  ASSERT_NE(setName, nullptr);
  // Discs are ordered by set: tensile first.
  EXPECT_EQ(cd->GetArray("Set")->GetTuple1(0), 0.0);
  EXPECT_EQ(cd->GetArray("Set")->GetTuple1(1), 1.0);
  EXPECT_EQ(setName->GetValue(0), "Tensile");
  EXPECT_EQ(setName->GetValue(1), "Shear");
  EXPECT_NEAR(cd->GetArray("Dip")->GetTuple1(0), 40.0, 2.0);
  EXPECT_NEAR(cd->GetArray("Azimuth")->GetTuple1(0), 130.0, 3.0);
  EXPECT_NEAR(cd->GetArray("Dip")->GetTuple1(1), 75.0, 2.0);
  EXPECT_NEAR(cd->GetArray("Azimuth")->GetTuple1(1), 300.0, 3.0);
  EXPECT_EQ(cd->GetArray("CrackCount")->GetTuple1(0), static_cast<double>(tensile));
  EXPECT_EQ(cd->GetArray("CrackCount")->GetTuple1(1), static_cast<double>(shear));
  EXPECT_GT(cd->GetArray("Fill")->GetRange(0)[0], 0.9) << "planted planes are fully broken";
  for (vtkIdType c = 0; c < 2; ++c)
  {
    const double r = cd->GetArray("Radius")->GetTuple1(c);
    EXPECT_NEAR(cd->GetArray("Area")->GetTuple1(c), M_PI * r * r, 1e-12);
    const double* n = cd->GetArray("Normal")->GetTuple3(c);
    EXPECT_NEAR(std::acos(n[2]) * 180.0 / M_PI, cd->GetArray("Dip")->GetTuple1(c), 1e-9) << "Dip = arccos(nz)";
    // Every vertex of the polygon lies at Radius from Center, in the plane.
    const double* x0 = cd->GetArray("Center")->GetTuple3(c);
    const double centre[3] = { x0[0], x0[1], x0[2] };
    const double normal[3] = { n[0], n[1], n[2] };
    vtkIdType npts = 0;
    const vtkIdType* ids = nullptr;
    discs->GetCellPoints(c, npts, ids);
    ASSERT_EQ(npts, 16);
    for (vtkIdType k = 0; k < npts; ++k)
    {
      double x[3];
      discs->GetPoint(ids[k], x);
      double d2 = 0, dn = 0;
      for (int j = 0; j < 3; ++j)
      {
        d2 += (x[j] - centre[j]) * (x[j] - centre[j]);
        dn += (x[j] - centre[j]) * normal[j];
      }
      EXPECT_NEAR(std::sqrt(d2), r, 1e-12);
      EXPECT_NEAR(dn, 0.0, 1e-12);
    }
  }

  // The summary table: one row per disc, the columns the CSV needs, the same values.
  ASSERT_EQ(table->GetNumberOfRows(), 2);
  const char* columns[] = { "CenterX", "CenterY", "CenterZ", "NormalX", "NormalY", "NormalZ", "Dip", "Azimuth",
    "Radius", "Area", "Set", "SetName", "CrackCount", "Planarity", "Fill" };
  ASSERT_EQ(table->GetNumberOfColumns(), 15);
  for (int k = 0; k < 15; ++k)
  {
    EXPECT_EQ(std::string(table->GetColumnName(k)), columns[k]);
  }
  for (vtkIdType r = 0; r < 2; ++r)
  {
    EXPECT_EQ(table->GetValueByName(r, "Dip").ToDouble(), cd->GetArray("Dip")->GetTuple1(r));
    EXPECT_EQ(table->GetValueByName(r, "Azimuth").ToDouble(), cd->GetArray("Azimuth")->GetTuple1(r));
    EXPECT_EQ(table->GetValueByName(r, "CenterY").ToDouble(), cd->GetArray("Center")->GetComponent(r, 1));
    EXPECT_EQ(table->GetValueByName(r, "NormalZ").ToDouble(), cd->GetArray("Normal")->GetComponent(r, 2));
    EXPECT_EQ(table->GetValueByName(r, "SetName").ToString(), setName->GetValue(r));
  }
}

TEST(FracturesToDFN, NothingEmittedSaysWhy)
{
  dem::Model m = CementedPack();
  vtkNew<vtkMultiBlockDataSet> mb;
  rockdem::ModelToMultiBlock(m, mb);
  vtkNew<vtkDEMFracturesToDFN> dfn;
  dfn->SetInputData(mb);
  vtkNew<ErrorCatcher> warnings;
  dfn->AddObserver(vtkCommand::WarningEvent, warnings);
  ASSERT_TRUE(UpdateSucceeded(dfn));
  EXPECT_EQ(vtkPolyData::SafeDownCast(dfn->GetOutputDataObject(0))->GetNumberOfCells(), 0);
  EXPECT_EQ(vtkTable::SafeDownCast(dfn->GetOutputDataObject(1))->GetNumberOfRows(), 0);
  EXPECT_EQ(dfn->GetNumberOfBrokenBonds(), 0);
  EXPECT_NE(warnings->All().find("no broken bonds"), std::string::npos) << warnings->All();

  // Scattered damage: clusters found, every one rejected, and the warning says so.
  for (std::size_t k = 0; k < m.bonds.size(); k += 20)
  {
    m.bonds.failure[k] = static_cast<std::uint8_t>(dem::BondFailure::Tension);
  }
  rockdem::ModelToMultiBlock(m, mb);
  dfn->Modified();
  warnings->Messages.clear();
  ASSERT_TRUE(UpdateSucceeded(dfn));
  EXPECT_EQ(dfn->GetNumberOfDiscs(), 0);
  EXPECT_GT(dfn->GetNumberOfClusters(), 0);
  EXPECT_EQ(dfn->GetRejectedTooSmall() + dfn->GetRejectedNonPlanar(), dfn->GetNumberOfClusters());
  EXPECT_NE(warnings->All().find("every cluster of broken bonds was rejected"), std::string::npos) << warnings->All();
}

TEST(FracturesToDFN, BadParameterIsNamedAndGivesNoOutput)
{
  dem::Model m = CementedPack();
  BreakAcross(m, 30, 30, dem::BondFailure::Tension);
  vtkNew<vtkMultiBlockDataSet> mb;
  rockdem::ModelToMultiBlock(m, mb);
  vtkNew<vtkDEMFracturesToDFN> dfn;
  dfn->SetInputData(mb);
  ASSERT_TRUE(UpdateSucceeded(dfn));
  ASSERT_EQ(dfn->GetNumberOfDiscs(), 1);
  for (int bad = 0; bad < 5; ++bad)
  {
    vtkNew<vtkDEMFracturesToDFN> f;
    f->SetInputData(mb);
    const char* name = bad == 0 ? "Minimum Cracks"
      : bad == 1                ? "Minimum Planarity"
      : bad == 2                ? "Cluster Distance"
      : bad == 3                ? "Orientation Tolerance = 90 degrees"
                                : "Band Significance = -1 standard deviations";
    if (bad == 0)
    {
      f->SetMinimumCracks(2);
    }
    else if (bad == 1)
    {
      f->SetMinimumPlanarity(-0.1);
      f->SetMinimumFill(0.5); // valid: the error names the bad one
    }
    else if (bad == 2)
    {
      f->SetClusterDistance(-1.0);
    }
    else if (bad == 3)
    {
      f->SetOrientationTolerance(90.0); // the property reaches the engine's validation
    }
    else
    {
      f->SetBandSignificance(-1.0);
    }
    vtkNew<ErrorCatcher> errors;
    f->AddObserver(vtkCommand::ErrorEvent, errors);
    EXPECT_FALSE(UpdateSucceeded(f));
    EXPECT_NE(errors->All().find(name), std::string::npos) << errors->All();
    EXPECT_NE(std::string(f->GetLastMessage()).find(name), std::string::npos);
    EXPECT_EQ(vtkPolyData::SafeDownCast(f->GetOutputDataObject(0))->GetNumberOfCells(), 0);
    EXPECT_EQ(vtkTable::SafeDownCast(f->GetOutputDataObject(1))->GetNumberOfRows(), 0);
    EXPECT_EQ(f->GetNumberOfDiscs(), 0);
  }
}

// Seeding through the pipeline: a quad and a triangle strip; the bonds broken are those
// the engine breaks for the same polygons, with FailureMode 3; exported again, the seeded
// quad comes back as an inherited disc.
TEST(SeedFracturesFilter, PipelineSeedsAndExportsAgain)
{
  const dem::Model m = CementedPack();
  vtkNew<vtkMultiBlockDataSet> mb;
  rockdem::ModelToMultiBlock(m, mb);

  vtkNew<vtkPolyData> fractures;
  vtkNew<vtkPoints> points;
  // A horizontal quad through the middle, 16 mm square.
  points->InsertNextPoint(0.004, 0.004, 0.012);
  points->InsertNextPoint(0.020, 0.004, 0.012);
  points->InsertNextPoint(0.020, 0.020, 0.012);
  points->InsertNextPoint(0.004, 0.020, 0.012);
  // A vertical triangle strip (two triangles) near the X- side, below the quad.
  points->InsertNextPoint(0.003, 0.002, 0.002);
  points->InsertNextPoint(0.003, 0.002, 0.008);
  points->InsertNextPoint(0.003, 0.010, 0.002);
  points->InsertNextPoint(0.003, 0.010, 0.008);
  fractures->SetPoints(points);
  vtkNew<vtkCellArray> polys;
  const vtkIdType quad[4] = { 0, 1, 2, 3 };
  polys->InsertNextCell(4, quad);
  fractures->SetPolys(polys);
  vtkNew<vtkCellArray> strips;
  const vtkIdType strip[4] = { 4, 5, 6, 7 };
  strips->InsertNextCell(4, strip);
  fractures->SetStrips(strips);

  vtkNew<vtkDEMSeedFractures> seed;
  seed->SetInputData(0, mb);
  seed->SetInputData(1, fractures);
  ASSERT_TRUE(UpdateSucceeded(seed));
  EXPECT_EQ(seed->GetNumberOfPolygons(), 3);

  dem::Model expected = m;
  const dem::SeedReport report = dem::seedFractures(expected,
    { { dem::Vec3(0.004, 0.004, 0.012), dem::Vec3(0.020, 0.004, 0.012), dem::Vec3(0.020, 0.020, 0.012),
        dem::Vec3(0.004, 0.020, 0.012) },
      { dem::Vec3(0.003, 0.002, 0.002), dem::Vec3(0.003, 0.002, 0.008), dem::Vec3(0.003, 0.010, 0.002) },
      { dem::Vec3(0.003, 0.002, 0.008), dem::Vec3(0.003, 0.010, 0.002), dem::Vec3(0.003, 0.010, 0.008) } });
  ASSERT_GT(report.seeded, 50u);
  EXPECT_EQ(seed->GetNumberOfSeededBonds(), static_cast<vtkIdType>(report.seeded));
  EXPECT_NE(std::string(seed->GetLastMessage()).find(std::to_string(report.seeded)), std::string::npos);

  auto* out = vtkMultiBlockDataSet::SafeDownCast(seed->GetOutputDataObject(0));
  vtkPolyData* bonds = Bonds(out);
  ASSERT_NE(bonds, nullptr);
  vtkDataArray* mode = bonds->GetCellData()->GetArray("FailureMode");
  vtkDataArray* broken = bonds->GetCellData()->GetArray("Broken");
  ASSERT_EQ(mode->GetNumberOfTuples(), static_cast<vtkIdType>(m.bonds.size()));
  std::size_t mismatches = 0;
  for (vtkIdType c = 0; c < mode->GetNumberOfTuples(); ++c)
  {
    mismatches += mode->GetTuple1(c) != expected.bonds.failure[static_cast<std::size_t>(c)];
    if (mode->GetTuple1(c) == 3.0)
    {
      EXPECT_EQ(broken->GetTuple1(c), 1.0) << "inherited bonds are broken";
    }
  }
  EXPECT_EQ(mismatches, 0u);
  // The round trip keeps the mode: the model read back has the inherited bonds.
  EXPECT_EQ(dem::countBonds(rockdem::MultiBlockToModel(out).bonds).inherited, report.seeded);

  vtkNew<vtkDEMFracturesToDFN> dfn;
  dfn->SetInputConnection(seed->GetOutputPort());
  ASSERT_TRUE(UpdateSucceeded(dfn));
  EXPECT_GE(dfn->GetNumberOfInheritedDiscs(), 1);
  auto* discs = vtkPolyData::SafeDownCast(dfn->GetOutputDataObject(0));
  ASSERT_GE(discs->GetNumberOfCells(), 1);
  // The largest inherited disc is the quad: horizontal, at z = 12 mm.
  EXPECT_EQ(discs->GetCellData()->GetArray("Set")->GetTuple1(0), 2.0);
  EXPECT_LT(discs->GetCellData()->GetArray("Dip")->GetTuple1(0), 2.0);
  EXPECT_NEAR(discs->GetCellData()->GetArray("Center")->GetComponent(0, 2), 0.012, 2.0 * dem::meanParticleDiameter(m) / 2);
}

TEST(SeedFracturesFilter, BadFracturesAreNamedAndGiveNoOutput)
{
  const dem::Model m = CementedPack();
  vtkNew<vtkMultiBlockDataSet> mb;
  rockdem::ModelToMultiBlock(m, mb);
  vtkNew<vtkPolyData> lines; // points but no polygons
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(1, 0, 0);
  lines->SetPoints(points);
  vtkNew<vtkDEMSeedFractures> seed;
  seed->SetInputData(0, mb);
  seed->SetInputData(1, lines);
  vtkNew<ErrorCatcher> errors;
  seed->AddObserver(vtkCommand::ErrorEvent, errors);
  EXPECT_FALSE(UpdateSucceeded(seed));
  EXPECT_NE(errors->All().find("has no polygons"), std::string::npos) << errors->All();
  EXPECT_EQ(vtkMultiBlockDataSet::SafeDownCast(seed->GetOutputDataObject(0))->GetNumberOfBlocks(), 0u);
  EXPECT_EQ(seed->GetNumberOfSeededBonds(), 0);

  // A degenerate polygon (collinear vertices) is named by its index.
  vtkNew<vtkPolyData> flat;
  vtkNew<vtkPoints> p3;
  p3->InsertNextPoint(0, 0, 0);
  p3->InsertNextPoint(1, 0, 0);
  p3->InsertNextPoint(2, 0, 0);
  flat->SetPoints(p3);
  vtkNew<vtkCellArray> polys;
  const vtkIdType tri[3] = { 0, 1, 2 };
  polys->InsertNextCell(3, tri);
  flat->SetPolys(polys);
  seed->SetInputData(1, flat);
  errors->Messages.clear();
  EXPECT_FALSE(UpdateSucceeded(seed));
  EXPECT_NE(errors->All().find("Fracture polygon 0 has no area"), std::string::npos) << errors->All();
}
