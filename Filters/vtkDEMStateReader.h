/**
 * @class   vtkDEMStateReader
 * @brief   Reads a RockDEM state file (.rdem) into a RockDEM model.
 *
 * The reference guide's "Saving and reopening": the state file holds the whole model
 * (particles, contacts with their slip and rolling history, bonds with their state,
 * walls and servo state, the load-test state machine and history, clock, random state
 * and every parameter), see Documentation/StateFile.md. The output is the model as a
 * RockDEM multiblock (vtkDEMModelConversion.h), at the time it was saved; connect a
 * DEM Load Test to continue the run exactly where it stopped.
 *
 * A missing, truncated, corrupt or unknown-version file is reported with vtkErrorMacro
 * naming the file and the problem; the output is then empty.
 */
#ifndef vtkDEMStateReader_h
#define vtkDEMStateReader_h

#include "RockDEMFiltersModule.h" // for export macro
#include "vtkMultiBlockDataSetAlgorithm.h"

#include <string> // for the read-only strings

class ROCKDEMFILTERS_EXPORT vtkDEMStateReader : public vtkMultiBlockDataSetAlgorithm
{
public:
  static vtkDEMStateReader* New();
  vtkTypeMacro(vtkDEMStateReader, vtkMultiBlockDataSetAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The state file to read.
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  /// 1 if the file starts with the RockDEM state file magic bytes (the full checks run
  /// when it is read).
  static int CanReadFile(const char* fileName);

  ///@{
  /// Read-only values of the last read.
  vtkGetMacro(ModelTime, double);            ///< s, the saved model clock
  vtkGetMacro(Step, vtkIdType);              ///< physics steps taken
  vtkGetMacro(NumberOfParticles, vtkIdType);
  vtkGetMacro(NumberOfBonds, vtkIdType);
  vtkGetMacro(NumberOfBrokenBonds, vtkIdType);
  const char* GetStage() const { return this->StageText.c_str(); } ///< "idle", "shear", ...
  const char* GetTestMode() const { return this->ModeText.c_str(); } ///< "Off", "Triaxial", ...
  ///@}

protected:
  vtkDEMStateReader();
  ~vtkDEMStateReader() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;
  double ModelTime = 0.0;
  vtkIdType Step = 0;
  vtkIdType NumberOfParticles = 0;
  vtkIdType NumberOfBonds = 0;
  vtkIdType NumberOfBrokenBonds = 0;
  std::string StageText = "idle";
  std::string ModeText = "Off";

private:
  vtkDEMStateReader(const vtkDEMStateReader&) = delete;
  void operator=(const vtkDEMStateReader&) = delete;
};

#endif
