#include "vtkDEMInstantStage.h"

#include "vtkDEMPipelineTime.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkOutputWindow.h>

#include <exception>

vtkDEMInstantStage::vtkDEMInstantStage() = default;

vtkDEMInstantStage::~vtkDEMInstantStage() = default;

int vtkDEMInstantStage::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkMultiBlockDataSet");
  return 1;
}

int vtkDEMInstantStage::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // The upstream times (copied here by the pipeline) are not ours to publish. ParaView
  // then leaves the upstream stage's times out of the animation.
  rockdem::PublishNoTimeSteps(outputVector->GetInformationObject(0));
  return 1;
}

int vtkDEMInstantStage::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // A stepped upstream model is read at a fixed time, its last time step, so that
  // changing the animation time never re-runs the stage before this one.
  rockdem::RequestLastUpstreamTime(inputVector[0]->GetInformationObject(0));
  return 1;
}

int vtkDEMInstantStage::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  auto* output = vtkMultiBlockDataSet::GetData(outputVector, 0);
  try
  {
    const std::string line = this->Execute(inputVector, output);
    if (!line.empty())
    {
      this->LastMessageText = line;
      vtkOutputWindowDisplayText((std::string(this->StageName()) + ": " + line + "\n").c_str());
    }
  }
  catch (const std::exception& e)
  {
    this->ClearResults();
    this->LastMessageText = e.what();
    vtkErrorMacro(<< e.what());
    output->Initialize();
    return 0;
  }
  // The result does not depend on time: stamp the time asked for, so that the pipeline
  // sees the request satisfied (a copy of the input carries no upstream time).
  rockdem::StampRequestedTime(outputVector->GetInformationObject(0), output);
  return 1;
}

void vtkDEMInstantStage::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LastMessage: " << this->LastMessageText << "\n";
}
