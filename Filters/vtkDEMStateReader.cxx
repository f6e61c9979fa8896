#include "vtkDEMStateReader.h"

#include "vtkDEMModelConversion.h"

#include "dem/Bonds.h"
#include "dem/LoadTest.h"
#include "dem/StateFile.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkObjectFactory.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <exception>
#include <fstream>
#include <string>

#include <sys/stat.h>

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
  struct stat info
  {
  };
  if (::stat(fileName, &info) != 0 || !S_ISREG(info.st_mode))
  {
    return 0;
  }
  // A .rdem file is ours to explain, whatever is wrong with it.
  const std::string name = fileName;
  const std::string extension = dem::StateFileExtension;
  if (name.size() >= extension.size() &&
    std::equal(extension.rbegin(), extension.rend(), name.rbegin(),
      [](char a, char b) { return a == std::tolower(static_cast<unsigned char>(b)); }))
  {
    return 1;
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
  this->LastMessageText.clear();
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
    this->SyncHistory(model);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    this->LastMessageText = e.what();
    output->Initialize();
    this->NumberOfParticles = 0;
    return 0;
  }
  return 1;
}

void vtkDEMStateReader::SyncHistory(const dem::Model& model)
{
  // The state file is the truth: a history CSV beside it that another write left (a crash
  // between the state file's rename and the CSV's) is made to agree with it.
  try
  {
    const dem::HistorySyncReport sync = dem::syncHistoryCSV(model.test, this->FileName);
    if (sync.action == dem::HistorySync::Rewritten)
    {
      this->LastMessageText = "The history file '" + sync.path + "' was out of step with the state file (" +
        std::to_string(sync.fileRows) + " rows; the state file has " + std::to_string(sync.stateRows) +
        "): rewritten from the state file.";
    }
    else if (sync.action == dem::HistorySync::Removed)
    {
      this->LastMessageText = "The history file '" + sync.path + "' (" + std::to_string(sync.fileRows) +
        " rows) belonged to another write: the state file has no test history, so it was removed.";
    }
  }
  catch (const std::exception& e)
  {
    this->LastMessageText = e.what();
  }
  if (!this->LastMessageText.empty())
  {
    vtkWarningMacro(<< this->LastMessageText);
  }
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
