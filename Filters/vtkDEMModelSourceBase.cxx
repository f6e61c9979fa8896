#include "vtkDEMModelSourceBase.h"

#include "vtkDEMModelConversion.h"

#include "dem/Errors.h"
#include "dem/Model.h"
#include "dem/Pack.h"

#include <vtkDataObject.h>
#include <vtkDataSet.h>
#include <vtkCompositeDataSet.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkOutputWindow.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>

vtkDEMModelSourceBase::vtkDEMModelSourceBase()
  : OriginX(0.0)
  , OriginY(0.0)
  , OriginZ(0.0)
  , XDimension(0.1)
  , YDimension(0.1)
  , ZDimension(0.1)
  , PeriodicX(0)
  , PeriodicY(0)
  , PeriodicZ(0)
  , Section2D(0)
  , FitToInput(0)
  , ShowDomainBox(1)
  , Density(2650.0)
  , YoungsModulus(1.0e9)
  , PoissonsRatio(0.25)
  , Restitution(0.5)
  , Friction(0.5)
  , RollingFriction(0.0)
  , ContactStiffness(0.0)
  , CurrentPorosity(1.0)
  , NumberOfElements(0)
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(2);
}

vtkDEMModelSourceBase::~vtkDEMModelSourceBase() = default;

int vtkDEMModelSourceBase::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

int vtkDEMModelSourceBase::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkMultiBlockDataSet" : "vtkPolyData");
  return 1;
}

void vtkDEMModelSourceBase::ResolveBox(
  vtkInformationVector** inputVector, double origin[3], double size[3])
{
  origin[0] = this->OriginX;
  origin[1] = this->OriginY;
  origin[2] = this->OriginZ;
  size[0] = this->XDimension;
  size[1] = this->YDimension;
  size[2] = this->ZDimension;
  vtkDataObject* input = nullptr;
  if (this->GetNumberOfInputConnections(0) > 0)
  {
    input = vtkDataObject::GetData(inputVector[0], 0);
  }
  if (!this->FitToInput || !input)
  {
    return;
  }
  double bounds[6] = { 1, -1, 1, -1, 1, -1 };
  if (auto* ds = vtkDataSet::SafeDownCast(input))
  {
    ds->GetBounds(bounds);
  }
  else if (auto* cd = vtkCompositeDataSet::SafeDownCast(input))
  {
    cd->GetBounds(bounds);
  }
  if (!(bounds[0] <= bounds[1] && bounds[2] <= bounds[3] && bounds[4] <= bounds[5]))
  {
    throw dem::InputError("Fit To Input: the input has no points, so it has no bounds to fit "
                          "the model box to (connect a dataset with points, or turn Fit To Input off).");
  }
  static const char* const axisName[3] = { "X", "Y", "Z" };
  for (int k = 0; k < 3; ++k)
  {
    const double extent = bounds[2 * k + 1] - bounds[2 * k];
    origin[k] = bounds[2 * k];
    if (extent > 0.0)
    {
      size[k] = extent;
    }
    else
    {
      // A flat input (e.g. a map-view surface) gives no extent on this axis: keep the
      // box dimension the user set, starting at the input's coordinate.
      this->ReportInfo(std::string("Fit To Input: the input is flat along ") + axisName[k] +
        "; keeping " + axisName[k] + " Dimension = " + dem::formatValue(size[k]) + " m.");
    }
  }
  this->WarnIfFitReplacesBox(origin, size);
}

void vtkDEMModelSourceBase::ConfigureModel(
  dem::Model& model, const double origin[3], const double size[3]) const
{
  dem::Domain& d = model.domain;
  d.origin = dem::Vec3(origin[0], origin[1], origin[2]);
  d.size = dem::Vec3(size[0], size[1], size[2]);
  d.periodic = { { this->PeriodicX != 0, this->PeriodicY != 0, this->PeriodicZ != 0 } };
  d.section2D = this->Section2D != 0;
  dem::Material& m = model.material;
  m.density = this->Density;
  m.youngsModulus = this->YoungsModulus;
  m.poissonsRatio = this->PoissonsRatio;
  m.restitution = this->Restitution;
  m.friction = this->Friction;
  m.rollingFriction = this->RollingFriction;
  model.gravity = d.section2D ? dem::Vec3(0.0, -9.81, 0.0) : dem::Vec3(0.0, 0.0, -9.81);
  dem::validate(d);
  dem::validate(m);
}

void vtkDEMModelSourceBase::PublishModel(const dem::Model& model, vtkInformationVector* outputVector)
{
  auto* out = vtkMultiBlockDataSet::GetData(outputVector, 0);
  auto* box = vtkPolyData::GetData(outputVector, 1);
  rockdem::ModelToMultiBlock(model, out);
  if (this->ShowDomainBox)
  {
    rockdem::DomainBoxToPolyData(model.domain, box);
  }
  else
  {
    box->Initialize();
  }
  const auto& r = model.particles.radius;
  const double largest = r.empty() ? 0.0 : *std::max_element(r.begin(), r.end());
  this->ContactStiffness =
    largest > 0.0 ? dem::derivedContactStiffness(model.material, model.domain, largest) : 0.0;
  this->CurrentPorosity = dem::currentPorosity(model);
  this->NumberOfElements = static_cast<vtkIdType>(model.particles.size());
}

void vtkDEMModelSourceBase::ReportFailure(const char* what, vtkInformationVector* outputVector)
{
  vtkErrorMacro(<< what);
  this->LastMessageText = what;
  if (auto* out = vtkMultiBlockDataSet::GetData(outputVector, 0))
  {
    out->Initialize();
  }
  if (auto* box = vtkPolyData::GetData(outputVector, 1))
  {
    box->Initialize();
  }
  this->NumberOfElements = 0;
  this->CurrentPorosity = 1.0;
  this->ContactStiffness = 0.0;
}

void vtkDEMModelSourceBase::ReportWarning(const std::string& line)
{
  this->LastMessageText = line;
  vtkWarningMacro(<< line);
}

void vtkDEMModelSourceBase::WarnIfFitReplacesBox(const double origin[3], const double size[3])
{
  // The box properties at their defaults (0 and 0.1 m) were not set. In a 2D section the
  // Z Dimension is the slab thickness, which fitting keeps.
  const double set[6] = { this->OriginX, this->OriginY, this->OriginZ, this->XDimension,
    this->YDimension, this->Section2D ? 0.1 : this->ZDimension };
  const double defaults[6] = { 0.0, 0.0, 0.0, 0.1, 0.1, 0.1 };
  if (!this->FitToInput || std::equal(set, set + 6, defaults))
  {
    return;
  }
  auto triple = [](const double v[3]) {
    return "(" + dem::formatValue(v[0]) + ", " + dem::formatValue(v[1]) + ", " + dem::formatValue(v[2]) + ") m";
  };
  const double userOrigin[3] = { this->OriginX, this->OriginY, this->OriginZ };
  const double userSize[3] = { this->XDimension, this->YDimension, this->ZDimension };
  this->ReportWarning("Fit To Input is on: the box you set (Origin " + triple(userOrigin) +
    ", Dimensions " + triple(userSize) + ") is replaced by the box fitted to the input (origin " +
    triple(origin) + ", size " + triple(size) + "). Turn Fit To Input off to use your box.");
}

void vtkDEMModelSourceBase::ReportInfo(const std::string& line)
{
  this->LastMessageText = line;
  vtkOutputWindowDisplayText((std::string(this->GetClassName()) + ": " + line + "\n").c_str());
}

void vtkDEMModelSourceBase::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Origin: " << this->OriginX << " " << this->OriginY << " " << this->OriginZ << " m\n";
  os << indent << "Dimensions: " << this->XDimension << " " << this->YDimension << " "
     << this->ZDimension << " m\n";
  os << indent << "Periodic: " << this->PeriodicX << " " << this->PeriodicY << " " << this->PeriodicZ << "\n";
  os << indent << "Section2D: " << this->Section2D << "\n";
  os << indent << "FitToInput: " << this->FitToInput << "\n";
  os << indent << "ShowDomainBox: " << this->ShowDomainBox << "\n";
  os << indent << "Density: " << this->Density << " kg/m^3\n";
  os << indent << "YoungsModulus: " << this->YoungsModulus << " Pa\n";
  os << indent << "PoissonsRatio: " << this->PoissonsRatio << "\n";
  os << indent << "Restitution: " << this->Restitution << "\n";
  os << indent << "Friction: " << this->Friction << "\n";
  os << indent << "RollingFriction: " << this->RollingFriction << "\n";
  os << indent << "ContactStiffness: " << this->ContactStiffness << " N/m\n";
  os << indent << "CurrentPorosity: " << this->CurrentPorosity << "\n";
  os << indent << "NumberOfElements: " << this->NumberOfElements << "\n";
  os << indent << "LastMessage: " << this->LastMessageText << "\n";
}
