#include "vtkDEMVoxelize.h"

#include "vtkDEMFracturePolygons.h"
#include "vtkDEMModelConversion.h"
#include "vtkDEMPipelineTime.h"

#include "dem/Model.h"
#include "dem/ParticleStress.h"
#include "dem/Voxelize.h"

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
  , MemoryLimit(2048.0)
{
  this->SetNumberOfInputPorts(2);
  this->ResetResults();
}

vtkDEMVoxelize::~vtkDEMVoxelize() = default;

void vtkDEMVoxelize::ResetResults()
{
  std::fill(this->GridDimensions, this->GridDimensions + 3, 0);
  std::fill(this->VoxelSpacing, this->VoxelSpacing + 3, 0.0);
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

int vtkDEMVoxelize::RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*)
{
  // The grid depends on where the particles are, known in RequestData only: the output
  // carries its extent itself (no WHOLE_EXTENT here). The upstream times pass through.
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
  this->ResetResults();
  try
  {
    dem::VoxelParameters params;
    params.sizing = dem::voxelSizing(this->SizeBy);
    params.voxelSize = this->VoxelSize;
    params.numberOfVoxels = this->NumberOfVoxels;
    params.memoryLimit = this->MemoryLimit;
    dem::validate(params);
    const dem::Model model = rockdem::MultiBlockToModel(input);
    // Refuse a grid over the limit before the particle stresses are computed.
    dem::planVoxelGrid(model, params, dfn != nullptr);
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
      dem::voxelize(model, params, dem::particleStresses(model), dfn ? &fractures : nullptr);

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
    int extent[6] = { 0, g.dimensions[0] - 1, 0, g.dimensions[1] - 1, 0, g.dimensions[2] - 1 };
    outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);

    std::copy(g.dimensions.begin(), g.dimensions.end(), this->GridDimensions);
    for (int k = 0; k < 3; ++k)
    {
      this->VoxelSpacing[k] = g.spacing[k];
    }
    this->SolidVolume = vox.solidVolume;
    this->FractureArea = vox.fractureArea;
    this->LastMessageText = vox.message;
    vtkOutputWindowDisplayText(("DEM Voxelize: " + vox.message + "\n").c_str());
  }
  catch (const std::exception& e)
  {
    this->ResetResults();
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
  os << indent << "MemoryLimit: " << this->MemoryLimit << " MiB\n";
  os << indent << "GridDimensions: " << this->GridDimensions[0] << " " << this->GridDimensions[1] << " "
     << this->GridDimensions[2] << "\n";
  os << indent << "VoxelSpacing: " << this->VoxelSpacing[0] << " " << this->VoxelSpacing[1] << " "
     << this->VoxelSpacing[2] << " m\n";
  os << indent << "SolidVolume: " << this->SolidVolume << " m^3\n";
  os << indent << "FractureArea: " << this->FractureArea << " m^2\n";
  os << indent << "LastMessage: " << this->LastMessageText << "\n";
}
