#include "vtkDEMSeedFractures.h"

#include "vtkDEMFracturePolygons.h"
#include "vtkDEMModelConversion.h"
#include "vtkDEMPipelineTime.h"

#include "dem/Errors.h"
#include "dem/Model.h"
#include "dem/SeedFractures.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPolyData.h>

#include <exception>
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
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), port == 1 ? "vtkPolyData" : "vtkMultiBlockDataSet");
  return 1;
}

int vtkDEMSeedFractures::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // An instantaneous stage: the upstream times are not ours to publish.
  rockdem::PublishNoTimeSteps(outputVector->GetInformationObject(0));
  return 1;
}

int vtkDEMSeedFractures::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // The model where its upstream run ended; the fractures at the time asked for (a DFN
  // exported from a load test follows time).
  rockdem::RequestLastUpstreamTime(inputVector[0]->GetInformationObject(0));
  return 1;
}

int vtkDEMSeedFractures::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  auto* output = vtkMultiBlockDataSet::GetData(outputVector, 0);
  auto* input = vtkMultiBlockDataSet::GetData(inputVector[0], 0);
  auto* fractures = vtkPolyData::GetData(inputVector[1], 0);
  this->NumberOfSeededBonds = 0;
  this->NumberOfPolygons = 0;
  this->NumberOfAlreadyBroken = 0;
  try
  {
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
    dem::Model model = rockdem::MultiBlockToModel(input);
    const dem::SeedReport report = dem::seedFractures(model, polygons);
    rockdem::ModelToMultiBlock(model, output);
    this->NumberOfSeededBonds = static_cast<vtkIdType>(report.seeded);
    this->NumberOfPolygons = static_cast<vtkIdType>(report.polygons);
    this->NumberOfAlreadyBroken = static_cast<vtkIdType>(report.alreadyBroken);
    this->LastMessageText = report.summary();
    vtkOutputWindowDisplayText(("DEM Seed Fractures: " + this->LastMessageText + "\n").c_str());
    if (report.bonds == 0)
    {
      vtkWarningMacro(<< "DEM Seed Fractures: the model has no bonds, so nothing was seeded (cement it first).");
    }
  }
  catch (const std::exception& e)
  {
    this->NumberOfSeededBonds = 0;
    this->NumberOfPolygons = 0;
    this->NumberOfAlreadyBroken = 0;
    this->LastMessageText = e.what();
    vtkErrorMacro(<< e.what());
    output->Initialize();
    return 0;
  }
  rockdem::StampRequestedTime(outInfo, output);
  return 1;
}

void vtkDEMSeedFractures::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SeededBonds: " << this->NumberOfSeededBonds << "\n";
  os << indent << "Polygons: " << this->NumberOfPolygons << "\n";
  os << indent << "AlreadyBroken: " << this->NumberOfAlreadyBroken << "\n";
  os << indent << "LastMessage: " << this->LastMessageText << "\n";
}
