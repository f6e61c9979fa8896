/**
 * @file vtkDEMFracturePolygons.h
 * @brief A fracture network given as VTK polygonal data, as the engine's polygons (not
 *        wrapped). Used by DEM Seed Fractures and DEM Voxelize.
 */
#ifndef vtkDEMFracturePolygons_h
#define vtkDEMFracturePolygons_h

#include "dem/SeedFractures.h"

#include <vtkType.h>

#include <vector>

class vtkPolyData;

namespace rockdem
{
/// The polygons, triangles and quads (Polys) of `data`, and its triangle strips split into
/// triangles, as planar fracture polygons (vertex coordinates in m). With `cells`, the
/// cell id each polygon came from (a strip's triangles share the strip's id).
std::vector<dem::FracturePolygon> FracturePolygons(vtkPolyData* data, std::vector<vtkIdType>* cells = nullptr);
}

#endif
