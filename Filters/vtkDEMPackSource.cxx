#include "vtkDEMPackSource.h"

#include "dem/Errors.h"
#include "dem/MemoryEstimate.h"
#include "dem/Model.h"
#include "dem/Pack.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>

#include <cstring>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkDEMPackSource);

namespace
{
/// Everything that shapes the pack: a change rebuilds it. The material shapes it only
/// through Compact Elements (it runs the solver), so it counts once that command is used.
std::vector<double> PackSignature(const dem::PackParameters& p, const dem::Domain& d,
  const dem::CompactParameters& c, const dem::Material& m, bool compacting)
{
  const dem::FineZone& f = p.fineZone;
  std::vector<double> signature = { static_cast<double>(p.initialElements), p.minimumSize,
    p.maximumSize, p.targetPorosity, static_cast<double>(p.randomSeed), f.enabled ? 1.0 : 0.0,
    f.origin.x(), f.origin.y(), f.origin.z(), f.size.x(), f.size.y(), f.size.z(), f.minimumSize,
    f.maximumSize, d.origin.x(), d.origin.y(), d.origin.z(), d.size.x(), d.size.y(), d.size.z(),
    d.periodic[0] ? 1.0 : 0.0, d.periodic[1] ? 1.0 : 0.0, d.periodic[2] ? 1.0 : 0.0,
    d.section2D ? 1.0 : 0.0 };
  if (compacting)
  {
    signature.insert(signature.end(), { c.stressCeiling, c.equilibriumRatio, m.density, m.youngsModulus,
      m.poissonsRatio, m.restitution });
  }
  return signature;
}
}

struct vtkDEMPackSource::vtkInternals
{
  bool Valid = false;
  dem::Model Model;
  std::vector<double> Signature;
  std::string AppliedCommands;
};

vtkDEMPackSource::vtkDEMPackSource()
  : InitialElements(2000)
  , MinimumSize(0.002)
  , MaximumSize(0.004)
  , TargetPorosity(0.4)
  , RandomSeed(1)
  , FineZone(0)
  , FineZoneMinimumSize(0.001)
  , FineZoneMaximumSize(0.002)
  , MaximumLockedInStress(0.0)
  , EquilibriumRatio(0.01)
  , LockedInStress(0.0)
  , LargestOverlap(0.0)
  , EstimatedMemory(0.0)
  , Internals(new vtkInternals)
{
  for (int k = 0; k < 3; ++k)
  {
    this->FineZoneOrigin[k] = 0.0;
    this->FineZoneDimensions[k] = 0.0;
  }
}

vtkDEMPackSource::~vtkDEMPackSource()
{
  delete this->Internals;
}

void vtkDEMPackSource::AddElements()
{
  this->Commands.push_back('A');
  this->Modified();
}

void vtkDEMPackSource::GrowElements()
{
  this->Commands.push_back('G');
  this->Modified();
}

void vtkDEMPackSource::CompactElements()
{
  this->Commands.push_back('C');
  this->Modified();
}

void vtkDEMPackSource::SetCommands(const char* commands)
{
  const std::string wanted = commands ? commands : "";
  if (wanted == this->Commands)
  {
    return;
  }
  // A sequence that does not extend the one applied is replayed from a fresh pack.
  if (wanted.compare(0, this->Commands.size(), this->Commands) != 0)
  {
    this->Internals->Valid = false;
  }
  this->Commands = wanted;
  this->Modified();
}

void vtkDEMPackSource::ResetPack()
{
  this->Commands.clear();
  this->Internals->Valid = false;
  this->Modified();
}

dem::PackParameters vtkDEMPackSource::PackSettings() const
{
  dem::PackParameters params;
  params.initialElements = this->InitialElements;
  params.minimumSize = this->MinimumSize;
  params.maximumSize = this->MaximumSize;
  params.targetPorosity = this->TargetPorosity;
  params.randomSeed = static_cast<std::uint64_t>(static_cast<std::uint32_t>(this->RandomSeed));
  params.fineZone.enabled = this->FineZone != 0;
  params.fineZone.origin =
    dem::Vec3(this->FineZoneOrigin[0], this->FineZoneOrigin[1], this->FineZoneOrigin[2]);
  params.fineZone.size = dem::Vec3(
    this->FineZoneDimensions[0], this->FineZoneDimensions[1], this->FineZoneDimensions[2]);
  params.fineZone.minimumSize = this->FineZoneMinimumSize;
  params.fineZone.maximumSize = this->FineZoneMaximumSize;
  return params;
}

dem::Model vtkDEMPackSource::ConfiguredModel(vtkInformationVector** inputVector)
{
  double origin[3];
  double size[3];
  this->ResolveBox(inputVector, origin, size);
  dem::Model configured;
  this->ConfigureModel(configured, origin, size);
  return configured;
}

int vtkDEMPackSource::RequestInformation(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Before the pack is built: the memory of the particles it will make
  // (dem/MemoryEstimate.h). Invalid settings give 0 here and their error in RequestData.
  this->EstimatedMemory = 0.0;
  try
  {
    const dem::Model configured = this->ConfiguredModel(inputVector);
    const bool adds = this->Commands.find('A') != std::string::npos;
    this->EstimatedMemory =
      dem::estimateMemory(dem::expectedParticleCount(this->PackSettings(), configured.domain, adds));
  }
  catch (const std::exception&)
  {
  }
  return this->Superclass::RequestInformation(request, inputVector, outputVector);
}

int vtkDEMPackSource::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInternals& cache = *this->Internals;
  try
  {
    dem::Model configured = this->ConfiguredModel(inputVector);

    const dem::PackParameters params = this->PackSettings();
    dem::validate(params, configured.domain);
    const std::size_t bad = this->Commands.find_first_not_of("AGC");
    if (bad != std::string::npos)
    {
      throw dem::InputError("Commands = '" + this->Commands + "' has '" +
        this->Commands.substr(bad, 1) + "' at position " + std::to_string(bad + 1) +
        ": the recorded commands are 'A' (Add Elements), 'G' (Grow Elements) and "
        "'C' (Compact Elements).");
    }
    dem::CompactParameters compact;
    compact.targetPorosity = this->TargetPorosity;
    compact.stressCeiling = this->MaximumLockedInStress;
    compact.equilibriumRatio = this->EquilibriumRatio;
    dem::validate(compact);

    const bool compacting = this->Commands.find('C') != std::string::npos;
    const std::vector<double> signature =
      PackSignature(params, configured.domain, compact, configured.material, compacting);
    const bool reusable = cache.Valid && cache.Signature == signature &&
      this->Commands.compare(0, cache.AppliedCommands.size(), cache.AppliedCommands) == 0;
    if (!reusable)
    {
      cache.Valid = false;
      cache.Model = std::move(configured);
      const dem::PackReport built = dem::buildPack(cache.Model, params);
      this->ReportInfo("built pack: " + built.summary());
      cache.AppliedCommands.clear();
      cache.Signature = signature;
      this->LockedInStress = 0.0;
      this->LargestOverlap = 0.0;
    }
    else
    {
      // Only the material may differ: update it (and the masses that follow from it).
      cache.Model.material = configured.material;
      dem::updateMassProperties(cache.Model);
    }
    for (std::size_t c = cache.AppliedCommands.size(); c < this->Commands.size(); ++c)
    {
      this->UpdateProgress(static_cast<double>(c) / static_cast<double>(this->Commands.size()));
      if (this->Commands[c] == 'A')
      {
        this->ReportInfo(dem::addElements(cache.Model, params).summary());
      }
      else if (this->Commands[c] == 'G')
      {
        this->ReportInfo(dem::growElements(cache.Model).summary());
      }
      else
      {
        const dem::CompactReport compacted = dem::compactElements(cache.Model, compact);
        this->LockedInStress = compacted.lockedInStress;
        this->LargestOverlap = compacted.largestOverlap;
        this->ReportInfo(compacted.summary());
      }
      cache.AppliedCommands.push_back(this->Commands[c]);
    }
    cache.Valid = true;
    // Built: the memory of the particles it holds.
    this->EstimatedMemory = dem::estimateMemory(static_cast<double>(cache.Model.particles.size()));
    this->PublishModel(cache.Model, outputVector);
    return 1;
  }
  catch (const std::exception& e)
  {
    cache.Valid = false;
    this->LockedInStress = 0.0;
    this->LargestOverlap = 0.0;
    this->ReportFailure(e.what(), outputVector);
    return 0;
  }
}

void vtkDEMPackSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "InitialElements: " << this->InitialElements << "\n";
  os << indent << "MinimumSize: " << this->MinimumSize << " m\n";
  os << indent << "MaximumSize: " << this->MaximumSize << " m\n";
  os << indent << "TargetPorosity: " << this->TargetPorosity << "\n";
  os << indent << "RandomSeed: " << this->RandomSeed << "\n";
  os << indent << "FineZone: " << this->FineZone << "\n";
  os << indent << "FineZoneOrigin: " << this->FineZoneOrigin[0] << " " << this->FineZoneOrigin[1]
     << " " << this->FineZoneOrigin[2] << " m\n";
  os << indent << "FineZoneDimensions: " << this->FineZoneDimensions[0] << " "
     << this->FineZoneDimensions[1] << " " << this->FineZoneDimensions[2] << " m\n";
  os << indent << "FineZoneMinimumSize: " << this->FineZoneMinimumSize << " m\n";
  os << indent << "FineZoneMaximumSize: " << this->FineZoneMaximumSize << " m\n";
  os << indent << "MaximumLockedInStress: " << this->MaximumLockedInStress << " Pa\n";
  os << indent << "EquilibriumRatio: " << this->EquilibriumRatio << "\n";
  os << indent << "LockedInStress: " << this->LockedInStress << " Pa\n";
  os << indent << "LargestOverlap: " << this->LargestOverlap << "\n";
  os << indent << "EstimatedMemory: " << this->EstimatedMemory << " bytes\n";
  os << indent << "Commands: " << this->Commands << "\n";
}
