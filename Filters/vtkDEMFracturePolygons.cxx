#include "vtkDEMFracturePolygons.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

namespace rockdem
{
std::vector<dem::FracturePolygon> FracturePolygons(vtkPolyData* data, std::vector<vtkIdType>* cells)
{
  std::vector<dem::FracturePolygon> polygons;
  if (cells)
  {
    cells->clear();
  }
  vtkPoints* points = data ? data->GetPoints() : nullptr;
  if (!points)
  {
    return polygons;
  }
  auto vertex = [&](vtkIdType id) {
    double x[3];
    points->GetPoint(id, x);
    return dem::Vec3(x[0], x[1], x[2]);
  };
  // Cell ids run over verts, lines, polys, strips in that order.
  vtkIdType cell = data->GetNumberOfVerts() + data->GetNumberOfLines();
  vtkIdType npts = 0;
  const vtkIdType* ids = nullptr;
  if (data->GetPolys())
  {
    auto it = vtkSmartPointer<vtkCellArrayIterator>::Take(data->GetPolys()->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++cell)
    {
      it->GetCurrentCell(npts, ids);
      dem::FracturePolygon poly;
      for (vtkIdType k = 0; k < npts; ++k)
      {
        poly.push_back(vertex(ids[k]));
      }
      polygons.push_back(std::move(poly));
      if (cells)
      {
        cells->push_back(cell);
      }
    }
  }
  if (data->GetStrips())
  {
    auto it = vtkSmartPointer<vtkCellArrayIterator>::Take(data->GetStrips()->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++cell)
    {
      it->GetCurrentCell(npts, ids);
      for (vtkIdType k = 0; k + 2 < npts; ++k)
      {
        polygons.push_back({ vertex(ids[k]), vertex(ids[k + 1]), vertex(ids[k + 2]) });
        if (cells)
        {
          cells->push_back(cell);
        }
      }
    }
  }
  return polygons;
}
}
