#include "vtkSMDEMLoadTestProxy.h"

#include "vtkCompositeAnimationPlayer.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkSMParaViewPipelineController.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMSessionProxyManager.h"

vtkStandardNewMacro(vtkSMDEMLoadTestProxy);

vtkSMDEMLoadTestProxy::vtkSMDEMLoadTestProxy() = default;
vtkSMDEMLoadTestProxy::~vtkSMDEMLoadTestProxy() = default;

void vtkSMDEMLoadTestProxy::UpdatePipelineInformation()
{
  this->Superclass::UpdatePipelineInformation();
  if (this->GetProperty("TimeStepsRevision"))
  {
    this->KnownRevision = vtkSMPropertyHelper(this, "TimeStepsRevision").GetAsInt();
  }
  this->SnapAnimationToTimeSteps();
}

bool vtkSMDEMLoadTestProxy::RefreshAfterUpdate()
{
  if (this->InRefresh || !this->ObjectsCreated || !this->GetProperty("TimeStepsRevision"))
  {
    return false;
  }
  this->InRefresh = true;
  this->UpdatePropertyInformation();
  const int revision = vtkSMPropertyHelper(this, "TimeStepsRevision").GetAsInt();
  const bool changed = revision != this->KnownRevision;
  if (changed)
  {
    this->UpdatePipelineInformation();
  }
  this->InRefresh = false;
  return changed;
}

void vtkSMDEMLoadTestProxy::SnapAnimationToTimeSteps()
{
  vtkSMSessionProxyManager* pxm = this->GetSessionProxyManager();
  if (!pxm || !pxm->GetProxyName("sources", this) || !this->GetProperty("TimestepValues") ||
    vtkSMPropertyHelper(this, "TimestepValues").GetNumberOfElements() < 2)
  {
    return; // not in the pipeline yet, or nothing to animate
  }
  vtkNew<vtkSMParaViewPipelineController> controller;
  vtkSMProxy* scene = controller->FindAnimationScene(this->GetSession());
  if (!scene || !scene->GetProperty("PlayMode"))
  {
    return;
  }
  vtkSMPropertyHelper playMode(scene, "PlayMode");
  // Only the default: a mode the user chose (Real Time) is left alone.
  if (playMode.GetAsInt() == vtkCompositeAnimationPlayer::SEQUENCE)
  {
    playMode.Set(vtkCompositeAnimationPlayer::SNAP_TO_TIMESTEPS);
    scene->UpdateVTKObjects();
  }
}

void vtkSMDEMLoadTestProxy::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "KnownRevision: " << this->KnownRevision << "\n";
}
