/**
 * @class   vtkDEMSection
 * @brief   Cuts a RockDEM model with a plane: the exact circle of every sphere the plane
 *          cuts, the intact bonds crossing it and the traces of the broken bonds near it.
 *
 * The reference guide's "Cut sections" (Add Section XZ / YZ / XY), drawn: see
 * dem/Section.h and Documentation/Sections.md. Section XY, XZ or YZ cuts across Z, Y or
 * X through Origin; Custom cuts with any Normal.
 *
 * Input: a RockDEM model (vtkDEMModelConversion.h). The section follows time: with a
 * stepped upstream model (DEM Load Test) it is cut from the model at the time asked for,
 * so it plays with the animation. Outputs (vtkPolyData):
 * - port 0 "Section": one polygon (Circle Sides vertices on the exact circle) per cut
 *   particle, carrying that particle's point arrays of the Particles block as cell arrays
 *   (Id, Radius, Displacement, Stress, MeanStress, VonMisesStress, SizeClass, ...) plus
 *   SectionRadius (m, sqrt(R^2 - d^2)) and Distance (m, signed, of its centre from the
 *   plane). A 2D section model is its own section: every disc, in the model plane.
 * - port 1 "Bond Crossings": one vertex per intact bond whose segment between the centres
 *   crosses the plane, at the crossing point, carrying the bond's cell arrays of the Bonds
 *   block as point arrays (in 2D: every intact bond at its contact point).
 * - port 2 "Broken Bond Traces": one closed polyline per broken bond whose contact point
 *   lies within Trace Distance of the plane: its crack (a disc of the bond radius, normal
 *   along the bond) projected onto the plane, carrying the bond's cell arrays (FailureMode
 *   for colouring) plus Distance (m).
 * A plane that cuts nothing gives empty outputs and a warning that says so (not an
 * error). Invalid parameters are reported with vtkErrorMacro naming the parameter, its
 * value and the valid range; the outputs are then empty.
 */
#ifndef vtkDEMSection_h
#define vtkDEMSection_h

#include "RockDEMFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // for the read-only message

class ROCKDEMFILTERS_EXPORT vtkDEMSection : public vtkPolyDataAlgorithm
{
public:
  static vtkDEMSection* New();
  vtkTypeMacro(vtkDEMSection, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Section: 0 XY (normal Z), 1 XZ (normal Y), 2 YZ (normal X), 3 Custom (Normal).
  vtkSetMacro(Section, int);
  vtkGetMacro(Section, int);
  ///@}

  ///@{
  /// A point of the plane, m.
  vtkSetVector3Macro(Origin, double);
  vtkGetVector3Macro(Origin, double);
  ///@}

  ///@{
  /// The plane's normal (Section Custom; any non-zero length).
  vtkSetVector3Macro(Normal, double);
  vtkGetVector3Macro(Normal, double);
  ///@}

  ///@{
  /// Broken bonds whose contact point lies within this distance of the plane leave a
  /// trace, m (>= 0; 0 = half the mean particle diameter).
  vtkSetMacro(TraceDistance, double);
  vtkGetMacro(TraceDistance, double);
  ///@}

  ///@{
  /// Vertices of each circle polygon and of each trace (>= 3; the geometry is exact at
  /// the vertices).
  vtkSetMacro(CircleSides, int);
  vtkGetMacro(CircleSides, int);
  ///@}

  ///@{
  /// Read-only values of the last execution (0 after an error).
  vtkGetMacro(NumberOfCutParticles, vtkIdType);
  vtkGetMacro(NumberOfCrossingBonds, vtkIdType);
  vtkGetMacro(NumberOfTraces, vtkIdType);
  vtkGetMacro(UsedTraceDistance, double);
  const char* GetLastMessage() const { return this->LastMessageText.c_str(); }
  ///@}

protected:
  vtkDEMSection();
  ~vtkDEMSection() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Section;
  double Origin[3];
  double Normal[3];
  double TraceDistance;
  int CircleSides;

  vtkIdType NumberOfCutParticles;
  vtkIdType NumberOfCrossingBonds;
  vtkIdType NumberOfTraces;
  double UsedTraceDistance;
  std::string LastMessageText;

private:
  vtkDEMSection(const vtkDEMSection&) = delete;
  void operator=(const vtkDEMSection&) = delete;
};

#endif
