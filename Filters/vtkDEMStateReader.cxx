#include "vtkDEMStateReader.h"

#include "vtkDEMModelConversion.h"

#include "dem/Bonds.h"
#include "dem/LoadTest.h"
#include "dem/StateFile.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkObjectFactory.h>

#include <cstring>
#include <exception>
#include <fstream>

vtkStandardNewMacro(vtkDEMStateReader);

vtkDEMStateReader::vtkDEMStateReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkDEMStateReader::~vtkDEMStateReader()
{
  this->SetFileName(nullptr);
}

int vtkDEMStateReader::CanReadFile(const char* fileName)
{
  if (!fileName)
  {
    return 0;
  }
  std::ifstream in(fileName, std::ios::binary);
  char magic[sizeof(dem::StateMagic)] = {};
  in.read(magic, sizeof(magic));
  return in && std::memcmp(magic, dem::StateMagic, sizeof(magic)) == 0 ? 1 : 0;
}

int vtkDEMStateReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  auto* output = vtkMultiBlockDataSet::GetData(outputVector, 0);
  try
  {
    if (!this->FileName || !*this->FileName)
    {
      throw dem::FileError("File Name is empty: choose a RockDEM state file (.rdem) to read.");
    }
    const dem::Model model = dem::readState(this->FileName);
    rockdem::ModelToMultiBlock(model, output);
    this->ModelTime = model.clock.time;
    this->Step = static_cast<vtkIdType>(model.clock.step);
    this->NumberOfParticles = static_cast<vtkIdType>(model.particles.size());
    const dem::BondCounts bonds = dem::countBonds(model.bonds);
    this->NumberOfBonds = static_cast<vtkIdType>(bonds.installed);
    this->NumberOfBrokenBonds = static_cast<vtkIdType>(bonds.broken);
    this->StageText = dem::stageName(model.test.stage);
    this->ModeText = dem::modeName(model.test.settings.mode);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    output->Initialize();
    this->NumberOfParticles = 0;
    return 0;
  }
  return 1;
}

void vtkDEMStateReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "ModelTime: " << this->ModelTime << " s\n";
  os << indent << "Step: " << this->Step << "\n";
  os << indent << "NumberOfParticles: " << this->NumberOfParticles << "\n";
  os << indent << "Stage: " << this->StageText << "\n";
}
