/**
 * @class   vtkDEMModelSourceBase
 * @brief   Common base of the algorithms that create a RockDEM model: the model box
 *          and the material properties.
 *
 * Output port 0 is the model (vtkMultiBlockDataSet, see vtkDEMModelConversion.h);
 * output port 1 is the domain box as an outline (vtkPolyData, empty when
 * ShowDomainBox is off). Input port 0 is optional; subclasses say what it means.
 *
 * Units are SI: lengths in m, density in kg/m^3, moduli in Pa.
 *
 * Invalid parameters are reported with vtkErrorMacro naming the parameter, its value
 * and the valid range; the outputs are then left empty (never half-built).
 */
#ifndef vtkDEMModelSourceBase_h
#define vtkDEMModelSourceBase_h

#include "RockDEMFiltersModule.h" // for export macro
#include "vtkMultiBlockDataSetAlgorithm.h"

#include <string> // for ReportInfo

namespace dem
{
struct Model;
}

class ROCKDEMFILTERS_EXPORT vtkDEMModelSourceBase : public vtkMultiBlockDataSetAlgorithm
{
public:
  vtkTypeMacro(vtkDEMModelSourceBase, vtkMultiBlockDataSetAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Minimum corner of the model box, m.
  vtkSetMacro(OriginX, double);
  vtkGetMacro(OriginX, double);
  vtkSetMacro(OriginY, double);
  vtkGetMacro(OriginY, double);
  vtkSetMacro(OriginZ, double);
  vtkGetMacro(OriginZ, double);
  ///@}

  ///@{
  /// Size of the model box, m. In a 2D section the Z dimension is the slab thickness.
  vtkSetMacro(XDimension, double);
  vtkGetMacro(XDimension, double);
  vtkSetMacro(YDimension, double);
  vtkGetMacro(YDimension, double);
  vtkSetMacro(ZDimension, double);
  vtkGetMacro(ZDimension, double);
  ///@}

  ///@{
  /// Join the two faces of an axis (no walls on that axis).
  vtkSetMacro(PeriodicX, vtkTypeBool);
  vtkGetMacro(PeriodicX, vtkTypeBool);
  vtkBooleanMacro(PeriodicX, vtkTypeBool);
  vtkSetMacro(PeriodicY, vtkTypeBool);
  vtkGetMacro(PeriodicY, vtkTypeBool);
  vtkBooleanMacro(PeriodicY, vtkTypeBool);
  vtkSetMacro(PeriodicZ, vtkTypeBool);
  vtkGetMacro(PeriodicZ, vtkTypeBool);
  vtkBooleanMacro(PeriodicZ, vtkTypeBool);
  ///@}

  ///@{
  /// 2D section in the XY plane: discs at mid-slab; the Z dimension is the slab thickness.
  vtkSetMacro(Section2D, vtkTypeBool);
  vtkGetMacro(Section2D, vtkTypeBool);
  vtkBooleanMacro(Section2D, vtkTypeBool);
  ///@}

  ///@{
  /// Size and position the box over the bounds of the input (when one is connected).
  vtkSetMacro(FitToInput, vtkTypeBool);
  vtkGetMacro(FitToInput, vtkTypeBool);
  vtkBooleanMacro(FitToInput, vtkTypeBool);
  ///@}

  ///@{
  /// Produce the domain box outline on output port 1.
  vtkSetMacro(ShowDomainBox, vtkTypeBool);
  vtkGetMacro(ShowDomainBox, vtkTypeBool);
  vtkBooleanMacro(ShowDomainBox, vtkTypeBool);
  ///@}

  ///@{
  /// Material: Density (kg/m^3), Young's Modulus (Pa), Poisson's Ratio (-),
  /// Restitution (-, 0-1), Friction (-), Rolling Friction (-).
  vtkSetMacro(Density, double);
  vtkGetMacro(Density, double);
  vtkSetMacro(YoungsModulus, double);
  vtkGetMacro(YoungsModulus, double);
  vtkSetMacro(PoissonsRatio, double);
  vtkGetMacro(PoissonsRatio, double);
  vtkSetMacro(Restitution, double);
  vtkGetMacro(Restitution, double);
  vtkSetMacro(Friction, double);
  vtkGetMacro(Friction, double);
  vtkSetMacro(RollingFriction, double);
  vtkGetMacro(RollingFriction, double);
  ///@}

  /// Read-only: normal stiffness (N/m) of a linear contact between two particles of
  /// the largest size in the model, derived from Young's Modulus (updated on execute).
  vtkGetMacro(ContactStiffness, double);
  /// Read-only: Current Porosity of the model built by the last execution (1 when empty).
  vtkGetMacro(CurrentPorosity, double);
  /// Read-only: number of particles in the model built by the last execution.
  vtkGetMacro(NumberOfElements, vtkIdType);
  /// Read-only: the last error or report line (empty when none).
  const char* GetLastMessage() const { return this->LastMessageText.c_str(); }

protected:
  vtkDEMModelSourceBase();
  ~vtkDEMModelSourceBase() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;

  /// Box from the properties, or from the input's bounds when FitToInput is on and an
  /// input is connected. Writes origin[3] and size[3]; returns false with a message when
  /// the input has no bounds (throws dem::InputError).
  void ResolveBox(vtkInformationVector** inputVector, double origin[3], double size[3]);

  /// Sets the model's domain (from origin/size and the periodic and 2D flags), its
  /// material, and gravity (-Z, or -Y in a 2D section), then validates both.
  /// Throws dem::InputError.
  void ConfigureModel(dem::Model& model, const double origin[3], const double size[3]) const;

  /// Writes the model to output port 0 and its domain outline to port 1, and updates
  /// the read-only values (Current Porosity, Contact Stiffness, number of elements).
  void PublishModel(const dem::Model& model, vtkInformationVector* outputVector);

  /// Reports an error (vtkErrorMacro, shown in ParaView's Output Messages) and
  /// empties both outputs so nothing half-built is shown.
  void ReportFailure(const char* what, vtkInformationVector* outputVector);
  /// Reports an informational line (ParaView's Output Messages) and keeps it as LastMessage.
  void ReportInfo(const std::string& line);

  /// A warning: Output Messages (vtkWarningMacro) and Last Message.
  void ReportWarning(const std::string& line);

  /// With Fit To Input on, warns when the Origin or Dimensions differ from their defaults
  /// (the user set a box) that the fitted box (origin, size in m) replaces them.
  void WarnIfFitReplacesBox(const double origin[3], const double size[3]);

  double OriginX, OriginY, OriginZ;
  double XDimension, YDimension, ZDimension;
  vtkTypeBool PeriodicX, PeriodicY, PeriodicZ;
  vtkTypeBool Section2D;
  vtkTypeBool FitToInput;
  vtkTypeBool ShowDomainBox;

  double Density;
  double YoungsModulus;
  double PoissonsRatio;
  double Restitution;
  double Friction;
  double RollingFriction;

  double ContactStiffness;
  double CurrentPorosity;
  vtkIdType NumberOfElements;
  // A result, not a parameter: setting it must not call Modified().
  std::string LastMessageText;

private:
  vtkDEMModelSourceBase(const vtkDEMModelSourceBase&) = delete;
  void operator=(const vtkDEMModelSourceBase&) = delete;
};

#endif
