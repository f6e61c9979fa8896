/**
 * @class   vtkSMDEMPackSourceProxy
 * @brief   Client-side proxy of DEM Pack Source: records Add / Grow / Reset in the proxy.
 *
 * Add Elements, Grow Elements and Reset are command buttons (pvpython:
 * `pack.InvokeCommand('AddElements')`): they act on the algorithm, not on a property, so a
 * saved state (.pvsm) would not hold them and would rebuild a different pack. The
 * algorithm keeps the sequence pressed since the last reset (read-only CommandsInfo, e.g.
 * "AGAG"); this proxy copies it into the Commands property before its state is saved, and
 * loading the state sets Commands, which replays the presses: the same pack, bit for bit.
 * Used for the XML element `<DEMPackSourceProxy>`.
 */
#ifndef vtkSMDEMPackSourceProxy_h
#define vtkSMDEMPackSourceProxy_h

#include "RockDEMServerManagerModule.h" // for export macro
#include "vtkSMDEMSourceProxy.h"

class ROCKDEMSERVERMANAGER_EXPORT vtkSMDEMPackSourceProxy : public vtkSMDEMSourceProxy
{
public:
  static vtkSMDEMPackSourceProxy* New();
  vtkTypeMacro(vtkSMDEMPackSourceProxy, vtkSMDEMSourceProxy);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Copies the algorithm's command sequence (CommandsInfo) into the Commands property.
  void RecordCommands();

  /// Records the commands, then saves the state as usual.
  vtkPVXMLElement* SaveXMLState(vtkPVXMLElement* root, vtkSMPropertyIterator* iter) override;
  using Superclass::SaveXMLState;

protected:
  vtkSMDEMPackSourceProxy();
  ~vtkSMDEMPackSourceProxy() override;

private:
  vtkSMDEMPackSourceProxy(const vtkSMDEMPackSourceProxy&) = delete;
  void operator=(const vtkSMDEMPackSourceProxy&) = delete;
};

#endif
