#include "vtkDEMStateWriter.h"

#include "vtkDEMModelConversion.h"

#include "dem/StateFile.h"

#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>

#include <exception>

vtkStandardNewMacro(vtkDEMStateWriter);

vtkDEMStateWriter::vtkDEMStateWriter() = default;

vtkDEMStateWriter::~vtkDEMStateWriter()
{
  this->SetFileName(nullptr);
}

int vtkDEMStateWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkMultiBlockDataSet");
  return 1;
}

void vtkDEMStateWriter::WriteData()
{
  this->LastWriteSucceeded = 0;
  try
  {
    if (!this->FileName || !*this->FileName)
    {
      throw dem::FileError("File Name is empty: give the path of the state file (.rdem) to write.");
    }
    const dem::Model model =
      rockdem::MultiBlockToModel(vtkMultiBlockDataSet::SafeDownCast(this->GetInput()));
    if (this->WriteHistory)
    {
      dem::writeStateAndHistory(model, this->FileName); // one pair: see dem/StateFile.h
    }
    else
    {
      dem::writeState(model, this->FileName);
    }
    this->LastWriteSucceeded = 1;
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
  }
}

void vtkDEMStateWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "WriteHistory: " << this->WriteHistory << "\n";
}
