#include "vtkDEMSpecimen.h"

#include "vtkDEMModelConversion.h"

#include "dem/Model.h"
#include "dem/Specimen.h"

#include <vtkInformationVector.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkObjectFactory.h>

vtkStandardNewMacro(vtkDEMSpecimen);

vtkDEMSpecimen::vtkDEMSpecimen()
  : Shape(1)
  , Axis(2)
  , CenterOnModel(1)
  , Diameter(0.05)
  , Length(0.1)
  , NumberOfParticles(0)
  , RemovedParticles(0)
  , SpecimenPorosity(0.0)
{
  this->Center[0] = this->Center[1] = this->Center[2] = 0.0;
  this->Size[0] = this->Size[1] = this->Size[2] = 0.05;
}

vtkDEMSpecimen::~vtkDEMSpecimen() = default;

const char* vtkDEMSpecimen::StageName() const
{
  return "DEM Specimen";
}

void vtkDEMSpecimen::ClearResults()
{
  this->NumberOfParticles = 0;
  this->RemovedParticles = 0;
  this->SpecimenPorosity = 0.0;
}

std::string vtkDEMSpecimen::Execute(vtkInformationVector** inputVector, vtkMultiBlockDataSet* output)
{
  dem::SpecimenSettings s;
  s.shape = dem::specimenShape(this->Shape);
  s.axis = this->Axis;
  s.centerOnModel = this->CenterOnModel != 0;
  s.center = dem::Vec3(this->Center[0], this->Center[1], this->Center[2]);
  s.size = dem::Vec3(this->Size[0], this->Size[1], this->Size[2]);
  s.diameter = this->Diameter;
  s.length = this->Length;
  dem::Model model = rockdem::MultiBlockToModel(vtkMultiBlockDataSet::GetData(inputVector[0], 0));
  const dem::SpecimenReport report = dem::carveSpecimen(model, s);
  rockdem::ModelToMultiBlock(model, output);
  this->NumberOfParticles = static_cast<vtkIdType>(report.kept);
  this->RemovedParticles = static_cast<vtkIdType>(report.removed.particles);
  this->SpecimenPorosity = report.porosity;
  return report.summary();
}

void vtkDEMSpecimen::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Shape: " << this->Shape << "\n";
  os << indent << "Axis: " << this->Axis << "\n";
  os << indent << "CenterOnModel: " << this->CenterOnModel << "\n";
  os << indent << "Center: " << this->Center[0] << " " << this->Center[1] << " " << this->Center[2] << " m\n";
  os << indent << "Size: " << this->Size[0] << " " << this->Size[1] << " " << this->Size[2] << " m\n";
  os << indent << "Diameter: " << this->Diameter << " m\n";
  os << indent << "Length: " << this->Length << " m\n";
  os << indent << "NumberOfParticles: " << this->NumberOfParticles << "\n";
  os << indent << "RemovedParticles: " << this->RemovedParticles << "\n";
  os << indent << "SpecimenPorosity: " << this->SpecimenPorosity << "\n";
}
