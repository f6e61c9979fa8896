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
#include "vtkDEMInstantStage.h"

class ROCKDEMFILTERS_EXPORT vtkDEMSeedFractures : public vtkDEMInstantStage
{
public:
  static vtkDEMSeedFractures* New();
  vtkTypeMacro(vtkDEMSeedFractures, vtkDEMInstantStage);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Connects the fracture polygons (input port 1).
  void SetFracturesConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }

  ///@{
  /// Read-only values of the last execution (0 after an error).
  vtkGetMacro(NumberOfSeededBonds, vtkIdType);   ///< Seeded Bonds: bonds broken now
  vtkGetMacro(NumberOfPolygons, vtkIdType);      ///< fracture polygons read
  vtkGetMacro(NumberOfAlreadyBroken, vtkIdType); ///< crossing bonds that were already broken
  ///@}

protected:
  vtkDEMSeedFractures();
  ~vtkDEMSeedFractures() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  const char* StageName() const override;
  std::string Execute(vtkInformationVector** inputVector, vtkMultiBlockDataSet* output) override;
  void ClearResults() override;

  vtkIdType NumberOfSeededBonds;
  vtkIdType NumberOfPolygons;
  vtkIdType NumberOfAlreadyBroken;

private:
  vtkDEMSeedFractures(const vtkDEMSeedFractures&) = delete;
  void operator=(const vtkDEMSeedFractures&) = delete;
};

#endif
