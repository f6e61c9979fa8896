/**
 * @class   vtkDEMInstantStage
 * @brief   Common base of the instantaneous RockDEM stages that turn a model into a model
 *          (DEM Cement, DEM Specimen, DEM Seed Fractures).
 *
 * Input port 0 is a RockDEM model (vtkMultiBlockDataSet, see vtkDEMModelConversion.h);
 * output port 0 is the model the stage makes of it. The base holds the pipeline contract
 * these stages share (DESIGN.md, time contract):
 * - the output publishes no time steps (the upstream times are not the stage's to publish);
 * - a stepped upstream model is read at a fixed time, where its run ended, so changing the
 *   animation time never re-runs the stage before this one;
 * - the output is stamped with the time asked for (the result does not depend on time);
 * - a failure (dem::InputError or any other exception from the engine) is reported with
 *   vtkErrorMacro naming the parameter, its value and the valid range, the read-only
 *   values are cleared and the output is left empty (never half-built).
 *
 * A subclass implements StageName(), Execute() and ClearResults().
 */
#ifndef vtkDEMInstantStage_h
#define vtkDEMInstantStage_h

#include "RockDEMFiltersModule.h" // for export macro
#include "vtkMultiBlockDataSetAlgorithm.h"

#include <string> // for the read-only message

class ROCKDEMFILTERS_EXPORT vtkDEMInstantStage : public vtkMultiBlockDataSetAlgorithm
{
public:
  vtkTypeMacro(vtkDEMInstantStage, vtkMultiBlockDataSetAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Read-only: the last report line, or the error of the last execution (empty when none).
  const char* GetLastMessage() const { return this->LastMessageText.c_str(); }

protected:
  vtkDEMInstantStage();
  ~vtkDEMInstantStage() override;

  /// Port 0 takes a model (vtkMultiBlockDataSet); a subclass with more ports extends it.
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// The name users see in front of the stage's messages, e.g. "DEM Cement".
  virtual const char* StageName() const = 0;

  /// Makes the output model from the inputs and sets the read-only values. Returns the
  /// report line to show in Output Messages and keep as Last Message, or an empty string
  /// when there is nothing new to report (a cached result re-output). Throws on bad input.
  virtual std::string Execute(vtkInformationVector** inputVector, vtkMultiBlockDataSet* output) = 0;

  /// Resets the read-only values after a failed execution (they read 0 then).
  virtual void ClearResults() = 0;

  // A result, not a parameter: setting it must not call Modified().
  std::string LastMessageText;

private:
  vtkDEMInstantStage(const vtkDEMInstantStage&) = delete;
  void operator=(const vtkDEMInstantStage&) = delete;
};

#endif
