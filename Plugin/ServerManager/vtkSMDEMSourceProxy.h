/**
 * @class   vtkSMDEMSourceProxy
 * @brief   Client-side proxy of a RockDEM stage: its read-only values follow its updates.
 *
 * ParaView pulls a proxy's information-only properties (the read-only values: Current
 * Porosity, Bonds, Stage, ...) when its pipeline information is updated, which happens
 * before the stage runs. This proxy pulls them again after every update of its pipeline
 * (pvpython UpdatePipeline, Show), so `pack.CurrentPorosity` is the value of the pack just
 * computed. In the GUI the RockDEM plugin calls RefreshAfterUpdate() after each render.
 * Used for the XML element `<DEMSourceProxy>`; subclasses refine RefreshAfterUpdate().
 */
#ifndef vtkSMDEMSourceProxy_h
#define vtkSMDEMSourceProxy_h

#include "RockDEMServerManagerModule.h" // for export macro
#include "vtkSMSourceProxy.h"

class ROCKDEMSERVERMANAGER_EXPORT vtkSMDEMSourceProxy : public vtkSMSourceProxy
{
public:
  static vtkSMDEMSourceProxy* New();
  vtkTypeMacro(vtkSMDEMSourceProxy, vtkSMSourceProxy);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Update as usual, then RefreshAfterUpdate().
  void UpdatePipeline() override;
  void UpdatePipeline(double time) override;
  ///@}

  /// Pulls the read-only values. Returns true when more than the values changed (see
  /// vtkSMDEMLoadTestProxy).
  virtual bool RefreshAfterUpdate();

protected:
  vtkSMDEMSourceProxy();
  ~vtkSMDEMSourceProxy() override;

private:
  vtkSMDEMSourceProxy(const vtkSMDEMSourceProxy&) = delete;
  void operator=(const vtkSMDEMSourceProxy&) = delete;
};

#endif
