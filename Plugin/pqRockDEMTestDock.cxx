#include "pqRockDEMTestDock.h"

#include "pqRockDEMAutoStart.h"
#include "pqRockDEMReadOnlyWidget.h"
#include "vtkDEMLoadTest.h"

#include <QVTKOpenGLNativeWidget.h>
#include <pqActiveObjects.h>
#include <pqApplicationCore.h>
#include <pqCoreUtilities.h>
#include <pqFileDialog.h>
#include <pqPipelineSource.h>
#include <pqServerManagerModel.h>
#include <pqView.h>
#include <vtkAlgorithm.h>
#include <vtkAxis.h>
#include <vtkChartLegend.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkPVDataInformation.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkSMPropertyHelper.h>
#include <vtkSMSourceProxy.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>

#include <QDateTime>
#include <QFormLayout>
#include <QLabel>
#include <QMessageBox>
#include <QPushButton>
#include <QVBoxLayout>

#include <cmath>

namespace
{
/// What the chart plots: the History table's plot columns (units in the names).
const char* const StrainColumn = "Axial Strain (%)";
struct Series
{
  const char* column;
  unsigned char rgb[3];
  int corner; ///< 0 left axis (stress), 1 right axis (volumetric strain)
  int line;   ///< vtkPen line type: the deviator is dashed (unconfined it equals the axial)
};
const Series PlottedSeries[] = {
  { "Axial Stress (MPa)", { 214, 39, 40 }, 0, vtkPen::SOLID_LINE },
  { "Lateral Stress (MPa)", { 31, 119, 180 }, 0, vtkPen::SOLID_LINE },
  { "Deviator Stress (MPa)", { 255, 127, 14 }, 0, vtkPen::DASH_LINE },
  { "Volumetric Strain (%)", { 44, 160, 44 }, 1, vtkPen::SOLID_LINE },
};
constexpr double ShearStage = 2.0; ///< the Stage column's value during shear
constexpr qint64 RefreshPeriodMs = 500; ///< at most twice a second

QString formatDuration(double seconds)
{
  if (!(seconds >= 0.0) || !std::isfinite(seconds))
  {
    return QString("unknown");
  }
  if (seconds < 120.0)
  {
    return QString("%1 s").arg(seconds, 0, 'g', 3);
  }
  if (seconds < 7200.0)
  {
    return QString("%1 min").arg(seconds / 60.0, 0, 'f', 1);
  }
  if (seconds < 3.0 * 86400.0)
  {
    return QString("%1 h").arg(seconds / 3600.0, 0, 'f', 1);
  }
  if (seconds < 3.0 * 365.25 * 86400.0)
  {
    return QString("%1 days").arg(seconds / 86400.0, 0, 'f', 0);
  }
  return QString("%1 years").arg(seconds / (365.25 * 86400.0), 0, 'g', 3);
}
}

pqRockDEMTestDock::pqRockDEMTestDock(QWidget* parent)
  : Superclass("DEM Test", parent)
  , ModelLabel(new QLabel(this))
  , StageLabel(new QLabel(this))
  , PeakLabel(new QLabel(this))
  , StatusLabel(new QLabel(this))
  , EstimateLabel(new QLabel(this))
  , ExportButton(new QPushButton("Export CSV...", this))
  , ChartWidget(new QVTKOpenGLNativeWidget(this))
{
  this->setWindowTitle("DEM Test");
  auto* body = new QWidget(this);
  auto* layout = new QVBoxLayout(body);
  this->ModelLabel->setObjectName("Model");
  this->StageLabel->setObjectName("Stage");
  this->PeakLabel->setObjectName("PeakStress");
  this->StatusLabel->setObjectName("Status");
  this->EstimateLabel->setObjectName("Estimate");
  this->ExportButton->setObjectName("ExportCSV");
  this->ChartWidget->setObjectName("Chart");
  for (QLabel* label :
    { this->ModelLabel, this->StageLabel, this->PeakLabel, this->StatusLabel, this->EstimateLabel })
  {
    label->setWordWrap(true);
    label->setTextInteractionFlags(Qt::TextSelectableByMouse);
  }
  QFont bold = this->ModelLabel->font();
  bold.setBold(true);
  this->ModelLabel->setFont(bold);
  auto* values = new QFormLayout();
  values->addRow("Stage:", this->StageLabel);
  values->addRow("Peak Stress:", this->PeakLabel);
  layout->addWidget(this->ModelLabel);
  layout->addLayout(values);
  this->ChartWidget->setMinimumSize(320, 260);
  layout->addWidget(this->ChartWidget, 1);
  layout->addWidget(this->StatusLabel);
  layout->addWidget(this->EstimateLabel);
  layout->addWidget(this->ExportButton, 0, Qt::AlignLeft);
  body->setObjectName("Body");
  this->setWidget(body);
  // Hidden until a test is started (or View > DEM Test shows it).
  this->hide();

  vtkNew<vtkGenericOpenGLRenderWindow> window;
  this->ChartWidget->setRenderWindow(window);
  this->View->SetRenderWindow(window);
  this->View->SetInteractor(this->ChartWidget->interactor());
  this->View->GetScene()->AddItem(this->Chart);
  this->Chart->SetShowLegend(true);
  this->Chart->GetLegend()->SetHorizontalAlignment(vtkChartLegend::LEFT);
  this->Chart->GetLegend()->SetVerticalAlignment(vtkChartLegend::TOP);
  this->Chart->GetAxis(vtkAxis::BOTTOM)->SetTitle(StrainColumn);
  this->Chart->GetAxis(vtkAxis::LEFT)->SetTitle("Stress (MPa)");
  this->Chart->GetAxis(vtkAxis::RIGHT)->SetTitle("Volumetric Strain (%)");
  this->Chart->GetTitleProperties()->SetFontSize(12);

  this->RefreshTimer.setSingleShot(true);
  QObject::connect(&this->RefreshTimer, &QTimer::timeout, this, &pqRockDEMTestDock::refresh);
  QObject::connect(this->ExportButton, &QPushButton::clicked, this, &pqRockDEMTestDock::exportCSV);

  pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
  QObject::connect(&pqActiveObjects::instance(), &pqActiveObjects::sourceChanged, this,
    &pqRockDEMTestDock::onActiveSourceChanged);
  QObject::connect(
    model, &pqServerManagerModel::sourceAdded, this, &pqRockDEMTestDock::onSourceAdded);
  QObject::connect(
    model, &pqServerManagerModel::sourceRemoved, this, &pqRockDEMTestDock::onSourceRemoved);
  QObject::connect(model, &pqServerManagerModel::viewAdded, this, &pqRockDEMTestDock::onViewAdded);
  for (pqView* view : model->findItems<pqView*>())
  {
    this->onViewAdded(view);
  }
  for (pqPipelineSource* source : model->findItems<pqPipelineSource*>())
  {
    this->onSourceAdded(source);
  }
  this->refresh();
}

pqRockDEMTestDock::~pqRockDEMTestDock() = default;

void pqRockDEMTestDock::onViewAdded(pqView* view)
{
  QObject::connect(view, &pqView::endRender, this, &pqRockDEMTestDock::scheduleRefresh,
    Qt::UniqueConnection);
}

void pqRockDEMTestDock::onSourceAdded(pqPipelineSource* source)
{
  if (!pqRockDEMAutoStart::isLoadTest(source))
  {
    return;
  }
  QObject::connect(source, &pqProxy::modifiedStateChanged, this,
    &pqRockDEMTestDock::onModifiedStateChanged, Qt::UniqueConnection);
  if (source->modifiedState() == pqProxy::UNMODIFIED)
  {
    // Made by a script (the GUI makes proxies uninitialized until Apply).
    this->PendingStart = source;
  }
}

void pqRockDEMTestDock::onSourceRemoved(pqPipelineSource* source)
{
  if (source == this->Followed)
  {
    this->Followed = nullptr;
    this->scheduleRefresh();
  }
}

void pqRockDEMTestDock::onModifiedStateChanged(pqServerManagerModelItem* item)
{
  auto* source = qobject_cast<pqPipelineSource*>(item);
  if (source && source->modifiedState() == pqProxy::UNMODIFIED)
  {
    this->PendingStart = source; // just applied: a test starts if its Mode is one
  }
}

void pqRockDEMTestDock::onActiveSourceChanged(pqPipelineSource* source)
{
  if (pqRockDEMAutoStart::isLoadTest(source))
  {
    this->follow(source);
  }
}

void pqRockDEMTestDock::follow(pqPipelineSource* source)
{
  if (!pqRockDEMAutoStart::isLoadTest(source) || source == this->Followed)
  {
    return;
  }
  this->Followed = source;
  this->refresh();
}

void pqRockDEMTestDock::testStarted(pqPipelineSource* source)
{
  this->Followed = source;
  this->show();
  this->raise();
}

void pqRockDEMTestDock::scheduleRefresh()
{
  const qint64 now = QDateTime::currentMSecsSinceEpoch();
  const qint64 wait = std::max<qint64>(0, RefreshPeriodMs - (now - this->LastRefresh));
  if (!this->RefreshTimer.isActive())
  {
    this->RefreshTimer.start(static_cast<int>(wait));
  }
}

void pqRockDEMTestDock::plotRows(vtkTable* history, vtkTable* plotted)
{
  plotted->Initialize();
  if (!history)
  {
    return;
  }
  vtkDataArray* stage = vtkDataArray::SafeDownCast(history->GetColumnByName("Stage"));
  const vtkIdType rows = history->GetNumberOfRows();
  bool anyShear = false;
  for (vtkIdType r = 0; stage && r < rows; ++r)
  {
    anyShear = anyShear || stage->GetTuple1(r) == ShearStage;
  }
  std::vector<const char*> names{ StrainColumn };
  for (const Series& s : PlottedSeries)
  {
    names.push_back(s.column);
  }
  for (const char* name : names)
  {
    vtkDataArray* source = vtkDataArray::SafeDownCast(history->GetColumnByName(name));
    vtkNew<vtkDoubleArray> column;
    column->SetName(name);
    for (vtkIdType r = 0; source && r < rows; ++r)
    {
      if (!anyShear || stage->GetTuple1(r) == ShearStage)
      {
        column->InsertNextValue(source->GetTuple1(r));
      }
    }
    plotted->AddColumn(column);
  }
}

void pqRockDEMTestDock::refresh()
{
  this->LastRefresh = QDateTime::currentMSecsSinceEpoch();
  if (this->PendingStart)
  {
    vtkSMProxy* pending = this->PendingStart->getProxy();
    if (vtkSMPropertyHelper(pending, "Mode").GetAsInt() != vtkDEMLoadTest::MODE_OFF &&
      vtkSMSourceProxy::SafeDownCast(pending)->GetDataInformation(0)->GetNumberOfPoints() > 0)
    {
      pqPipelineSource* started = this->PendingStart;
      this->PendingStart = nullptr;
      this->testStarted(started);
    }
  }
  this->Chart->ClearPlots();
  this->Plotted->Initialize();
  vtkSMProxy* proxy = this->Followed ? this->Followed->getProxy() : nullptr;
  this->ExportButton->setEnabled(proxy != nullptr);
  if (!proxy)
  {
    this->ModelLabel->setText("No DEM Load Test: apply one, or select one in the Pipeline Browser.");
    for (QLabel* label : { this->StageLabel, this->PeakLabel, this->StatusLabel, this->EstimateLabel })
    {
      label->setText(QString());
    }
    this->Chart->SetTitle("");
    this->ChartWidget->renderWindow()->Render();
    return;
  }
  proxy->UpdatePropertyInformation();
  static const char* const modeNames[] = { "Off", "Compression", "Tension", "Triaxial", "Isotropic", "Brazilian" };
  const int m = vtkSMPropertyHelper(proxy, "Mode").GetAsInt();
  this->ModelLabel->setText(QString("%1 (Mode %2)")
                              .arg(this->Followed->getSMName())
                              .arg(m >= 0 && m <= 5 ? QString(modeNames[m]) : QString::number(m)));
  this->StageLabel->setText(
    pqRockDEMReadOnlyWidget::text(proxy->GetProperty("Stage")));
  this->PeakLabel->setText(
    QString("%1 MPa").arg(vtkSMPropertyHelper(proxy, "PeakStress").GetAsDouble() * 1e-6, 0, 'g', 4));
  this->StatusLabel->setText(pqRockDEMReadOnlyWidget::text(proxy->GetProperty("Status")));
  const double steps = vtkSMPropertyHelper(proxy, "EstimatedSteps", true).GetAsDouble();
  const double seconds = vtkSMPropertyHelper(proxy, "EstimatedRunTime", true).GetAsDouble();
  this->EstimateLabel->setText(steps > 0.0
      ? QString("Estimated: %1 steps, about %2 of computing for the whole stage.")
          .arg(steps, 0, 'g', 4)
          .arg(formatDuration(seconds))
      : QString());

  auto* algorithm = vtkAlgorithm::SafeDownCast(proxy->GetClientSideObject());
  if (!algorithm)
  {
    this->Chart->SetTitle("The chart reads the test in this process: connect to the built-in server.");
    this->ChartWidget->renderWindow()->Render();
    return;
  }
  plotRows(vtkTable::SafeDownCast(algorithm->GetOutputDataObject(1)), this->Plotted);
  const bool curve = this->Plotted->GetNumberOfRows() >= 2;
  this->Chart->SetTitle(curve ? "" : "No test history yet: Play runs the test");
  for (const Series& s : PlottedSeries)
  {
    if (!curve)
    {
      break;
    }
    vtkPlot* line = this->Chart->AddPlot(vtkChart::LINE);
    line->SetInputData(this->Plotted, StrainColumn, s.column);
    line->SetColor(s.rgb[0], s.rgb[1], s.rgb[2], 255);
    line->SetWidth(2.0);
    line->GetPen()->SetLineType(s.line);
    this->Chart->SetPlotCorner(line, s.corner);
  }
  this->Chart->RecalculateBounds();
  this->ChartWidget->renderWindow()->Render();
}

void pqRockDEMTestDock::exportCSV()
{
  vtkSMProxy* proxy = this->Followed ? this->Followed->getProxy() : nullptr;
  auto* test = proxy ? vtkDEMLoadTest::SafeDownCast(proxy->GetClientSideObject()) : nullptr;
  if (!test)
  {
    return;
  }
  pqFileDialog dialog(nullptr, pqCoreUtilities::mainWidget(), "Export Test History", QString(),
    "CSV files (*.csv)");
  dialog.setObjectName("ExportHistoryDialog");
  dialog.setFileMode(pqFileDialog::AnyFile);
  if (dialog.exec() != QDialog::Accepted || dialog.getSelectedFiles().isEmpty())
  {
    return;
  }
  const QString path = dialog.getSelectedFiles()[0];
  if (!test->WriteHistory(path.toUtf8().data()))
  {
    QMessageBox::warning(this, "Export Test History", test->GetLastExportMessage());
  }
}
