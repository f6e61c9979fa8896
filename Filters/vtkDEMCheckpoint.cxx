#include "vtkDEMCheckpoint.h"

#include "dem/StateFile.h"

#include <vtkAbstractArray.h>
#include <vtkCompositeDataIterator.h>
#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkFieldData.h>
#include <vtkCellData.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkCellArray.h>
#include <vtkSmartPointer.h>

#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace
{
void HashArray(vtkAbstractArray* array, std::vector<std::uint64_t>& hashes)
{
  if (!array)
  {
    hashes.push_back(0);
    return;
  }
  const char* name = array->GetName() ? array->GetName() : "";
  hashes.push_back(dem::fnv1a64(name, std::strlen(name)));
  if (auto* data = vtkDataArray::SafeDownCast(array))
  {
    const std::size_t bytes = static_cast<std::size_t>(data->GetNumberOfValues()) *
      static_cast<std::size_t>(data->GetDataTypeSize());
    hashes.push_back(dem::fnv1a64(data->GetVoidPointer(0), bytes));
  }
  else
  {
    // Non-numeric arrays (strings): their text.
    std::string text;
    for (vtkIdType k = 0; k < array->GetNumberOfValues(); ++k)
    {
      text += array->GetVariantValue(k).ToString();
      text.push_back('\0');
    }
    hashes.push_back(dem::fnv1a64(text.data(), text.size()));
  }
}

void HashFields(vtkFieldData* fields, std::vector<std::uint64_t>& hashes)
{
  const int n = fields ? fields->GetNumberOfArrays() : 0;
  hashes.push_back(static_cast<std::uint64_t>(n));
  for (int k = 0; k < n; ++k)
  {
    HashArray(fields->GetAbstractArray(k), hashes);
  }
}

void HashDataSet(vtkDataSet* data, std::vector<std::uint64_t>& hashes)
{
  if (auto* points = vtkPointSet::SafeDownCast(data))
  {
    HashArray(points->GetPoints() ? points->GetPoints()->GetData() : nullptr, hashes);
  }
  if (auto* poly = vtkPolyData::SafeDownCast(data))
  {
    for (vtkCellArray* cells : { poly->GetVerts(), poly->GetLines(), poly->GetPolys() })
    {
      HashArray(cells ? cells->GetConnectivityArray() : nullptr, hashes);
      HashArray(cells ? cells->GetOffsetsArray() : nullptr, hashes);
    }
  }
  HashFields(data->GetPointData(), hashes);
  HashFields(data->GetCellData(), hashes);
  HashFields(data->GetFieldData(), hashes);
}
}

namespace rockdem
{
std::uint64_t RunFingerprint(vtkDataObject* input, const std::string& settings)
{
  std::vector<std::uint64_t> hashes;
  hashes.push_back(dem::fnv1a64(settings.data(), settings.size()));
  if (auto* composite = vtkCompositeDataSet::SafeDownCast(input))
  {
    HashFields(composite->GetFieldData(), hashes);
    vtkSmartPointer<vtkCompositeDataIterator> it;
    it.TakeReference(composite->NewIterator());
    it->SkipEmptyNodesOff();
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      if (auto* data = vtkDataSet::SafeDownCast(it->GetCurrentDataObject()))
      {
        HashDataSet(data, hashes);
      }
      else
      {
        hashes.push_back(0);
      }
    }
  }
  else if (auto* data = vtkDataSet::SafeDownCast(input))
  {
    HashDataSet(data, hashes);
  }
  return dem::fnv1a64(hashes.data(), hashes.size() * sizeof(std::uint64_t));
}

std::string CheckpointRecordPath(const std::string& checkpoint)
{
  return checkpoint + ".stage";
}

void WriteCheckpointRecord(const std::string& checkpoint, const CheckpointRecord& record)
{
  std::ostringstream out;
  out << "RockDEM checkpoint record: the DEM Load Test run that wrote " << checkpoint << "\n"
      << "run " << std::hex << record.run << std::dec << "\n"
      << "steps-per-frame " << record.stepsPerFrame << "\n"
      << "frame " << record.frame << "\n"
      << "finished " << (record.finished ? 1 : 0) << "\n";
  const std::string text = out.str();
  // The engine's atomic writer: a temporary file renamed over the record.
  dem::writeFileAtomically(CheckpointRecordPath(checkpoint), text.data(), text.size());
}

bool ReadCheckpointRecord(const std::string& checkpoint, CheckpointRecord& record)
{
  std::ifstream in(CheckpointRecordPath(checkpoint));
  std::string header;
  if (!in || !std::getline(in, header) || header.rfind("RockDEM checkpoint record", 0) != 0)
  {
    return false;
  }
  CheckpointRecord read;
  std::string key;
  int fields = 0;
  while (in >> key)
  {
    if (key == "run" && (in >> std::hex >> read.run >> std::dec))
    {
      ++fields;
    }
    else if (key == "steps-per-frame" && (in >> read.stepsPerFrame))
    {
      ++fields;
    }
    else if (key == "frame" && (in >> read.frame))
    {
      ++fields;
    }
    else if (key == "finished" && (in >> read.finished))
    {
      ++fields;
    }
    else
    {
      return false;
    }
  }
  if (fields != 4 || read.frame < 0 || read.stepsPerFrame < 1)
  {
    return false;
  }
  record = read;
  return true;
}
}
