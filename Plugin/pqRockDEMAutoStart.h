/**
 * @class   pqRockDEMAutoStart
 * @brief   GUI behaviours of the RockDEM plugin (ParaView client only).
 *
 * - Read-only values are current: ParaView pulls a proxy's information before the pipeline
 *   runs (on Apply) and not at all after a command button or a Play frame. After every
 *   render this pulls the read-only values of every RockDEM stage (a DEM Load Test also
 *   refreshes its published times: vtkSMDEMLoadTestProxy::RefreshAfterUpdate), so the
 *   Properties panel shows what was just computed.
 * - A DEM Load Test applied for the first time is shown at its first frame (the animation
 *   time goes to it), so Apply computes nothing ahead; Play then runs frame by frame.
 * - Play follows a DEM Load Test to the end of its run: it stops where the test finished
 *   (or the model settled), and when a stage with Number Of Frames 0 published more frames
 *   while it played (it learns how many it needs as it runs), Play goes on.
 * - A DEM Load Test's particles are coloured by their Displacement; DEM Fractures To DFN
 *   discs by Set, with the fracture sets' categorical map.
 *
 * Particles are drawn at their true size by the "DEM Spheres" representation (RockDEM.xml)
 * and FailureMode gets a categorical colour map from vtkSMDEMDefaults: both work without
 * the GUI too. The DEM Test dock is pqRockDEMTestDock.
 */
#ifndef pqRockDEMAutoStart_h
#define pqRockDEMAutoStart_h

#include <QObject>
#include <QPointer>
#include <QTimer>

class pqDataRepresentation;
class pqPipelineSource;
class pqRepresentation;
class pqServerManagerModelItem;
class pqView;

class pqRockDEMAutoStart : public QObject
{
  Q_OBJECT
  typedef QObject Superclass;

public:
  pqRockDEMAutoStart(QObject* p = nullptr);
  ~pqRockDEMAutoStart() override;

  void startup();
  void shutdown();

  /// Whether a pipeline source is one of RockDEM's (its XML name starts with "DEM").
  static bool isRockDEM(pqPipelineSource* source);
  /// Whether it is a DEM Load Test.
  static bool isLoadTest(pqPipelineSource* source);

  /// The default colouring of a RockDEM output (see the class description).
  static void colorByDefault(pqDataRepresentation* representation);

private Q_SLOTS:
  void onSourceAdded(pqPipelineSource* source);
  void onModifiedStateChanged(pqServerManagerModelItem* item);
  void onViewAdded(pqView* view);
  void onRepresentationAdded(pqRepresentation* representation);
  void refreshReadOnlyValues();
  void onEndPlay();

private:
  Q_DISABLE_COPY(pqRockDEMAutoStart)
  QTimer RefreshTimer;
};

#endif
