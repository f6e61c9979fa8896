/**
 * @class   vtkSMDEMLoadTestProxy
 * @brief   Client-side proxy of DEM Load Test: keeps its published times and read-only
 *          values current, and the animation on its time steps.
 *
 * The stage learns its timestep, and so the exact model time of each frame, when it runs;
 * with Number Of Frames 0 it also learns how many frames the test needs as it goes, and a
 * test that finishes ends its frames there. The algorithm counts these changes (read-only
 * TimeStepsRevision). After every update of this proxy (pvpython UpdatePipeline, Show) the
 * read-only values are pulled, and when the published times changed the pipeline
 * information is updated too, here and in every filter downstream (which copies the
 * stage's times), so `TimestepValues`, the time keeper and Play see them.
 * Whenever the pipeline information is updated, an animation scene still in Sequence mode
 * (the default of a pipeline built by a script) is switched to Snap To TimeSteps, so a
 * script's pipeline animates by the stage's frames. In the GUI the RockDEM plugin calls
 * RefreshAfterUpdate() after each render. Used for the XML element `<DEMLoadTestProxy>`.
 */
#ifndef vtkSMDEMLoadTestProxy_h
#define vtkSMDEMLoadTestProxy_h

#include "RockDEMServerManagerModule.h" // for export macro
#include "vtkSMDEMSourceProxy.h"

#include <set> // for the filters visited downstream

class ROCKDEMSERVERMANAGER_EXPORT vtkSMDEMLoadTestProxy : public vtkSMDEMSourceProxy
{
public:
  static vtkSMDEMLoadTestProxy* New();
  vtkTypeMacro(vtkSMDEMLoadTestProxy, vtkSMDEMSourceProxy);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Update the pipeline information as usual, then snap a Sequence-mode animation to
  /// the data time steps (see the class description).
  void UpdatePipelineInformation() override;

  /// Pulls the read-only values; when the published times changed since the last call,
  /// updates the pipeline information as well. Returns true when the times changed.
  bool RefreshAfterUpdate() override;

protected:
  vtkSMDEMLoadTestProxy();
  ~vtkSMDEMLoadTestProxy() override;

private:
  vtkSMDEMLoadTestProxy(const vtkSMDEMLoadTestProxy&) = delete;
  void operator=(const vtkSMDEMLoadTestProxy&) = delete;

  void SnapAnimationToTimeSteps();
  /// UpdatePipelineInformation() on every filter downstream of proxy, once each.
  void UpdateDownstreamInformation(vtkSMProxy* proxy, std::set<vtkSMProxy*>& visited);

  int KnownRevision = -1;
  bool InRefresh = false;
};

#endif
