/**
 * @class   vtkSMDEMDefaults
 * @brief   RockDEM's colour-map defaults, registered with ParaView's settings when the
 *          plugin is loaded (GUI, pvpython, pvbatch).
 *
 * A bond's FailureMode is a category (0 intact, 1 tension, 2 shear, 3 inherited), so the
 * colour map made for an array of that name is categorical, with those four annotations
 * and fixed colours (grey, red, blue, green), instead of a continuous map over a degenerate
 * 0..0 range. The defaults are added at a low priority: a user's own settings win.
 */
#ifndef vtkSMDEMDefaults_h
#define vtkSMDEMDefaults_h

#include "RockDEMServerManagerModule.h" // for export macro
#include "vtkObject.h"

class ROCKDEMSERVERMANAGER_EXPORT vtkSMDEMDefaults : public vtkObject
{
public:
  static vtkSMDEMDefaults* New();
  vtkTypeMacro(vtkSMDEMDefaults, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The settings (JSON) RockDEM adds.
  static const char* GetSettingsJSON();
  /// Adds them to vtkSMSettings once (called when the plugin library is loaded).
  static void Register();

protected:
  vtkSMDEMDefaults();
  ~vtkSMDEMDefaults() override;

private:
  vtkSMDEMDefaults(const vtkSMDEMDefaults&) = delete;
  void operator=(const vtkSMDEMDefaults&) = delete;
};

#endif
