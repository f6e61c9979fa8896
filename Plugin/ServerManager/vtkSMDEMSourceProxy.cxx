#include "vtkSMDEMSourceProxy.h"

#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkSMDEMSourceProxy);

vtkSMDEMSourceProxy::vtkSMDEMSourceProxy() = default;
vtkSMDEMSourceProxy::~vtkSMDEMSourceProxy() = default;

void vtkSMDEMSourceProxy::UpdatePipeline()
{
  this->Superclass::UpdatePipeline();
  this->RefreshAfterUpdate();
}

void vtkSMDEMSourceProxy::UpdatePipeline(double time)
{
  this->Superclass::UpdatePipeline(time);
  this->RefreshAfterUpdate();
}

bool vtkSMDEMSourceProxy::RefreshAfterUpdate()
{
  if (this->ObjectsCreated)
  {
    this->UpdatePropertyInformation();
  }
  return false;
}

void vtkSMDEMSourceProxy::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
