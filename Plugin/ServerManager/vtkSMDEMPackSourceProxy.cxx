#include "vtkSMDEMPackSourceProxy.h"

#include "vtkObjectFactory.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMStringVectorProperty.h"

#include <string>

vtkStandardNewMacro(vtkSMDEMPackSourceProxy);

vtkSMDEMPackSourceProxy::vtkSMDEMPackSourceProxy() = default;
vtkSMDEMPackSourceProxy::~vtkSMDEMPackSourceProxy() = default;

void vtkSMDEMPackSourceProxy::RecordCommands()
{
  auto* info = vtkSMStringVectorProperty::SafeDownCast(this->GetProperty("CommandsInfo"));
  if (!info || !this->GetProperty("Commands") || !this->ObjectsCreated)
  {
    return;
  }
  this->UpdatePropertyInformation(info);
  const std::string pressed = info->GetNumberOfElements() > 0 && info->GetElement(0)
    ? info->GetElement(0)
    : "";
  vtkSMPropertyHelper commands(this, "Commands");
  const char* recorded = commands.GetAsString();
  if (pressed != (recorded ? recorded : ""))
  {
    // The algorithm already holds this sequence: pushing it changes nothing there.
    commands.Set(pressed.c_str());
    this->UpdateVTKObjects();
  }
}

vtkPVXMLElement* vtkSMDEMPackSourceProxy::SaveXMLState(
  vtkPVXMLElement* root, vtkSMPropertyIterator* iter)
{
  this->RecordCommands();
  return this->Superclass::SaveXMLState(root, iter);
}

void vtkSMDEMPackSourceProxy::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
