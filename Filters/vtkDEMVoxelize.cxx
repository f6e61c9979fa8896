#include "vtkDEMVoxelize.h"

#include "vtkDEMFracturePolygons.h"
#include "vtkDEMModelConversion.h"
#include "vtkDEMPipelineTime.h"

#include "dem/Errors.h"
#include "dem/Model.h"
#include "dem/ParticleStress.h"
#include "dem/Voxelize.h"

#include <vtkAlgorithmOutput.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <cstring>
#include <exception>

vtkStandardNewMacro(vtkDEMVoxelize);

namespace
{
/// A point array holding a copy of v (T a plain value or an array of doubles).
template <typename ArrayT, typename T>
vtkNew<ArrayT> FieldArray(const char* name, const std::vector<T>& v, int components)
{
  vtkNew<ArrayT> a;
  a->SetName(name);
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(static_cast<vtkIdType>(v.size()));
  if (!v.empty())
  {
    std::memcpy(a->GetPointer(0), v.data(), v.size() * sizeof(T));
  }
  return a;
}
}

vtkDEMVoxelize::vtkDEMVoxelize()
  : SizeBy(1)
  , VoxelSize(0.001)
  , NumberOfVoxels(64)
  , Margin(0.05)
  , MemoryLimit(2048.0)
  , GridValid(false)
{
  this->SetNumberOfInputPorts(2);
  this->ResetResults();
}

vtkDEMVoxelize::~vtkDEMVoxelize() = default;

void vtkDEMVoxelize::ResetResults()
{
  std::fill(this->GridDimensions, this->GridDimensions + 3, 0);
  std::fill(this->VoxelSpacing, this->VoxelSpacing + 3, 0.0);
  std::fill(this->GridOrigin, this->GridOrigin + 3, 0.0);
  std::fill(this->GridWraps, this->GridWraps + 3, 0);
  this->GridValid = false;
  this->SolidVolume = 0.0;
  this->FractureArea = 0.0;
}

int vtkDEMVoxelize::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  else
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkMultiBlockDataSet");
  }
  return 1;
}

namespace
{
dem::VoxelParameters Parameters(int sizeBy, double voxelSize, int numberOfVoxels, double margin, double limit)
{
  dem::VoxelParameters params;
  params.sizing = dem::voxelSizing(sizeBy);
  params.voxelSize = voxelSize;
  params.numberOfVoxels = numberOfVoxels;
  params.margin = margin;
  params.memoryLimit = limit;
  dem::validate(params);
  return params;
}
}

int vtkDEMVoxelize::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // ParaView needs the image's extent before it asks for a time: the grid is fitted here,
  // to the model at the upstream's first time step (or as it is), and kept for all times.
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  this->ResetResults();
  try
  {
    const dem::VoxelParameters params = Parameters(
      this->SizeBy, this->VoxelSize, this->NumberOfVoxels, this->Margin, this->MemoryLimit);
    vtkAlgorithm* upstream = this->GetInputAlgorithm(0, 0);
    const int port = this->GetInputConnection(0, 0)->GetIndex();
    auto* executive = vtkStreamingDemandDrivenPipeline::SafeDownCast(upstream->GetExecutive());
    const int times = inInfo->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    vtkNew<vtkInformationVector> requests;
    requests->SetNumberOfInformationObjects(upstream->GetNumberOfOutputPorts());
    if (times > 0)
    {
      requests->GetInformationObject(port)->Set(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP(),
        inInfo->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS())[0]);
    }
    executive->Update(port, requests);
    const dem::Model reference =
      rockdem::MultiBlockToModel(vtkMultiBlockDataSet::SafeDownCast(upstream->GetOutputDataObject(port)));
    const bool withFractures = inputVector[1]->GetNumberOfInformationObjects() > 0;
    const dem::VoxelGrid grid = dem::planVoxelGrid(reference, params, withFractures);
    for (int k = 0; k < 3; ++k)
    {
      this->GridDimensions[k] = grid.dimensions[k];
      this->VoxelSpacing[k] = grid.spacing[k];
      this->GridOrigin[k] = grid.origin[k];
      this->GridWraps[k] = grid.wraps[k] ? 1 : 0;
    }
    this->GridValid = true;
    const int extent[6] = { 0, grid.dimensions[0] - 1, 0, grid.dimensions[1] - 1, 0, grid.dimensions[2] - 1 };
    const dem::Vec3 first = grid.origin + 0.5 * grid.spacing; // the centre of voxel (0, 0, 0)
    outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
    outInfo->Set(vtkDataObject::ORIGIN(), first.x(), first.y(), first.z());
    outInfo->Set(vtkDataObject::SPACING(), grid.spacing.x(), grid.spacing.y(), grid.spacing.z());
  }
  catch (const std::exception& e)
  {
    this->ResetResults();
    this->LastMessageText = e.what();
    vtkErrorMacro(<< e.what());
    return 0;
  }
  return 1;
}

int vtkDEMVoxelize::RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*)
{
  return 1; // the whole model and the whole DFN, at the time asked for (passed upstream)
}

int vtkDEMVoxelize::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  auto* output = vtkImageData::GetData(outputVector, 0);
  auto* input = vtkMultiBlockDataSet::GetData(inputVector[0], 0);
  auto* dfn = inputVector[1]->GetNumberOfInformationObjects() > 0 ? vtkPolyData::GetData(inputVector[1], 0) : nullptr;
  output->Initialize();
  try
  {
    if (!this->GridValid)
    {
      throw dem::InputError(this->LastMessageText.empty() ? "DEM Voxelize has no grid." : this->LastMessageText);
    }
    dem::VoxelGrid grid;
    for (int k = 0; k < 3; ++k)
    {
      grid.dimensions[k] = this->GridDimensions[k];
      grid.origin[k] = this->GridOrigin[k];
      grid.spacing[k] = this->VoxelSpacing[k];
      grid.wraps[k] = this->GridWraps[k] != 0;
    }
    const dem::Model model = rockdem::MultiBlockToModel(input);
    dem::FractureSetPolygons fractures;
    if (dfn)
    {
      std::vector<vtkIdType> cells;
      fractures.polygons = rockdem::FracturePolygons(dfn, &cells);
      vtkDataArray* set = dfn->GetCellData()->GetArray("Set");
      for (vtkIdType cell : cells)
      {
        fractures.sets.push_back(set ? static_cast<int>(set->GetTuple1(cell)) : -1);
      }
    }
    const dem::VoxelModel vox =
      dem::voxelize(model, grid, dem::particleStresses(model), dfn ? &fractures : nullptr);

    const dem::VoxelGrid& g = vox.grid;
    output->SetDimensions(g.dimensions[0], g.dimensions[1], g.dimensions[2]);
    output->SetSpacing(g.spacing.x(), g.spacing.y(), g.spacing.z());
    const dem::Vec3 first = g.origin + 0.5 * g.spacing; // the centre of voxel (0, 0, 0)
    output->SetOrigin(first.x(), first.y(), first.z());
    vtkPointData* pd = output->GetPointData();
    pd->AddArray(FieldArray<vtkDoubleArray>("SolidFraction", vox.solidFraction, 1));
    pd->AddArray(FieldArray<vtkIntArray>("Bonds", vox.bonds, 1));
    pd->AddArray(FieldArray<vtkIntArray>("BrokenBonds", vox.brokenBonds, 1));
    pd->AddArray(FieldArray<vtkDoubleArray>("Damage", vox.damage, 1));
    pd->AddArray(FieldArray<vtkDoubleArray>("BrokenBondDensity", vox.brokenBondDensity, 1));
    pd->AddArray(FieldArray<vtkDoubleArray>("Stress", vox.stress, 6));
    pd->AddArray(FieldArray<vtkDoubleArray>("MeanStress", vox.meanStress, 1));
    pd->AddArray(FieldArray<vtkDoubleArray>("DeviatoricStress", vox.deviatoricStress, 1));
    pd->AddArray(FieldArray<vtkDoubleArray>("Displacement", vox.displacement, 3));
    if (dfn)
    {
      pd->AddArray(FieldArray<vtkDoubleArray>("FractureIntensity", vox.fractureIntensity, 1));
      pd->AddArray(FieldArray<vtkIntArray>("FractureSet", vox.fractureSet, 1));
    }
    pd->SetActiveScalars("Damage");
    this->SolidVolume = vox.solidVolume;
    this->FractureArea = vox.fractureArea;
    this->LastMessageText = vox.message;
    vtkOutputWindowDisplayText(("DEM Voxelize: " + vox.message + "\n").c_str());
  }
  catch (const std::exception& e)
  {
    this->SolidVolume = 0.0;
    this->FractureArea = 0.0;
    this->LastMessageText = e.what();
    vtkErrorMacro(<< e.what());
    output->Initialize();
    return 0;
  }
  rockdem::StampRequestedTime(outInfo, output);
  return 1;
}

void vtkDEMVoxelize::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SizeBy: " << this->SizeBy << "\n";
  os << indent << "VoxelSize: " << this->VoxelSize << " m\n";
  os << indent << "NumberOfVoxels: " << this->NumberOfVoxels << "\n";
  os << indent << "Margin: " << this->Margin << "\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit << " MiB\n";
  os << indent << "GridDimensions: " << this->GridDimensions[0] << " " << this->GridDimensions[1] << " "
     << this->GridDimensions[2] << "\n";
  os << indent << "VoxelSpacing: " << this->VoxelSpacing[0] << " " << this->VoxelSpacing[1] << " "
     << this->VoxelSpacing[2] << " m\n";
  os << indent << "SolidVolume: " << this->SolidVolume << " m^3\n";
  os << indent << "FractureArea: " << this->FractureArea << " m^2\n";
  os << indent << "LastMessage: " << this->LastMessageText << "\n";
}
