#include "vtkDEMModelFromPoints.h"

#include "dem/Errors.h"
#include "dem/Model.h"
#include "dem/Overlaps.h"

#include <vtkDataArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

vtkStandardNewMacro(vtkDEMModelFromPoints);

namespace
{
std::string PointText(vtkIdType i, const double x[3])
{
  return "point " + std::to_string(i) + " (" + dem::formatValue(x[0]) + ", " +
    dem::formatValue(x[1]) + ", " + dem::formatValue(x[2]) + ")";
}

/// An optional point array with the expected number of components, or null.
vtkDataArray* OptionalArray(vtkPointData* pd, const char* name, int components)
{
  vtkDataArray* a = pd->GetArray(name);
  if (a && a->GetNumberOfComponents() != components)
  {
    throw dem::InputError(std::string("Input array '") + name + "' has " +
      std::to_string(a->GetNumberOfComponents()) + " components; expected " +
      std::to_string(components) + ".");
  }
  return a;
}
}

vtkDEMModelFromPoints::vtkDEMModelFromPoints()
{
  this->FitToInput = 1;
}

int vtkDEMModelFromPoints::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

int vtkDEMModelFromPoints::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  this->LastMessageText.clear();
  try
  {
    vtkPointSet* input = vtkPointSet::GetData(inputVector[0], 0);
    if (!input)
    {
      throw dem::InputError("DEM Model From Points needs a point set input (vtkPolyData or "
                            "vtkUnstructuredGrid with points and a Radius array).");
    }
    const vtkIdType n = input->GetNumberOfPoints();
    if (n == 0)
    {
      throw dem::InputError("DEM Model From Points: the input has no points, so there is no "
                            "particle to build a model from (connect a point set with at least "
                            "one point and a Radius array).");
    }
    vtkPointData* pd = input->GetPointData();
    vtkDataArray* radius = pd->GetArray("Radius");
    if (!radius || radius->GetNumberOfComponents() != 1)
    {
      throw dem::InputError("Input has no point array named 'Radius' with one component: "
                            "every point needs a particle radius in m.");
    }
    vtkDataArray* velocity = OptionalArray(pd, "Velocity", 3);
    vtkDataArray* angular = OptionalArray(pd, "AngularVelocity", 3);
    vtkDataArray* fixed = OptionalArray(pd, "Fixed", 1);

    // Check every point before building anything.
    double lo[3] = { std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
      std::numeric_limits<double>::max() };
    double hi[3] = { -lo[0], -lo[1], -lo[2] };
    for (vtkIdType i = 0; i < n; ++i)
    {
      double x[3];
      input->GetPoint(i, x);
      if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
      {
        throw dem::InputError("Input " + PointText(i, x) +
          " has a non-finite coordinate: every coordinate must be a finite number (m).");
      }
      const double r = radius->GetComponent(i, 0);
      if (!(r > 0.0) || !std::isfinite(r))
      {
        throw dem::InputError("Radius of input " + PointText(i, x) + " = " + dem::formatValue(r) +
          " m is out of range: it must be a finite number > 0 m.");
      }
      for (int k = 0; k < 3; ++k)
      {
        lo[k] = std::min(lo[k], x[k] - r);
        hi[k] = std::max(hi[k], x[k] + r);
      }
    }

    double origin[3] = { this->OriginX, this->OriginY, this->OriginZ };
    double size[3] = { this->XDimension, this->YDimension, this->ZDimension };
    if (this->FitToInput)
    {
      for (int k = 0; k < 3; ++k)
      {
        origin[k] = lo[k];
        size[k] = hi[k] - lo[k];
      }
      if (this->Section2D)
      {
        // The slab thickness is the Z Dimension, centred on the points' mid-plane.
        const double mid = 0.5 * (lo[2] + hi[2]);
        size[2] = this->ZDimension;
        origin[2] = mid - 0.5 * size[2];
      }
      this->WarnIfFitReplacesBox(origin, size);
    }

    dem::Model model;
    this->ConfigureModel(model, origin, size);
    const dem::Domain& d = model.domain;
    model.particles.reserve(static_cast<std::size_t>(n));
    const int movingAxes = d.section2D ? 2 : 3;
    vtkIdType movedToMidPlane = 0;
    for (vtkIdType i = 0; i < n; ++i)
    {
      double x[3];
      input->GetPoint(i, x);
      for (int k = 0; k < movingAxes; ++k)
      {
        const double l = d.origin[k];
        const double h = l + d.size[k];
        if (d.periodic[k])
        {
          x[k] = l + (x[k] - l) - d.size[k] * std::floor((x[k] - l) / d.size[k]);
        }
        else if (x[k] < l || x[k] > h)
        {
          static const char* const axis[3] = { "X", "Y", "Z" };
          throw dem::InputError("Input " + PointText(i, x) + " lies outside the model box along " +
            axis[k] + ": valid range is [" + dem::formatValue(l) + ", " + dem::formatValue(h) +
            "] m (turn Fit To Input on, or enlarge the box).");
        }
      }
      if (d.section2D && x[2] != d.midPlaneZ())
      {
        x[2] = d.midPlaneZ();
        ++movedToMidPlane;
      }
      std::uint32_t flags = 0;
      if (fixed && fixed->GetComponent(i, 0) != 0.0)
      {
        flags |= dem::FlagFixed;
      }
      const std::size_t slot = model.particles.size();
      model.particles.append(dem::Vec3(x[0], x[1], x[2]), radius->GetComponent(i, 0), i, flags);
      if (velocity)
      {
        model.particles.velocity[slot] = dem::Vec3(
          velocity->GetComponent(i, 0), velocity->GetComponent(i, 1), velocity->GetComponent(i, 2));
      }
      if (angular)
      {
        model.particles.angularVelocity[slot] = dem::Vec3(
          angular->GetComponent(i, 0), angular->GetComponent(i, 1), angular->GetComponent(i, 2));
      }
    }
    if (d.section2D)
    {
      for (std::size_t i = 0; i < model.particles.size(); ++i)
      {
        // In-plane motion only: no z velocity, rotation about z only.
        model.particles.velocity[i].z() = 0.0;
        model.particles.angularVelocity[i].x() = 0.0;
        model.particles.angularVelocity[i].y() = 0.0;
      }
    }
    model.nextId = static_cast<std::int64_t>(n);
    dem::updateMassProperties(model);
    // Particle ids are the input point indices: the engine's messages name the points.
    dem::requireDistinctCentres(d, model.particles);
    if (movedToMidPlane > 0)
    {
      this->ReportInfo("2D Section (XY): " + std::to_string(movedToMidPlane) +
        " points were placed on the mid-plane z = " + dem::formatValue(d.midPlaneZ()) + " m.");
    }
    const dem::OverlapReport overlaps = dem::measureOverlaps(model);
    if (overlaps.pairs > 0)
    {
      this->ReportWarning(std::to_string(overlaps.pairs) + " pair(s) of input spheres overlap; the " +
        "largest overlap is " + dem::formatValue(overlaps.largest) + " m (" +
        dem::formatValue(100.0 * overlaps.largestRelative) + " % of the smaller radius), between " +
        "points " + std::to_string(overlaps.idA) + " and " + std::to_string(overlaps.idB) +
        ". Overlapping particles push apart hard when the model runs; Current Porosity counts the " +
        "volume two particles share once.");
    }
    this->PublishModel(model, outputVector);
    return 1;
  }
  catch (const std::exception& e)
  {
    this->ReportFailure(e.what(), outputVector);
    return 0;
  }
}

void vtkDEMModelFromPoints::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
