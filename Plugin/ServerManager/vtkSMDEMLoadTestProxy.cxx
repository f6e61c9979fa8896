#include "vtkSMDEMLoadTestProxy.h"

#include "vtkCompositeAnimationPlayer.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkSMParaViewPipelineController.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMSessionProxyManager.h"

#include <set>

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
    // The filters after the stage copy its times: theirs are updated too, so the time
    // keeper (which lists a filter's times in place of its input's) and Play see the
    // model's times downstream as well.
    std::set<vtkSMProxy*> visited;
    this->UpdateDownstreamInformation(this, visited);
  }
  this->InRefresh = false;
  return changed;
}

void vtkSMDEMLoadTestProxy::UpdateDownstreamInformation(
  vtkSMProxy* proxy, std::set<vtkSMProxy*>& visited)
{
  vtkSMSessionProxyManager* pxm = this->GetSessionProxyManager();
  for (unsigned int i = 0; pxm && i < proxy->GetNumberOfConsumers(); ++i)
  {
    // Only pipeline filters (registered as sources), not representations or views.
    auto* consumer = vtkSMSourceProxy::SafeDownCast(proxy->GetConsumerProxy(i));
    if (!consumer || !visited.insert(consumer).second || !pxm->GetProxyName("sources", consumer))
    {
      continue;
    }
    consumer->UpdatePipelineInformation();
    this->UpdateDownstreamInformation(consumer, visited);
  }
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
