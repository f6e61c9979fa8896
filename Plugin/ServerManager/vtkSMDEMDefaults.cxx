#include "vtkSMDEMDefaults.h"

#include "vtkObjectFactory.h"
#include "vtkSMSettings.h"

vtkStandardNewMacro(vtkSMDEMDefaults);

vtkSMDEMDefaults::vtkSMDEMDefaults() = default;
vtkSMDEMDefaults::~vtkSMDEMDefaults() = default;

const char* vtkSMDEMDefaults::GetSettingsJSON()
{
  // Colours: intact grey, tension red, shear blue, inherited green (the fracture sets'
  // colours of rockdem.FRACTURE_SET_COLORS).
  return R"json({
  "array_lookup_tables": {
    "FailureMode": {
      "PVLookupTable": {
        "IndexedLookup": 1,
        "AnnotationsInitialized": 1,
        "Annotations": ["0", "intact", "1", "tension", "2", "shear", "3", "inherited"],
        "IndexedColors": [0.75, 0.75, 0.75, 0.85, 0.15, 0.15, 0.15, 0.35, 0.85, 0.2, 0.7, 0.2],
        "IndexedOpacities": [1.0, 1.0, 1.0, 1.0]
      }
    }
  }
})json";
}

void vtkSMDEMDefaults::Register()
{
  static bool registered = false;
  if (!registered)
  {
    registered = true;
    // Priority 0.1: below the user's settings file (1.0) and the site settings.
    vtkSMSettings::GetInstance()->AddCollectionFromString(GetSettingsJSON(), 0.1);
  }
}

namespace
{
/// Registers the defaults when the plugin library is loaded.
struct RegisterOnLoad
{
  RegisterOnLoad() { vtkSMDEMDefaults::Register(); }
};
const RegisterOnLoad registerOnLoad;
}

void vtkSMDEMDefaults::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
