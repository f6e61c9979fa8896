/**
 * @class   vtkDEMModelFromPoints
 * @brief   Turns any point set with a Radius array into a RockDEM model.
 *
 * Each input point becomes a particle of that radius (m). Optional point arrays:
 * Velocity (m/s, 3 components), AngularVelocity (rad/s, 3 components) and Fixed
 * (non-zero: the particle does not move). The model box and the material come from
 * the same properties as vtkDEMPackSource. With Fit To Input on (the default) the box
 * is the bounding box of the spheres (each point +/- its radius); in a 2D section its
 * Z extent is the slab thickness (Z Dimension) centred on the points.
 *
 * Packs from other tools and hand-built test configurations (two spheres about to
 * collide) enter the pipeline this way.
 */
#ifndef vtkDEMModelFromPoints_h
#define vtkDEMModelFromPoints_h

#include "RockDEMFiltersModule.h" // for export macro
#include "vtkDEMModelSourceBase.h"

class ROCKDEMFILTERS_EXPORT vtkDEMModelFromPoints : public vtkDEMModelSourceBase
{
public:
  static vtkDEMModelFromPoints* New();
  vtkTypeMacro(vtkDEMModelFromPoints, vtkDEMModelSourceBase);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkDEMModelFromPoints();
  ~vtkDEMModelFromPoints() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkDEMModelFromPoints(const vtkDEMModelFromPoints&) = delete;
  void operator=(const vtkDEMModelFromPoints&) = delete;
};

#endif
