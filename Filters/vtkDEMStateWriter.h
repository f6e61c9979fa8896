/**
 * @class   vtkDEMStateWriter
 * @brief   Writes a RockDEM model to a state file (.rdem), with its test history as CSV.
 *
 * The reference guide's "Saving and reopening". Input: a RockDEM model (the output of any
 * RockDEM stage; a stepped model at the time it was last updated). The state file holds
 * the whole model (Documentation/StateFile.md) and is written to a temporary name beside
 * the target and renamed over it, so a crash never leaves a half-written file and a
 * failed write leaves the previous file as it was. When the model has a test history it
 * is also written beside it as CSV: "run.rdem" -> "run.history.csv".
 *
 * In ParaView: File > Save Data, type "RockDEM State File (*.rdem)"; in pvpython:
 * SaveData("run.rdem", proxy=loadTest). Errors are reported with vtkErrorMacro naming the
 * file and the cause.
 */
#ifndef vtkDEMStateWriter_h
#define vtkDEMStateWriter_h

#include "RockDEMFiltersModule.h" // for export macro
#include "vtkWriter.h"

class ROCKDEMFILTERS_EXPORT vtkDEMStateWriter : public vtkWriter
{
public:
  static vtkDEMStateWriter* New();
  vtkTypeMacro(vtkDEMStateWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The state file to write (conventionally *.rdem).
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /// Also write the test history as CSV beside the state file (default on).
  vtkSetMacro(WriteHistory, int);
  vtkGetMacro(WriteHistory, int);
  vtkBooleanMacro(WriteHistory, int);
  ///@}

  /// 1 when the last Write() succeeded.
  vtkGetMacro(LastWriteSucceeded, int);

protected:
  vtkDEMStateWriter();
  ~vtkDEMStateWriter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

  char* FileName = nullptr;
  int WriteHistory = 1;
  int LastWriteSucceeded = 0;

private:
  vtkDEMStateWriter(const vtkDEMStateWriter&) = delete;
  void operator=(const vtkDEMStateWriter&) = delete;
};

#endif
