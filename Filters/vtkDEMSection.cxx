#include "vtkDEMSection.h"

#include "vtkDEMModelConversion.h"
#include "vtkDEMPipelineTime.h"

#include "dem/Model.h"
#include "dem/Section.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCompositeDataSet.h>
#include <vtkDoubleArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <exception>
#include <string>

vtkStandardNewMacro(vtkDEMSection);

namespace
{
vtkPolyData* NamedBlock(vtkMultiBlockDataSet* input, const char* wanted)
{
  for (unsigned int b = 0; input && b < input->GetNumberOfBlocks(); ++b)
  {
    const char* name =
      input->HasMetaData(b) ? input->GetMetaData(b)->Get(vtkCompositeDataSet::NAME()) : nullptr;
    if (name && std::string(name) == wanted)
    {
      return vtkPolyData::SafeDownCast(input->GetBlock(b));
    }
  }
  return nullptr;
}

vtkNew<vtkDoubleArray> NewDoubleArray(const char* name, vtkIdType n)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfTuples(n);
  return a;
}
}

vtkDEMSection::vtkDEMSection()
  : Section(0)
  , TraceDistance(0.0)
  , CircleSides(32)
  , NumberOfCutParticles(0)
  , NumberOfCrossingBonds(0)
  , NumberOfTraces(0)
  , UsedTraceDistance(0.0)
{
  this->Origin[0] = this->Origin[1] = this->Origin[2] = 0.0;
  this->Normal[0] = this->Normal[1] = 0.0;
  this->Normal[2] = 1.0;
  this->SetNumberOfOutputPorts(3);
}

vtkDEMSection::~vtkDEMSection() = default;

int vtkDEMSection::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkMultiBlockDataSet");
  return 1;
}

int vtkDEMSection::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  auto* input = vtkMultiBlockDataSet::GetData(inputVector[0], 0);
  vtkPolyData* outputs[3];
  for (int port = 0; port < 3; ++port)
  {
    outputs[port] = vtkPolyData::GetData(outputVector, port);
    outputs[port]->Initialize();
  }
  vtkPolyData* circles = outputs[0];
  vtkPolyData* crossings = outputs[1];
  vtkPolyData* traces = outputs[2];
  this->NumberOfCutParticles = 0;
  this->NumberOfCrossingBonds = 0;
  this->NumberOfTraces = 0;
  this->UsedTraceDistance = 0.0;
  try
  {
    dem::SectionParameters params;
    params.orientation = dem::sectionOrientation(this->Section);
    params.origin = dem::Vec3(this->Origin[0], this->Origin[1], this->Origin[2]);
    params.normal = dem::Vec3(this->Normal[0], this->Normal[1], this->Normal[2]);
    params.traceDistance = this->TraceDistance;
    params.circleSides = this->CircleSides;
    dem::validate(params);
    const dem::Model model = rockdem::MultiBlockToModel(input);
    const dem::ModelSection section = dem::sectionModel(model, params);
    vtkPolyData* particles = NamedBlock(input, rockdem::ParticlesBlockName);
    vtkPolyData* bonds = NamedBlock(input, rockdem::BondsBlockName);
    const int sides = params.circleSides;

    // Port 0: the circles, with their particle's arrays.
    {
      const auto n = static_cast<vtkIdType>(section.circles.size());
      vtkNew<vtkPoints> points;
      points->SetDataTypeToDouble();
      points->SetNumberOfPoints(n * sides);
      vtkNew<vtkCellArray> polys;
      polys->AllocateExact(n, n * sides);
      vtkCellData* cd = circles->GetCellData();
      cd->CopyAllocate(particles->GetPointData(), n);
      auto sectionRadius = NewDoubleArray("SectionRadius", n);
      auto distance = NewDoubleArray("Distance", n);
      for (vtkIdType c = 0; c < n; ++c)
      {
        const dem::SectionCircle& circle = section.circles[static_cast<std::size_t>(c)];
        polys->InsertNextCell(sides);
        for (int k = 0; k < sides; ++k)
        {
          const dem::Vec3 x = dem::ellipseVertex(
            circle.centre, circle.radius * section.u, circle.radius * section.v, k, sides);
          points->SetPoint(c * sides + k, x.data());
          polys->InsertCellPoint(c * sides + k);
        }
        cd->CopyData(particles->GetPointData(), static_cast<vtkIdType>(circle.particle), c);
        sectionRadius->SetValue(c, circle.radius);
        distance->SetValue(c, circle.distance);
      }
      circles->SetPoints(points);
      circles->SetPolys(polys);
      cd->AddArray(sectionRadius);
      cd->AddArray(distance);
      if (cd->GetArray("VonMisesStress"))
      {
        cd->SetActiveScalars("VonMisesStress");
      }
    }

    // Port 1: the intact bonds crossing the plane, with their bond's arrays.
    vtkCellData* bondData = bonds ? bonds->GetCellData() : nullptr;
    {
      const auto n = static_cast<vtkIdType>(section.crossings.size());
      vtkNew<vtkPoints> points;
      points->SetDataTypeToDouble();
      points->SetNumberOfPoints(n);
      vtkNew<vtkCellArray> verts;
      verts->AllocateExact(n, n);
      vtkPointData* pd = crossings->GetPointData();
      if (bondData)
      {
        pd->CopyAllocate(bondData, n);
      }
      for (vtkIdType c = 0; c < n; ++c)
      {
        const dem::BondCrossing& crossing = section.crossings[static_cast<std::size_t>(c)];
        points->SetPoint(c, crossing.point.data());
        verts->InsertNextCell(1, &c);
        if (bondData)
        {
          pd->CopyData(bondData, static_cast<vtkIdType>(crossing.bond), c);
        }
      }
      crossings->SetPoints(points);
      crossings->SetVerts(verts);
    }

    // Port 2: the broken bonds' traces, with their bond's arrays.
    {
      const auto n = static_cast<vtkIdType>(section.traces.size());
      vtkNew<vtkPoints> points;
      points->SetDataTypeToDouble();
      points->SetNumberOfPoints(n * sides);
      vtkNew<vtkCellArray> lines;
      lines->AllocateExact(n, n * (sides + 1));
      vtkCellData* cd = traces->GetCellData();
      if (bondData)
      {
        cd->CopyAllocate(bondData, n);
      }
      auto distance = NewDoubleArray("Distance", n);
      for (vtkIdType c = 0; c < n; ++c)
      {
        const dem::CrackTrace& trace = section.traces[static_cast<std::size_t>(c)];
        lines->InsertNextCell(sides + 1); // closed
        for (int k = 0; k < sides; ++k)
        {
          const dem::Vec3 x = dem::ellipseVertex(trace.centre, trace.major, trace.minor, k, sides);
          points->SetPoint(c * sides + k, x.data());
          lines->InsertCellPoint(c * sides + k);
        }
        lines->InsertCellPoint(c * sides);
        if (bondData)
        {
          cd->CopyData(bondData, static_cast<vtkIdType>(trace.bond), c);
        }
        distance->SetValue(c, trace.distance);
      }
      traces->SetPoints(points);
      traces->SetLines(lines);
      cd->AddArray(distance);
      if (cd->GetArray("FailureMode"))
      {
        cd->SetActiveScalars("FailureMode");
      }
    }

    this->NumberOfCutParticles = static_cast<vtkIdType>(section.circles.size());
    this->NumberOfCrossingBonds = static_cast<vtkIdType>(section.crossings.size());
    this->NumberOfTraces = static_cast<vtkIdType>(section.traces.size());
    this->UsedTraceDistance = section.traceDistance;
    this->LastMessageText = section.message;
    if (section.circles.empty() && section.crossings.empty() && section.traces.empty())
    {
      vtkWarningMacro(<< "DEM Section: " << section.message);
    }
    else
    {
      vtkOutputWindowDisplayText(("DEM Section: " + section.message + "\n").c_str());
    }
  }
  catch (const std::exception& e)
  {
    this->LastMessageText = e.what();
    this->NumberOfCutParticles = this->NumberOfCrossingBonds = this->NumberOfTraces = 0;
    vtkErrorMacro(<< e.what());
    for (vtkPolyData* out : outputs)
    {
      out->Initialize();
    }
    return 0;
  }
  for (int port = 0; port < 3; ++port)
  {
    rockdem::StampRequestedTime(outputVector->GetInformationObject(port), outputs[port]);
  }
  return 1;
}

void vtkDEMSection::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Section: " << this->Section << "\n";
  os << indent << "Origin: " << this->Origin[0] << " " << this->Origin[1] << " " << this->Origin[2] << " m\n";
  os << indent << "Normal: " << this->Normal[0] << " " << this->Normal[1] << " " << this->Normal[2] << "\n";
  os << indent << "TraceDistance: " << this->TraceDistance << " m\n";
  os << indent << "CircleSides: " << this->CircleSides << "\n";
  os << indent << "CutParticles: " << this->NumberOfCutParticles << "\n";
  os << indent << "CrossingBonds: " << this->NumberOfCrossingBonds << "\n";
  os << indent << "Traces: " << this->NumberOfTraces << "\n";
  os << indent << "UsedTraceDistance: " << this->UsedTraceDistance << " m\n";
  os << indent << "LastMessage: " << this->LastMessageText << "\n";
}
