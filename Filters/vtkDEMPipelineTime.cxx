#include "vtkDEMPipelineTime.h"

#include <vtkDataObject.h>
#include <vtkInformation.h>
#include <vtkStreamingDemandDrivenPipeline.h>

namespace rockdem
{
void RequestLastUpstreamTime(vtkInformation* inInfo)
{
  if (inInfo->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()) &&
    inInfo->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS()) > 0)
  {
    // Not the last time step published: a stage that learns its frames as it runs (Number
    // Of Frames 0) publishes only its start before it has run.
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP(), EndOfRun);
  }
  else
  {
    inInfo->Remove(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
  }
}

void PublishNoTimeSteps(vtkInformation* outInfo)
{
  outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
}

void StampRequestedTime(vtkInformation* outInfo, vtkDataObject* output)
{
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
  {
    output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(),
      outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()));
  }
  else
  {
    output->GetInformation()->Remove(vtkDataObject::DATA_TIME_STEP());
  }
}
}
