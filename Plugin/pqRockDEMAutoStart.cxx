#include "pqRockDEMAutoStart.h"

#include "vtkSMDEMLoadTestProxy.h"

#include <pqActiveObjects.h>
#include <pqAnimationManager.h>
#include <pqAnimationScene.h>
#include <pqApplicationCore.h>
#include <pqDataRepresentation.h>
#include <pqOutputPort.h>
#include <pqPVApplicationCore.h>
#include <pqPipelineSource.h>
#include <pqServerManagerModel.h>
#include <pqView.h>
#include <vtkSMPVRepresentationProxy.h>
#include <vtkSMPropertyHelper.h>
#include <vtkSMSourceProxy.h>
#include <vtkSMTransferFunctionManager.h>
#include <vtkSMTransferFunctionProxy.h>
#include <vtkNew.h>

#include <QVariant>

#include <cstring>

pqRockDEMAutoStart::pqRockDEMAutoStart(QObject* p)
  : Superclass(p)
{
  // One pull per burst of renders, after the render (and between Play frames: the
  // animation processes events after each frame).
  this->RefreshTimer.setSingleShot(true);
  this->RefreshTimer.setInterval(0);
  QObject::connect(
    &this->RefreshTimer, &QTimer::timeout, this, &pqRockDEMAutoStart::refreshReadOnlyValues);
}

pqRockDEMAutoStart::~pqRockDEMAutoStart() = default;

bool pqRockDEMAutoStart::isRockDEM(pqPipelineSource* source)
{
  const char* name = source && source->getProxy() ? source->getProxy()->GetXMLName() : nullptr;
  return name && std::strncmp(name, "DEM", 3) == 0;
}

bool pqRockDEMAutoStart::isLoadTest(pqPipelineSource* source)
{
  const char* name = source && source->getProxy() ? source->getProxy()->GetXMLName() : nullptr;
  return name && std::strcmp(name, "DEMLoadTest") == 0;
}

void pqRockDEMAutoStart::startup()
{
  pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
  QObject::connect(
    model, &pqServerManagerModel::sourceAdded, this, &pqRockDEMAutoStart::onSourceAdded);
  QObject::connect(model, &pqServerManagerModel::viewAdded, this, &pqRockDEMAutoStart::onViewAdded);
  QObject::connect(model, &pqServerManagerModel::representationAdded, this,
    &pqRockDEMAutoStart::onRepresentationAdded);
  for (pqView* view : model->findItems<pqView*>())
  {
    this->onViewAdded(view);
  }
  for (pqPipelineSource* source : model->findItems<pqPipelineSource*>())
  {
    this->onSourceAdded(source);
  }
}

void pqRockDEMAutoStart::shutdown() {}

void pqRockDEMAutoStart::onSourceAdded(pqPipelineSource* source)
{
  if (isLoadTest(source))
  {
    QObject::connect(source, &pqProxy::modifiedStateChanged, this,
      &pqRockDEMAutoStart::onModifiedStateChanged, Qt::UniqueConnection);
  }
}

void pqRockDEMAutoStart::onModifiedStateChanged(pqServerManagerModelItem* item)
{
  auto* source = qobject_cast<pqPipelineSource*>(item);
  if (!source || source->modifiedState() != pqProxy::UNMODIFIED ||
    source->property("RockDEMApplied").toBool())
  {
    return;
  }
  // The first Apply: show the stage at its first frame, so nothing ahead is computed.
  source->setProperty("RockDEMApplied", true);
  vtkSMSourceProxy* proxy = vtkSMSourceProxy::SafeDownCast(source->getProxy());
  vtkSMPropertyHelper times(proxy, "TimestepValues", /*quiet=*/true);
  pqAnimationManager* manager = pqPVApplicationCore::instance()->animationManager();
  pqAnimationScene* scene = manager ? manager->getActiveScene() : nullptr;
  if (scene && times.GetNumberOfElements() > 0)
  {
    scene->setAnimationTime(times.GetAsDouble(0));
  }
}

void pqRockDEMAutoStart::onViewAdded(pqView* view)
{
  QObject::connect(view, &pqView::endRender, &this->RefreshTimer,
    QOverload<>::of(&QTimer::start), Qt::UniqueConnection);
}

void pqRockDEMAutoStart::refreshReadOnlyValues()
{
  pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
  for (pqPipelineSource* source : model->findItems<pqPipelineSource*>())
  {
    if (!isRockDEM(source))
    {
      continue;
    }
    if (auto* stage = vtkSMDEMSourceProxy::SafeDownCast(source->getProxy()))
    {
      stage->RefreshAfterUpdate();
    }
    if (auto* test = vtkSMDEMLoadTestProxy::SafeDownCast(source->getProxy()))
    {
      // A finished test ends the animation at its last frame.
      pqAnimationManager* manager = pqPVApplicationCore::instance()->animationManager();
      pqAnimationScene* scene = manager ? manager->getActiveScene() : nullptr;
      const char* stage = vtkSMPropertyHelper(test, "Stage", true).GetAsString();
      if (scene && stage && std::strcmp(stage, "done") == 0 &&
        vtkSMPropertyHelper(test, "Mode").GetAsInt() != 0 &&
        source->property("RockDEMStoppedAtDone").toBool() == false)
      {
        source->setProperty("RockDEMStoppedAtDone", true);
        scene->pause();
      }
      else if (stage && std::strcmp(stage, "done") != 0)
      {
        source->setProperty("RockDEMStoppedAtDone", false);
      }
    }
  }
}

void pqRockDEMAutoStart::onRepresentationAdded(pqRepresentation* representation)
{
  auto* dataRep = qobject_cast<pqDataRepresentation*>(representation);
  pqPipelineSource* source = dataRep ? dataRep->getInput() : nullptr;
  pqOutputPort* port = dataRep ? dataRep->getOutputPortFromInput() : nullptr;
  if (!source || !port || port->getPortNumber() != 0 || !source->getProxy()->GetXMLName() ||
    std::strcmp(source->getProxy()->GetXMLName(), "DEMFracturesToDFN") != 0)
  {
    return;
  }
  // After the representation is initialised (this signal comes from inside Show()).
  QPointer<pqDataRepresentation> guarded(dataRep);
  QTimer::singleShot(0, this, [guarded]() {
    if (!guarded)
    {
      return;
    }
    vtkSMProxy* rep = guarded->getProxy();
    if (!vtkSMPVRepresentationProxy::SetScalarColoring(rep, "Set", 1 /* cells */))
    {
      return;
    }
    vtkNew<vtkSMTransferFunctionManager> manager;
    vtkSMProxy* lut = manager->GetColorTransferFunction("Set", rep->GetSessionProxyManager());
    vtkSMPropertyHelper(lut, "IndexedLookup").Set(1);
    vtkSMPropertyHelper(lut, "AnnotationsInitialized").Set(1);
    const char* annotations[] = { "0", "tensile", "1", "shear", "2", "inherited" };
    vtkSMPropertyHelper annotate(lut, "Annotations");
    annotate.SetNumberOfElements(6);
    for (unsigned int k = 0; k < 6; ++k)
    {
      annotate.Set(k, annotations[k]);
    }
    const double colors[] = { 0.85, 0.15, 0.15, 0.15, 0.35, 0.85, 0.2, 0.7, 0.2 };
    vtkSMPropertyHelper(lut, "IndexedColors").Set(colors, 9);
    lut->UpdateVTKObjects();
    rep->UpdateVTKObjects();
    guarded->renderViewEventually();
  });
}
