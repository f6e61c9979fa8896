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
  // The animation manager exists once the application core is built (a plugin found on
  // PV_PLUGIN_PATH starts while it is being built): connect to it afterwards.
  QTimer::singleShot(0, this, [this]() {
    pqAnimationManager* manager = pqPVApplicationCore::instance()
      ? pqPVApplicationCore::instance()->animationManager()
      : nullptr;
    if (!manager)
    {
      return;
    }
    auto connectScene = [this](pqAnimationScene* scene) {
      if (scene)
      {
        QObject::connect(scene,
          QOverload<vtkObject*, unsigned long, void*, void*>::of(&pqAnimationScene::endPlay), this,
          &pqRockDEMAutoStart::onEndPlay, Qt::UniqueConnection);
      }
    };
    QObject::connect(manager, &pqAnimationManager::activeSceneChanged, this, connectScene);
    connectScene(manager->getActiveScene());
  });
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
      // The end of a run (a test finished, a model settled) ends the animation there.
      pqAnimationManager* manager = pqPVApplicationCore::instance()->animationManager();
      pqAnimationScene* scene = manager ? manager->getActiveScene() : nullptr;
      const bool finished = vtkSMPropertyHelper(test, "Finished", true).GetAsInt() != 0;
      const bool visible = !source->getRepresentations(nullptr).isEmpty();
      if (scene && finished && visible && !source->property("RockDEMStoppedAtEnd").toBool())
      {
        source->setProperty("RockDEMStoppedAtEnd", true);
        scene->pause();
      }
      else if (!finished)
      {
        source->setProperty("RockDEMStoppedAtEnd", false);
      }
    }
  }
}

void pqRockDEMAutoStart::onEndPlay()
{
  pqAnimationManager* manager = pqPVApplicationCore::instance()->animationManager();
  pqAnimationScene* scene = manager ? manager->getActiveScene() : nullptr;
  if (!scene)
  {
    return;
  }
  // Play ran to the end of the frames known when it started. A DEM Load Test that learnt
  // of more frames meanwhile (Number Of Frames 0) and has not finished goes on.
  const double reached = scene->getAnimationTime();
  const double end = scene->getClockTimeRange().second;
  if (reached < end)
  {
    return; // paused or stopped by the user
  }
  QPointer<pqAnimationScene> guarded(scene);
  QTimer::singleShot(0, this, [this, guarded, reached]() {
    this->refreshReadOnlyValues();
    if (!guarded)
    {
      return;
    }
    pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
    for (pqPipelineSource* source : model->findItems<pqPipelineSource*>())
    {
      auto* test = vtkSMDEMLoadTestProxy::SafeDownCast(source->getProxy());
      if (test && !source->getRepresentations(nullptr).isEmpty() &&
        vtkSMPropertyHelper(test, "Finished", true).GetAsInt() == 0 &&
        guarded->getClockTimeRange().second > reached)
      {
        guarded->play();
        return;
      }
    }
  });
}

void pqRockDEMAutoStart::onRepresentationAdded(pqRepresentation* representation)
{
  if (pqApplicationCore::instance()->isLoadingState())
  {
    return; // a saved state keeps the colouring it was saved with
  }
  // The representation knows its input, and is initialised, once Show() has returned.
  QPointer<pqDataRepresentation> guarded(qobject_cast<pqDataRepresentation*>(representation));
  QTimer::singleShot(0, this, [guarded]() {
    if (guarded)
    {
      colorByDefault(guarded);
    }
  });
}

void pqRockDEMAutoStart::colorByDefault(pqDataRepresentation* representation)
{
  pqPipelineSource* source = representation->getInput();
  pqOutputPort* port = representation->getOutputPortFromInput();
  vtkSMProxy* rep = representation->getProxy();
  if (!source || !port || port->getPortNumber() != 0 || !rep->GetProperty("ColorArrayName"))
  {
    return;
  }
  if (isLoadTest(source))
  {
    // A stepping model is coloured by how far its particles moved (the GUI would otherwise
    // carry the input's colouring, Radius, over), with the legend of that colouring only.
    pqView* view = representation->getView();
    vtkSMProxy* viewProxy = view ? view->getProxy() : nullptr;
    if (viewProxy)
    {
      vtkSMPVRepresentationProxy::SetScalarBarVisibility(rep, viewProxy, false);
    }
    if (vtkSMPVRepresentationProxy::SetScalarColoring(rep, "Displacement", 0 /* points */))
    {
      vtkSMPVRepresentationProxy::RescaleTransferFunctionToDataRange(rep, false, false);
      if (viewProxy)
      {
        vtkSMPVRepresentationProxy::SetScalarBarVisibility(rep, viewProxy, true);
      }
      rep->UpdateVTKObjects();
      representation->renderViewEventually();
    }
    return;
  }
  const char* name = source->getProxy()->GetXMLName();
  if (!name || std::strcmp(name, "DEMFracturesToDFN") != 0)
  {
    // Another RockDEM model left uncoloured (a state file opened with File > Open), or a
    // cemented model (ParaView would carry its input's colouring over, the Displacement of
    // the stage before, which says nothing about this one): coloured by Radius, like a pack.
    const char* colored = vtkSMPropertyHelper(rep, "ColorArrayName").GetInputArrayNameToProcess();
    const bool cement = name && std::strcmp(name, "DEMCement") == 0;
    if (!isRockDEM(source) || (colored && *colored && !cement))
    {
      return;
    }
    // The legend of the carried-over colouring goes; the one of Radius is shown.
    pqView* view = representation->getView();
    vtkSMProxy* viewProxy = view ? view->getProxy() : nullptr;
    if (viewProxy)
    {
      vtkSMPVRepresentationProxy::SetScalarBarVisibility(rep, viewProxy, false);
    }
    if (vtkSMPVRepresentationProxy::SetScalarColoring(rep, "Radius", 0 /* points */))
    {
      vtkSMPVRepresentationProxy::RescaleTransferFunctionToDataRange(rep, false, false);
      if (viewProxy)
      {
        vtkSMPVRepresentationProxy::SetScalarBarVisibility(rep, viewProxy, true);
      }
      rep->UpdateVTKObjects();
      representation->renderViewEventually();
    }
    return;
  }
  if (!vtkSMPVRepresentationProxy::SetScalarColoring(rep, "Set", 1 /* cells */))
  {
    return;
  }
  // The fracture sets: categorical, tensile red, shear blue, inherited green.
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
  representation->renderViewEventually();
}
