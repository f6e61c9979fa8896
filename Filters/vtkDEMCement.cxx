#include "vtkDEMCement.h"

#include "vtkDEMModelConversion.h"

#include "dem/Bonds.h"
#include "dem/Cement.h"
#include "dem/Errors.h"
#include "dem/Model.h"

#include <vtkInformationVector.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkObjectFactory.h>
#include <vtkSmartPointer.h>

#include <cstdint>
#include <string>

vtkStandardNewMacro(vtkDEMCement);

struct vtkDEMCement::vtkInternals
{
  bool Valid = false;
  vtkMTimeType BuildTime = 0; ///< this filter's MTime when the cache was built
  vtkMTimeType InputTime = 0; ///< the input data's MTime when the cache was built
  /// The cemented model as VTK data: a pure time change re-outputs it without cementing.
  vtkSmartPointer<vtkMultiBlockDataSet> Output;
};

vtkDEMCement::vtkDEMCement()
  : GapTolerance(0.05)
  , BondRange(1.0)
  , BondRadiusMultiplier(1.0)
  , BondModulus(1.0e9)
  , BondStiffnessRatio(0.4)
  , BondNormalStiffness(0.0)
  , TensileStrength(10.0e6)
  , Cohesion(20.0e6)
  , FrictionAngle(30.0)
  , MomentContribution(1.0)
  , SofteningRatio(0.0)
  , StrengthScatter(0.0)
  , RandomSeed(1)
  , NumberOfBonds(0)
  , BondedCoordination(0.0)
  , NumberOfBrokenBonds(0)
  , Damage(0.0)
  , BrokenInTension(0)
  , BrokenInShear(0)
  , BondStiffness(0.0)
  , Internals(new vtkInternals)
{
}

vtkDEMCement::~vtkDEMCement()
{
  delete this->Internals;
}

const char* vtkDEMCement::StageName() const
{
  return "DEM Cement";
}

void vtkDEMCement::ClearResults()
{
  this->NumberOfBonds = 0;
  this->BondedCoordination = 0.0;
  this->NumberOfBrokenBonds = 0;
  this->Damage = 0.0;
  this->BrokenInTension = 0;
  this->BrokenInShear = 0;
  this->BondStiffness = 0.0;
}

std::string vtkDEMCement::Execute(vtkInformationVector** inputVector, vtkMultiBlockDataSet* output)
{
  vtkInternals& in = *this->Internals;
  auto* input = vtkMultiBlockDataSet::GetData(inputVector[0], 0);
  const bool stale = !in.Valid || this->GetMTime() > in.BuildTime ||
    (input ? input->GetMTime() : 0) != in.InputTime;
  std::string line; // nothing new to report when the cached model is re-output
  if (stale)
  {
    in.Valid = false;
    in.Output = nullptr;
    dem::CementParameters params;
    params.gapTolerance = this->GapTolerance;
    params.bondRange = this->BondRange;
    params.bondRadiusMultiplier = this->BondRadiusMultiplier;
    params.bondModulus = this->BondModulus;
    params.bondStiffnessRatio = this->BondStiffnessRatio;
    params.bondNormalStiffness = this->BondNormalStiffness;
    params.tensileStrength = this->TensileStrength;
    params.cohesion = this->Cohesion;
    params.frictionAngle = this->FrictionAngle;
    params.momentContribution = this->MomentContribution;
    params.softeningRatio = this->SofteningRatio;
    params.strengthScatter = this->StrengthScatter;
    params.randomSeed = static_cast<std::uint64_t>(static_cast<std::uint32_t>(this->RandomSeed));
    dem::validate(params);

    dem::Model model = rockdem::MultiBlockToModel(input);
    const dem::CementReport report = dem::cement(model, params);
    const dem::BondCounts counts = dem::countBonds(model.bonds);

    auto cemented = vtkSmartPointer<vtkMultiBlockDataSet>::New();
    rockdem::ModelToMultiBlock(model, cemented);
    in.Output = cemented;
    this->NumberOfBonds = static_cast<vtkIdType>(counts.installed);
    this->BondedCoordination = report.bondedCoordination;
    this->NumberOfBrokenBonds = static_cast<vtkIdType>(counts.broken);
    this->Damage = counts.damage();
    this->BrokenInTension = static_cast<vtkIdType>(counts.tension);
    this->BrokenInShear = static_cast<vtkIdType>(counts.shear);
    this->BondStiffness = report.bondStiffness;
    in.BuildTime = this->GetMTime();
    in.InputTime = input ? input->GetMTime() : 0;
    in.Valid = true;
    line = report.summary();
  }
  // A pure time change re-outputs the cemented model without cementing again.
  output->ShallowCopy(in.Output);
  return line;
}

void vtkDEMCement::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "GapTolerance: " << this->GapTolerance << "\n";
  os << indent << "BondRange: " << this->BondRange << "\n";
  os << indent << "BondRadiusMultiplier: " << this->BondRadiusMultiplier << "\n";
  os << indent << "BondModulus: " << this->BondModulus << " Pa\n";
  os << indent << "BondStiffnessRatio: " << this->BondStiffnessRatio << "\n";
  os << indent << "BondNormalStiffness: " << this->BondNormalStiffness << " N/m^3\n";
  os << indent << "TensileStrength: " << this->TensileStrength << " Pa\n";
  os << indent << "Cohesion: " << this->Cohesion << " Pa\n";
  os << indent << "FrictionAngle: " << this->FrictionAngle << " degrees\n";
  os << indent << "MomentContribution: " << this->MomentContribution << "\n";
  os << indent << "SofteningRatio: " << this->SofteningRatio << "\n";
  os << indent << "StrengthScatter: " << this->StrengthScatter << "\n";
  os << indent << "RandomSeed: " << this->RandomSeed << "\n";
  os << indent << "Bonds: " << this->NumberOfBonds << "\n";
  os << indent << "BondedCoordination: " << this->BondedCoordination << "\n";
  os << indent << "BrokenBonds: " << this->NumberOfBrokenBonds << "\n";
  os << indent << "Damage: " << this->Damage << "\n";
  os << indent << "BrokenInTension: " << this->BrokenInTension << "\n";
  os << indent << "BrokenInShear: " << this->BrokenInShear << "\n";
  os << indent << "BondStiffness: " << this->BondStiffness << " N/m^3\n";
}
