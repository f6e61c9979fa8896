/**
 * @class   pqRockDEMTestDock
 * @brief   The DEM Test dock: the stress-strain chart of a DEM Load Test (View > DEM Test).
 *
 * The reference guide's DEM Test tab. It plots the followed load test's History (output
 * port 1): axial, lateral and deviator stress in MPa against axial strain in %, and
 * volumetric strain in % on the right-hand axis. Strains count from the start of shearing,
 * so a test with a shear stage plots its shear rows only (a triaxial test's consolidation
 * would otherwise run to the consolidation strain and back). Above the chart: the stage,
 * Peak Stress and the status line; below it the estimate of the stage (steps and run time)
 * and "Export CSV...", which writes the test history (the engine's columns, a header
 * naming them) to a file.
 *
 * It follows the active DEM Load Test, or the one whose test was just started; it opens
 * (and comes to the front) when a test is started: a DEM Load Test with a test mode is
 * applied, or first shown from Python. It refreshes after renders, at most twice a second,
 * so it keeps up while Play runs. The chart reads the test's table in this process (the
 * built-in server); with a remote server it says so.
 *
 * Object names for ParaView's recorded GUI tests: the chart widget "Chart", the labels
 * "Model", "Stage", "PeakStress", "Status", "Estimate", the button "ExportCSV".
 */
#ifndef pqRockDEMTestDock_h
#define pqRockDEMTestDock_h

#include <QDockWidget>
#include <pqPipelineSource.h> // for QPointer<pqPipelineSource>
#include <QPointer>
#include <QTimer>
#include <vtkNew.h>

class QLabel;
class QPushButton;
class QVTKOpenGLNativeWidget;
class pqServerManagerModelItem;
class pqView;
class vtkChartXY;
class vtkContextView;
class vtkTable;

class pqRockDEMTestDock : public QDockWidget
{
  Q_OBJECT
  typedef QDockWidget Superclass;

public:
  pqRockDEMTestDock(QWidget* parent = nullptr);
  ~pqRockDEMTestDock() override;

  /// The load test shown (nullptr: none).
  pqPipelineSource* followed() const { return this->Followed; }

  /// The rows plotted from a History table: the plot columns of the shear rows (Stage 2)
  /// when there are any, else of every row. Public for the tests.
  static void plotRows(vtkTable* history, vtkTable* plotted);

public Q_SLOTS:
  /// Shows this load test (a DEM Load Test; anything else is ignored).
  void follow(pqPipelineSource* source);
  /// Redraws now from the followed test's current data.
  void refresh();
  /// Asks for a file name and writes the followed test's history as CSV.
  void exportCSV();

private Q_SLOTS:
  void onActiveSourceChanged(pqPipelineSource* source);
  void onSourceAdded(pqPipelineSource* source);
  void onSourceRemoved(pqPipelineSource* source);
  void onModifiedStateChanged(pqServerManagerModelItem* item);
  void onViewAdded(pqView* view);
  void scheduleRefresh();

private:
  Q_DISABLE_COPY(pqRockDEMTestDock)

  /// A test was started on this load test: follow it and bring the dock to the front.
  void testStarted(pqPipelineSource* source);

  QPointer<pqPipelineSource> Followed;
  QPointer<pqPipelineSource> PendingStart; ///< applied with a test mode, not yet shown
  QLabel* ModelLabel;
  QLabel* StageLabel;
  QLabel* PeakLabel;
  QLabel* StatusLabel;
  QLabel* EstimateLabel;
  QPushButton* ExportButton;
  QVTKOpenGLNativeWidget* ChartWidget;
  vtkNew<vtkContextView> View;
  vtkNew<vtkChartXY> Chart;
  vtkNew<vtkTable> Plotted;
  QTimer RefreshTimer;
  qint64 LastRefresh = 0;
};

#endif
