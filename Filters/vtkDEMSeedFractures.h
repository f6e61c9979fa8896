/**
 * @class   vtkDEMSeedFractures
 * @brief   Seeds a cemented RockDEM model with mapped fractures: every bond whose
 *          segment between the particle centres crosses a fracture polygon starts broken.
 *
 * The reference guide's "Current limitations" (seeding from an existing DFN), done
 * properly. Input 0: a cemented RockDEM model (vtkDEMModelConversion.h); a stepped
 * upstream model is read at its last time step. Input 1 (Fractures): any polygonal data
 * set: polygons, triangles, quads and triangle strips are all accepted (a DFN from
 * DEM Fractures To DFN, a surface from any reader). Output: the same model with those
 * bonds broken, FailureMode 3 (inherited), failure time = the model's time (see
 * dem/SeedFractures.h and Documentation/Fractures.md). Bonds already broken keep their
 * mode. The stage is instantaneous: its output publishes no time steps.
 */
#ifndef vtkDEMSeedFractures_h
#define vtkDEMSeedFractures_h

#include "RockDEMFiltersModule.h" // for export macro
#include "vtkMultiBlockDataSetAlgorithm.h"

#include <string> // for the read-only message

class ROCKDEMFILTERS_EXPORT vtkDEMSeedFractures : public vtkMultiBlockDataSetAlgorithm
{
public:
  static vtkDEMSeedFractures* New();
  vtkTypeMacro(vtkDEMSeedFractures, vtkMultiBlockDataSetAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Connects the fracture polygons (input port 1).
  void SetFracturesConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }

  ///@{
  /// Read-only values of the last execution (0 after an error).
  vtkGetMacro(NumberOfSeededBonds, vtkIdType);   ///< Seeded Bonds: bonds broken now
  vtkGetMacro(NumberOfPolygons, vtkIdType);      ///< fracture polygons read
  vtkGetMacro(NumberOfAlreadyBroken, vtkIdType); ///< crossing bonds that were already broken
  const char* GetLastMessage() const { return this->LastMessageText.c_str(); }
  ///@}

protected:
  vtkDEMSeedFractures();
  ~vtkDEMSeedFractures() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkIdType NumberOfSeededBonds;
  vtkIdType NumberOfPolygons;
  vtkIdType NumberOfAlreadyBroken;
  std::string LastMessageText;

private:
  vtkDEMSeedFractures(const vtkDEMSeedFractures&) = delete;
  void operator=(const vtkDEMSeedFractures&) = delete;
};

#endif
