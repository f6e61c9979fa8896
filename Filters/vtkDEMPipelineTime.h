/**
 * @file vtkDEMPipelineTime.h
 * @brief Time handling shared by the RockDEM stages that consume a model (not wrapped).
 */
#ifndef vtkDEMPipelineTime_h
#define vtkDEMPipelineTime_h

class vtkDataObject;
class vtkInformation;

namespace rockdem
{
/// A request for this time asks a stepping stage for the end of its run: its last frame,
/// or with Number Of Frames 0 the frame where its test finishes (however many frames it
/// has published so far). Other time-varying sources give their last time step.
constexpr double EndOfRun = 1.0e300;

/// Asks the upstream stage for a fixed time: the end of its run (EndOfRun) when it
/// publishes time steps (a stepped model is consumed where its run ended), else no time
/// at all. Changing this stage's time then never re-runs the stage before it (DESIGN.md,
/// time contract). Call from RequestUpdateExtent with the input's information.
void RequestLastUpstreamTime(vtkInformation* inputInfo);

/// Removes the time steps and range the pipeline copied from upstream into an
/// instantaneous stage's output information (DEM Cement, DEM Seed Fractures, DEM
/// Specimen): they are not its to publish, and ParaView then leaves the upstream stage's
/// times out of the animation. Call from RequestInformation with the output's information.
void PublishNoTimeSteps(vtkInformation* outputInfo);

/// Stamps the output of a stage whose result does not depend on time with the time it
/// was asked for (DATA_TIME_STEP = the output's UPDATE_TIME_STEP), or removes the stamp
/// when no time was asked for, so that the pipeline sees the request satisfied (a shallow
/// copy of the input carries no upstream time). Call at the end of RequestData.
void StampRequestedTime(vtkInformation* outputInfo, vtkDataObject* output);
}

#endif
