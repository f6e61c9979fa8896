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

namespace dem
{
struct Model;
}

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

  /// 1 if the file is a regular file that starts with the RockDEM state file magic bytes
  /// or whose name ends in .rdem, damaged or not: the full checks run when it is read, and
  /// their message (truncated, corrupt, not a RockDEM state file, ...) reaches the user
  /// through File > Open instead of ParaView's "No reader found". 0 for a missing file.
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
  /// The error of the last read, or a note on the history CSV beside the file (rewritten
  /// because it was out of step with the state file); empty when none.
  const char* GetLastMessage() const { return this->LastMessageText.c_str(); }
  ///@}

protected:
  vtkDEMStateReader();
  ~vtkDEMStateReader() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// Makes the history CSV beside the file agree with the model read (dem::syncHistoryCSV)
  /// and says so in Last Message and Output Messages when it had to.
  void SyncHistory(const dem::Model& model);

  char* FileName = nullptr;
  double ModelTime = 0.0;
  vtkIdType Step = 0;
  vtkIdType NumberOfParticles = 0;
  vtkIdType NumberOfBonds = 0;
  vtkIdType NumberOfBrokenBonds = 0;
  std::string StageText = "idle";
  std::string ModeText = "Off";
  std::string LastMessageText;

private:
  vtkDEMStateReader(const vtkDEMStateReader&) = delete;
  void operator=(const vtkDEMStateReader&) = delete;
};

#endif
