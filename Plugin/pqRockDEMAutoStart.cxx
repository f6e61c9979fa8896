#include "pqRockDEMAutoStart.h"

#include <pqApplicationCore.h>
#include <pqDataRepresentation.h>
#include <pqOutputPort.h>
#include <pqPipelineSource.h>
#include <pqServerManagerModel.h>
#include <vtkDataObject.h>
#include <vtkSMPropertyHelper.h>
#include <vtkSMProxy.h>

#include <cstring>

pqRockDEMAutoStart::pqRockDEMAutoStart(QObject* p)
  : Superclass(p)
{
}

pqRockDEMAutoStart::~pqRockDEMAutoStart() = default;

void pqRockDEMAutoStart::startup()
{
  pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
  QObject::connect(model, &pqServerManagerModel::representationAdded, this,
    &pqRockDEMAutoStart::onRepresentationAdded);
}

void pqRockDEMAutoStart::shutdown() {}

void pqRockDEMAutoStart::onRepresentationAdded(pqRepresentation* representation)
{
  auto* dataRep = qobject_cast<pqDataRepresentation*>(representation);
  if (!dataRep)
  {
    return;
  }
  pqOutputPort* port = dataRep->getOutputPortFromInput();
  pqPipelineSource* source = dataRep->getInput();
  if (!port || !source || port->getPortNumber() != 0)
  {
    return;
  }
  const char* xmlName = source->getProxy()->GetXMLName();
  vtkSMProxy* repProxy = dataRep->getProxy();
  if (!xmlName || std::strncmp(xmlName, "DEM", 3) != 0 || !repProxy->GetProperty("SetScaleArray"))
  {
    return;
  }
  vtkSMPropertyHelper(repProxy, "ShaderPreset").Set(1); // Sphere
  vtkSMPropertyHelper(repProxy, "ScaleByArray").Set(1);
  vtkSMPropertyHelper(repProxy, "SetScaleArray")
    .SetInputArrayToProcess(vtkDataObject::FIELD_ASSOCIATION_POINTS, "Radius");
  vtkSMPropertyHelper(repProxy, "UseScaleFunction").Set(0);
  vtkSMPropertyHelper(repProxy, "GaussianRadius").Set(1.0);
  repProxy->UpdateVTKObjects();
}
