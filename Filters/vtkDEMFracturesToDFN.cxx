#include "vtkDEMFracturesToDFN.h"

#include "vtkDEMModelConversion.h"

#include "dem/Errors.h"
#include "dem/Fractures.h"
#include "dem/Model.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkStringArray.h>
#include <vtkTable.h>

#include <exception>

vtkStandardNewMacro(vtkDEMFracturesToDFN);

namespace
{
vtkNew<vtkDoubleArray> NewDoubleArray(const char* name, int components, vtkIdType n)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(n);
  return a;
}

/// Stamps an output with the time of the model it was computed from.
void StampTime(vtkDataObject* input, vtkDataObject* output)
{
  if (input && input->GetInformation()->Has(vtkDataObject::DATA_TIME_STEP()))
  {
    output->GetInformation()->Set(
      vtkDataObject::DATA_TIME_STEP(), input->GetInformation()->Get(vtkDataObject::DATA_TIME_STEP()));
  }
  else
  {
    output->GetInformation()->Remove(vtkDataObject::DATA_TIME_STEP());
  }
}
}

vtkDEMFracturesToDFN::vtkDEMFracturesToDFN()
  : MinimumCracks(10)
  , MinimumPlanarity(0.8)
  , ClusterDistance(0.0)
  , MinimumFill(0.0)
  , OrientationTolerance(dem::FractureParameters().orientationTolerance)
  , BandSignificance(dem::FractureParameters().bandSignificance)
  , DiscSides(24)
  , NumberOfBrokenBonds(0)
  , NumberOfClusters(0)
  , NumberOfDiscs(0)
  , NumberOfTensileDiscs(0)
  , NumberOfShearDiscs(0)
  , NumberOfInheritedDiscs(0)
  , RejectedTooSmall(0)
  , RejectedNonPlanar(0)
  , RejectedSparse(0)
  , UsedClusterDistance(0.0)
{
  this->SetNumberOfOutputPorts(2);
}

vtkDEMFracturesToDFN::~vtkDEMFracturesToDFN() = default;

int vtkDEMFracturesToDFN::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkMultiBlockDataSet");
  return 1;
}

int vtkDEMFracturesToDFN::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 1 ? "vtkTable" : "vtkPolyData");
  return 1;
}

void vtkDEMFracturesToDFN::ResetCounts()
{
  this->NumberOfBrokenBonds = 0;
  this->NumberOfClusters = 0;
  this->NumberOfDiscs = 0;
  this->NumberOfTensileDiscs = 0;
  this->NumberOfShearDiscs = 0;
  this->NumberOfInheritedDiscs = 0;
  this->RejectedTooSmall = 0;
  this->RejectedNonPlanar = 0;
  this->RejectedSparse = 0;
  this->UsedClusterDistance = 0.0;
}

int vtkDEMFracturesToDFN::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  auto* input = vtkMultiBlockDataSet::GetData(inputVector[0], 0);
  auto* discs = vtkPolyData::GetData(outputVector, 0);
  auto* table = vtkTable::GetData(outputVector, 1);
  discs->Initialize();
  table->Initialize();
  this->ResetCounts();
  try
  {
    dem::FractureParameters params;
    params.minimumCracks = this->MinimumCracks;
    params.minimumPlanarity = this->MinimumPlanarity;
    params.clusterDistance = this->ClusterDistance;
    params.minimumFill = this->MinimumFill;
    params.orientationTolerance = this->OrientationTolerance;
    params.bandSignificance = this->BandSignificance;
    params.discSides = this->DiscSides;
    dem::validate(params);
    const dem::Model model = rockdem::MultiBlockToModel(input);
    const dem::FractureNetwork net = dem::extractFractures(model, params);
    const vtkIdType n = static_cast<vtkIdType>(net.discs.size());

    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    vtkNew<vtkCellArray> polys;
    auto dip = NewDoubleArray("Dip", 1, n);
    auto azimuth = NewDoubleArray("Azimuth", 1, n);
    auto radius = NewDoubleArray("Radius", 1, n);
    auto area = NewDoubleArray("Area", 1, n);
    auto normal = NewDoubleArray("Normal", 3, n);
    auto center = NewDoubleArray("Center", 3, n);
    auto planarity = NewDoubleArray("Planarity", 1, n);
    auto fill = NewDoubleArray("Fill", 1, n);
    vtkNew<vtkIntArray> set;
    set->SetName("Set");
    set->SetNumberOfTuples(n);
    vtkNew<vtkIdTypeArray> cracks;
    cracks->SetName("CrackCount");
    cracks->SetNumberOfTuples(n);
    vtkNew<vtkStringArray> setName;
    setName->SetName("SetName");
    setName->SetNumberOfValues(n);
    for (vtkIdType c = 0; c < n; ++c)
    {
      const dem::FractureDisc& d = net.discs[static_cast<std::size_t>(c)];
      polys->InsertNextCell(static_cast<vtkIdType>(d.polygon.size()));
      for (const dem::Vec3& v : d.polygon)
      {
        polys->InsertCellPoint(points->InsertNextPoint(v.x(), v.y(), v.z()));
      }
      dip->SetValue(c, d.dip);
      azimuth->SetValue(c, d.azimuth);
      radius->SetValue(c, d.radius);
      area->SetValue(c, d.area);
      normal->SetTuple3(c, d.normal.x(), d.normal.y(), d.normal.z());
      center->SetTuple3(c, d.center.x(), d.center.y(), d.center.z());
      planarity->SetValue(c, d.planarity);
      fill->SetValue(c, d.fill);
      set->SetValue(c, static_cast<int>(d.set));
      setName->SetValue(c, dem::fractureSetName(d.set));
      cracks->SetValue(c, static_cast<vtkIdType>(d.crackCount()));
    }
    discs->SetPoints(points);
    discs->SetPolys(polys);
    vtkCellData* cd = discs->GetCellData();
    for (vtkAbstractArray* a : std::initializer_list<vtkAbstractArray*>{ dip, azimuth, set, setName, radius, area,
           normal, center, cracks, planarity, fill })
    {
      cd->AddArray(a);
    }
    cd->SetActiveScalars("Set");

    // The summary table: one row per disc, scalar columns (CSV through Save Data).
    auto column = [&](const char* name, vtkDataArray* from, int component) {
      auto a = NewDoubleArray(name, 1, n);
      for (vtkIdType c = 0; c < n; ++c)
      {
        a->SetValue(c, from->GetComponent(c, component));
      }
      table->AddColumn(a);
    };
    column("CenterX", center, 0);
    column("CenterY", center, 1);
    column("CenterZ", center, 2);
    column("NormalX", normal, 0);
    column("NormalY", normal, 1);
    column("NormalZ", normal, 2);
    column("Dip", dip, 0);
    column("Azimuth", azimuth, 0);
    column("Radius", radius, 0);
    column("Area", area, 0);
    table->AddColumn(set);
    table->AddColumn(setName);
    table->AddColumn(cracks);
    column("Planarity", planarity, 0);
    column("Fill", fill, 0);

    const dem::FractureReport& r = net.report;
    this->NumberOfBrokenBonds = static_cast<vtkIdType>(r.total.brokenBonds);
    this->NumberOfClusters = static_cast<vtkIdType>(r.total.clusters);
    this->NumberOfDiscs = static_cast<vtkIdType>(r.total.discs);
    this->NumberOfTensileDiscs = static_cast<vtkIdType>(r.sets[0].discs);
    this->NumberOfShearDiscs = static_cast<vtkIdType>(r.sets[1].discs);
    this->NumberOfInheritedDiscs = static_cast<vtkIdType>(r.sets[2].discs);
    this->RejectedTooSmall = static_cast<vtkIdType>(r.total.rejectedTooSmall);
    this->RejectedNonPlanar = static_cast<vtkIdType>(r.total.rejectedNonPlanar);
    this->RejectedSparse = static_cast<vtkIdType>(r.total.rejectedSparse);
    this->UsedClusterDistance = r.clusterDistance;
    this->LastMessageText = r.summary();
    vtkOutputWindowDisplayText(("DEM Fractures To DFN: " + this->LastMessageText + "\n").c_str());
    if (n == 0)
    {
      vtkWarningMacro(<< "DEM Fractures To DFN emitted no fracture: "
                      << (r.total.brokenBonds == 0 ? "the model has no broken bonds."
                                                   : "every cluster of broken bonds was rejected (" +
                            std::to_string(r.total.rejectedTooSmall) + " too small, " +
                            std::to_string(r.total.rejectedNonPlanar) + " non-planar, " +
                            std::to_string(r.total.rejectedSparse) + " sparse)."));
    }
  }
  catch (const std::exception& e)
  {
    this->ResetCounts();
    this->LastMessageText = e.what();
    vtkErrorMacro(<< e.what());
    discs->Initialize();
    table->Initialize();
    return 0;
  }
  StampTime(input, discs);
  StampTime(input, table);
  return 1;
}

void vtkDEMFracturesToDFN::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MinimumCracks: " << this->MinimumCracks << "\n";
  os << indent << "MinimumPlanarity: " << this->MinimumPlanarity << "\n";
  os << indent << "ClusterDistance: " << this->ClusterDistance << " m\n";
  os << indent << "MinimumFill: " << this->MinimumFill << "\n";
  os << indent << "OrientationTolerance: " << this->OrientationTolerance << " degrees\n";
  os << indent << "BandSignificance: " << this->BandSignificance << " standard deviations\n";
  os << indent << "DiscSides: " << this->DiscSides << "\n";
  os << indent << "BrokenBonds: " << this->NumberOfBrokenBonds << "\n";
  os << indent << "Clusters: " << this->NumberOfClusters << "\n";
  os << indent << "DiscsEmitted: " << this->NumberOfDiscs << " (tensile " << this->NumberOfTensileDiscs
     << ", shear " << this->NumberOfShearDiscs << ", inherited " << this->NumberOfInheritedDiscs << ")\n";
  os << indent << "RejectedTooSmall: " << this->RejectedTooSmall << "\n";
  os << indent << "RejectedNonPlanar: " << this->RejectedNonPlanar << "\n";
  os << indent << "RejectedSparse: " << this->RejectedSparse << "\n";
  os << indent << "UsedClusterDistance: " << this->UsedClusterDistance << " m\n";
  os << indent << "LastMessage: " << this->LastMessageText << "\n";
}
