#include "vtkDEMSeedFractures.h"

#include "vtkDEMFracturePolygons.h"
#include "vtkDEMModelConversion.h"

#include "dem/Errors.h"
#include "dem/Model.h"
#include "dem/SeedFractures.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

#include <string>
#include <vector>

vtkStandardNewMacro(vtkDEMSeedFractures);

vtkDEMSeedFractures::vtkDEMSeedFractures()
  : NumberOfSeededBonds(0)
  , NumberOfPolygons(0)
  , NumberOfAlreadyBroken(0)
{
  this->SetNumberOfInputPorts(2);
}

vtkDEMSeedFractures::~vtkDEMSeedFractures() = default;

int vtkDEMSeedFractures::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
    return 1;
  }
  return this->Superclass::FillInputPortInformation(port, info);
}

const char* vtkDEMSeedFractures::StageName() const
{
  return "DEM Seed Fractures";
}

void vtkDEMSeedFractures::ClearResults()
{
  this->NumberOfSeededBonds = 0;
  this->NumberOfPolygons = 0;
  this->NumberOfAlreadyBroken = 0;
}

std::string vtkDEMSeedFractures::Execute(vtkInformationVector** inputVector, vtkMultiBlockDataSet* output)
{
  // The model where its upstream run ended (the base reads it there); the fractures at
  // the time asked for (a DFN exported from a load test follows time).
  auto* fractures = vtkPolyData::GetData(inputVector[1], 0);
  if (!fractures)
  {
    throw dem::InputError("DEM Seed Fractures needs the fracture polygons on its Fractures input.");
  }
  // Polygons, triangles and quads (Polys), and triangle strips split into triangles.
  const std::vector<dem::FracturePolygon> polygons = rockdem::FracturePolygons(fractures);
  if (polygons.empty())
  {
    throw dem::InputError("DEM Seed Fractures: the Fractures input has no polygons (" +
      std::to_string(fractures->GetNumberOfCells()) +
      " cells, none of them a polygon, triangle, quad or triangle strip).");
  }
  dem::Model model = rockdem::MultiBlockToModel(vtkMultiBlockDataSet::GetData(inputVector[0], 0));
  const dem::SeedReport report = dem::seedFractures(model, polygons);
  rockdem::ModelToMultiBlock(model, output);
  this->NumberOfSeededBonds = static_cast<vtkIdType>(report.seeded);
  this->NumberOfPolygons = static_cast<vtkIdType>(report.polygons);
  this->NumberOfAlreadyBroken = static_cast<vtkIdType>(report.alreadyBroken);
  if (report.bonds == 0)
  {
    vtkWarningMacro(<< "DEM Seed Fractures: the model has no bonds, so nothing was seeded (cement it first).");
  }
  return report.summary();
}

void vtkDEMSeedFractures::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SeededBonds: " << this->NumberOfSeededBonds << "\n";
  os << indent << "Polygons: " << this->NumberOfPolygons << "\n";
  os << indent << "AlreadyBroken: " << this->NumberOfAlreadyBroken << "\n";
}
