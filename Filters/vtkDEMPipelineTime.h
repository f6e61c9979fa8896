/**
 * @file vtkDEMPipelineTime.h
 * @brief Time handling shared by the RockDEM stages that consume a model (not wrapped).
 */
#ifndef vtkDEMPipelineTime_h
#define vtkDEMPipelineTime_h

class vtkInformation;

namespace rockdem
{
/// Asks the upstream stage for a fixed time: its last published time step when it
/// publishes any (a stepped model is consumed where its run ended), else no time at all.
/// Changing this stage's time then never re-runs the stage before it (DESIGN.md, time
/// contract). Call from RequestUpdateExtent with the input's information.
void RequestLastUpstreamTime(vtkInformation* inputInfo);
}

#endif
