/**
 * @class   vtkDEMSpecimen
 * @brief   Carves a laboratory specimen (box, cylinder, disc) out of a dense RockDEM pack.
 *
 * See dem/Specimen.h and Documentation/Specimens.md. Input: a RockDEM model (see
 * vtkDEMModelConversion.h), usually a dense pack (DEM Pack Source, settled or
 * compacted); a stepped upstream model is read at its last time step. Output: the
 * particles whose centres lie inside the shape, with their bonds and contacts, in a model
 * box shrunk to their bounding box (walls there, no test running, no periodic axis), ready
 * for DEM Cement and DEM Load Test. In a 2D section: Box is a rectangle (Size X, Y), Disc
 * a disc in the plane (Axis Z); the slab is the thickness.
 *
 * The stage is instantaneous: its output publishes no time steps. Units are SI (m).
 * Invalid parameters (a shape that does not fit in the pack, a disc thicker than its
 * diameter, ...) are reported with vtkErrorMacro naming the parameter, its value and the
 * valid range; the output is then empty.
 */
#ifndef vtkDEMSpecimen_h
#define vtkDEMSpecimen_h

#include "RockDEMFiltersModule.h" // for export macro
#include "vtkDEMInstantStage.h"

class ROCKDEMFILTERS_EXPORT vtkDEMSpecimen : public vtkDEMInstantStage
{
public:
  static vtkDEMSpecimen* New();
  vtkTypeMacro(vtkDEMSpecimen, vtkDEMInstantStage);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Shape: 0 Box, 1 Cylinder (along Axis), 2 Disc (a short cylinder, Length <= Diameter).
  vtkSetMacro(Shape, int);
  vtkGetMacro(Shape, int);
  ///@}

  ///@{
  /// Axis of the cylinder or disc: 0 X, 1 Y, 2 Z (Z in a 2D section).
  vtkSetMacro(Axis, int);
  vtkGetMacro(Axis, int);
  ///@}

  ///@{
  /// Centre the specimen in the model box (1, default), or at Center (0).
  vtkSetMacro(CenterOnModel, int);
  vtkGetMacro(CenterOnModel, int);
  ///@}

  ///@{
  /// The specimen's centre when Center On Model is off, m.
  vtkSetVector3Macro(Center, double);
  vtkGetVector3Macro(Center, double);
  ///@}

  ///@{
  /// Box edge lengths along X, Y, Z, m (> 0; Z is not used in a 2D section).
  vtkSetVector3Macro(Size, double);
  vtkGetVector3Macro(Size, double);
  ///@}

  ///@{
  /// Cylinder or disc diameter, m (> 0).
  vtkSetMacro(Diameter, double);
  vtkGetMacro(Diameter, double);
  ///@}

  ///@{
  /// Cylinder length or disc thickness along Axis, m (> 0; a disc's <= Diameter; not used
  /// in a 2D section, whose slab is the thickness).
  vtkSetMacro(Length, double);
  vtkGetMacro(Length, double);
  ///@}

  ///@{
  /// Read-only values of the last execution (0 after an error): particles kept and
  /// removed, porosity of the specimen (1 - particle volume / shape volume).
  vtkGetMacro(NumberOfParticles, vtkIdType);
  vtkGetMacro(RemovedParticles, vtkIdType);
  vtkGetMacro(SpecimenPorosity, double);
  ///@}

protected:
  vtkDEMSpecimen();
  ~vtkDEMSpecimen() override;

  const char* StageName() const override;
  std::string Execute(vtkInformationVector** inputVector, vtkMultiBlockDataSet* output) override;
  void ClearResults() override;

  int Shape;
  int Axis;
  int CenterOnModel;
  double Center[3];
  double Size[3];
  double Diameter;
  double Length;

  vtkIdType NumberOfParticles;
  vtkIdType RemovedParticles;
  double SpecimenPorosity;

private:
  vtkDEMSpecimen(const vtkDEMSpecimen&) = delete;
  void operator=(const vtkDEMSpecimen&) = delete;
};

#endif
