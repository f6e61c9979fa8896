#include "vtkDEMModelConversion.h"

#include "dem/Errors.h"
#include "dem/ParticleStress.h"
#include "dem/SizeClass.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCompositeDataSet.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkInformation.h>
#include <vtkIntArray.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkTypeInt64Array.h>
#include <vtkTypeUInt32Array.h>
#include <vtkTypeUInt64Array.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <array>
#include <limits>
#include <limits>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <unordered_map>

namespace rockdem
{
namespace
{
// ---- writing ---------------------------------------------------------------------

vtkSmartPointer<vtkDoubleArray> VectorArray(const char* name, const std::vector<dem::Vec3>& v)
{
  auto a = vtkSmartPointer<vtkDoubleArray>::New();
  a->SetName(name);
  a->SetNumberOfComponents(3);
  a->SetNumberOfTuples(static_cast<vtkIdType>(v.size()));
  if (!v.empty())
  {
    std::memcpy(a->GetPointer(0), v.data(), v.size() * sizeof(dem::Vec3));
  }
  return a;
}

/// A one-component array of type ArrayT named `name` holding a copy of v.
template <typename ArrayT, typename T>
vtkSmartPointer<ArrayT> CopiedArray(const char* name, const std::vector<T>& v)
{
  auto a = vtkSmartPointer<ArrayT>::New();
  a->SetName(name);
  a->SetNumberOfTuples(static_cast<vtkIdType>(v.size()));
  std::copy(v.begin(), v.end(), a->GetPointer(0));
  return a;
}

vtkSmartPointer<vtkDoubleArray> ScalarArray(const char* name, const std::vector<double>& v)
{
  return CopiedArray<vtkDoubleArray>(name, v);
}

void AddField(vtkFieldData* fd, const char* name, std::initializer_list<double> values)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  vtkIdType i = 0;
  for (double v : values)
  {
    a->SetValue(i++, v);
  }
  fd->AddArray(a);
}

void AddIntField(vtkFieldData* fd, const char* name, std::initializer_list<long long> values)
{
  vtkNew<vtkTypeInt64Array> a;
  a->SetName(name);
  a->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  vtkIdType i = 0;
  for (long long v : values)
  {
    a->SetValue(i++, static_cast<vtkTypeInt64>(v));
  }
  fd->AddArray(a);
}

// ---- reading ---------------------------------------------------------------------

[[noreturn]] void Missing(const std::string& what)
{
  throw dem::InputError("Input is not a RockDEM model: " + what +
    " is missing (connect the output of a DEM source or filter).");
}

vtkDataArray* RequireArray(vtkFieldData* fd, const char* name, vtkIdType tuples, int comps)
{
  vtkDataArray* a = fd ? fd->GetArray(name) : nullptr;
  if (!a)
  {
    Missing(std::string("array '") + name + "'");
  }
  if (a->GetNumberOfTuples() != tuples || a->GetNumberOfComponents() != comps)
  {
    throw dem::InputError(std::string("RockDEM model array '") + name + "' has " +
      std::to_string(a->GetNumberOfTuples()) + " x " + std::to_string(a->GetNumberOfComponents()) +
      " values; expected " + std::to_string(tuples) + " x " + std::to_string(comps) + ".");
  }
  return a;
}

double Field(vtkFieldData* fd, const char* name, int component = 0, int comps = 1)
{
  return RequireArray(fd, name, comps, 1)->GetComponent(component, 0);
}

vtkTypeInt64 IntField(vtkFieldData* fd, const char* name, int component = 0, int comps = 1)
{
  auto* a = vtkTypeInt64Array::SafeDownCast(RequireArray(fd, name, comps, 1));
  if (!a)
  {
    Missing(std::string("64-bit integer array '") + name + "'");
  }
  return a->GetValue(component);
}

void ReadVectors(vtkPointData* pd, const char* name, vtkIdType n, std::vector<dem::Vec3>& out)
{
  auto* a = vtkDoubleArray::SafeDownCast(RequireArray(pd, name, n, 3));
  if (!a)
  {
    Missing(std::string("double array '") + name + "'");
  }
  out.resize(static_cast<std::size_t>(n));
  if (n > 0)
  {
    std::memcpy(out.data(), a->GetPointer(0), static_cast<std::size_t>(n) * sizeof(dem::Vec3));
  }
}

void ReadScalars(vtkPointData* pd, const char* name, vtkIdType n, std::vector<double>& out)
{
  auto* a = vtkDoubleArray::SafeDownCast(RequireArray(pd, name, n, 1));
  if (!a)
  {
    Missing(std::string("double array '") + name + "'");
  }
  out.assign(a->GetPointer(0), a->GetPointer(0) + n);
}
} // namespace

namespace
{
// The press: settings and state as two small arrays, the history as one array with a
// tuple per row (HistoryColumnCount components). Exact doubles: lossless.
void LoadTestToFieldData(const dem::LoadTestState& t, vtkFieldData* fd)
{
  const dem::LoadTestSettings& s = t.settings;
  AddField(fd, "TestSettings", { static_cast<double>(s.mode), static_cast<double>(s.axis),
    s.confiningStress, s.strainRate, s.maxStrain, s.servoAlpha, static_cast<double>(s.sampleInterval),
    s.settleTolerance, s.gripLength, s.platenFriction });
  AddField(fd, "TestConfinement", { static_cast<double>(s.confinement) });
  AddField(fd, "TestConsolidationDamping", { s.consolidationDamping });
  AddField(fd, "TestState", { static_cast<double>(t.stage), t.initialLength[0], t.initialLength[1],
    t.initialLength[2], t.initialVolume, t.peakStress, t.peakDeviator,
    static_cast<double>(t.settledChecks), static_cast<double>(t.stepsSinceSample), t.initialSpread[0],
    t.initialSpread[1], t.initialSpread[2] });
  vtkNew<vtkDoubleArray> history;
  history->SetName("TestHistory");
  history->SetNumberOfComponents(static_cast<int>(dem::HistoryColumnCount));
  history->SetNumberOfTuples(static_cast<vtkIdType>(t.history.size()));
  for (std::size_t r = 0; r < t.history.size(); ++r)
  {
    history->SetTypedTuple(static_cast<vtkIdType>(r), t.history[r].data());
  }
  fd->AddArray(history);
}

// `settlingDamping`: the model's Settling Damping, the Consolidation Damping of data saved
// before it existed (their whole test ran at Settling Damping; as dem::readState).
void LoadTestFromFieldData(vtkFieldData* fd, double settlingDamping, dem::LoadTestState& t)
{
  auto value = [&](const char* name, int k, int n) { return Field(fd, name, k, n); };
  dem::LoadTestSettings& s = t.settings;
  const double mode = value("TestSettings", 0, 10);
  if (!(mode >= 0 && mode <= 5))
  {
    throw dem::InputError("RockDEM model array 'TestSettings' has an unknown mode " +
      dem::formatValue(mode) + ".");
  }
  s.mode = static_cast<dem::TestMode>(static_cast<int>(mode));
  s.axis = static_cast<int>(value("TestSettings", 1, 10));
  s.confiningStress = value("TestSettings", 2, 10);
  s.strainRate = value("TestSettings", 3, 10);
  s.maxStrain = value("TestSettings", 4, 10);
  s.servoAlpha = value("TestSettings", 5, 10);
  s.sampleInterval = static_cast<std::int64_t>(value("TestSettings", 6, 10));
  s.settleTolerance = value("TestSettings", 7, 10);
  s.gripLength = value("TestSettings", 8, 10);
  s.platenFriction = value("TestSettings", 9, 10);
  // Confinement (0 Rigid Walls, 1 Membrane); a model written before it existed has rigid walls.
  const double confinement = fd->GetAbstractArray("TestConfinement") ? value("TestConfinement", 0, 1) : 0.0;
  if (!(confinement == 0.0 || confinement == 1.0))
  {
    throw dem::InputError("RockDEM model array 'TestConfinement' has an unknown confinement " +
      dem::formatValue(confinement) + " (valid: 0 Rigid Walls, 1 Membrane).");
  }
  s.confinement = static_cast<dem::Confinement>(static_cast<int>(confinement));
  s.consolidationDamping = fd->GetAbstractArray("TestConsolidationDamping")
    ? value("TestConsolidationDamping", 0, 1)
    : settlingDamping;
  const double stage = value("TestState", 0, 12);
  if (!(stage >= 0 && stage <= 3))
  {
    throw dem::InputError("RockDEM model array 'TestState' has an unknown stage " +
      dem::formatValue(stage) + ".");
  }
  t.stage = static_cast<dem::TestStage>(static_cast<int>(stage));
  for (int k = 0; k < 3; ++k)
  {
    t.initialLength[k] = value("TestState", 1 + k, 12);
  }
  t.initialVolume = value("TestState", 4, 12);
  t.peakStress = value("TestState", 5, 12);
  t.peakDeviator = value("TestState", 6, 12);
  t.settledChecks = static_cast<std::int64_t>(value("TestState", 7, 12));
  t.stepsSinceSample = static_cast<std::int64_t>(value("TestState", 8, 12));
  for (int k = 0; k < 3; ++k)
  {
    t.initialSpread[k] = value("TestState", 9 + k, 12);
  }
  auto* history = vtkDoubleArray::SafeDownCast(fd->GetArray("TestHistory"));
  // Data saved before the Gauge Strain column hold the first 27 columns: the gauge strain
  // reads as unknown (NaN), as in dem::readState.
  const int columns = history ? history->GetNumberOfComponents() : 0;
  if (columns != static_cast<int>(dem::HistoryColumnCount) &&
    columns != static_cast<int>(dem::HistoryColumnCountBeforeGaugeStrain))
  {
    Missing("array 'TestHistory' (" + std::to_string(dem::HistoryColumnCount) + " columns)");
  }
  std::array<double, dem::HistoryColumnCount> unknown{};
  unknown.fill(std::numeric_limits<double>::quiet_NaN());
  t.history.assign(static_cast<std::size_t>(history->GetNumberOfTuples()), unknown);
  for (std::size_t r = 0; r < t.history.size(); ++r)
  {
    for (int c = 0; c < columns; ++c)
    {
      t.history[r][static_cast<std::size_t>(c)] = history->GetComponent(static_cast<vtkIdType>(r), c);
    }
  }
}
} // namespace

void ParticlesToPolyData(
  const dem::Model& model, vtkPolyData* output, const std::vector<dem::StressTensor>* stresses)
{
  const dem::Particles& p = model.particles;
  const auto n = static_cast<vtkIdType>(p.size());

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetData(VectorArray("Points", p.position));
  output->SetPoints(points);

  vtkNew<vtkIdTypeArray> offsets;
  vtkNew<vtkIdTypeArray> connectivity;
  offsets->SetNumberOfTuples(n + 1);
  connectivity->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    offsets->SetValue(i, i);
    connectivity->SetValue(i, i);
  }
  offsets->SetValue(n, n);
  vtkNew<vtkCellArray> verts;
  verts->SetData(offsets, connectivity);
  output->SetVerts(verts);

  vtkPointData* pd = output->GetPointData();
  pd->AddArray(CopiedArray<vtkTypeInt64Array>("Id", p.id));
  pd->SetGlobalIds(nullptr);

  pd->AddArray(ScalarArray("Radius", p.radius));
  pd->SetActiveScalars("Radius");
  pd->AddArray(VectorArray("Velocity", p.velocity));
  pd->AddArray(VectorArray("AngularVelocity", p.angularVelocity));
  pd->AddArray(VectorArray("Displacement", p.displacement));
  pd->AddArray(VectorArray("Force", p.force));
  pd->AddArray(VectorArray("Torque", p.torque));
  pd->AddArray(ScalarArray("Mass", p.mass));
  pd->AddArray(ScalarArray("Inertia", p.inertia));

  pd->AddArray(CopiedArray<vtkTypeUInt32Array>("Flags", p.flags));

  // Derived, for colouring and thresholding (not read back).
  vtkNew<vtkUnsignedCharArray> fixed;
  fixed->SetName("Fixed");
  fixed->SetNumberOfTuples(n);
  vtkNew<vtkUnsignedCharArray> sizeClass;
  sizeClass->SetName("SizeClass");
  sizeClass->SetNumberOfTuples(n);
  const std::vector<std::uint8_t> classes = dem::sizeClasses(p.radius);
  for (vtkIdType i = 0; i < n; ++i)
  {
    fixed->SetValue(i, (p.flags[i] & dem::FlagFixed) ? 1 : 0);
    sizeClass->SetValue(i, classes[i]);
  }
  pd->AddArray(fixed);
  pd->AddArray(sizeClass);

  // Derived: the stress each particle carries (dem/ParticleStress.h), evaluated from the
  // model state, so a reloaded model shows the same values (not read back).
  std::vector<dem::StressTensor> evaluated;
  if (stresses == nullptr)
  {
    evaluated = dem::particleStresses(model);
    stresses = &evaluated;
  }
  const std::vector<dem::StressTensor>& stress = *stresses;
  if (stress.size() != p.size())
  {
    throw std::logic_error("ParticlesToPolyData: " + std::to_string(stress.size()) +
      " particle stresses given for " + std::to_string(p.size()) + " particles");
  }
  const bool planar = model.domain.section2D;
  vtkNew<vtkDoubleArray> tensor;
  tensor->SetName("Stress");
  tensor->SetNumberOfComponents(6);
  tensor->SetNumberOfTuples(n);
  vtkNew<vtkDoubleArray> mean;
  mean->SetName("MeanStress");
  mean->SetNumberOfTuples(n);
  vtkNew<vtkDoubleArray> vonMises;
  vonMises->SetName("VonMisesStress");
  vonMises->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    const dem::StressTensor& s = stress[static_cast<std::size_t>(i)];
    tensor->SetTypedTuple(i, s.data());
    mean->SetValue(i, dem::meanStress(s, planar));
    vonMises->SetValue(i, dem::vonMisesStress(s, planar));
  }
  pd->AddArray(tensor);
  pd->AddArray(mean);
  pd->AddArray(vonMises);
}

void WallsToPolyData(const dem::Model& model, vtkPolyData* output)
{
  output->Initialize();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> quads;
  vtkNew<vtkIntArray> axis;
  axis->SetName("Axis");
  vtkNew<vtkIntArray> side;
  side->SetName("Side");
  vtkNew<vtkDoubleArray> position;
  position->SetName("Position");
  vtkNew<vtkDoubleArray> velocity;
  velocity->SetName("Velocity");
  vtkNew<vtkDoubleArray> force;
  force->SetName("Force");
  force->SetNumberOfComponents(3);
  vtkNew<vtkDoubleArray> stress;
  stress->SetName("Stress");
  // The face spans the current positions of the walls on the other two axes.
  auto extent = [&](int k, int s) {
    const dem::Domain& d = model.domain;
    if (model.walls.size() == 6 && model.walls[2 * k].active)
    {
      return model.walls[2 * k + s].position;
    }
    return s == 0 ? d.origin[k] : d.origin[k] + d.size[k];
  };
  for (const dem::Wall& wall : model.walls)
  {
    if (!wall.active)
    {
      continue;
    }
    const int a = (wall.axis + 1) % 3;
    const int b = (wall.axis + 2) % 3;
    vtkIdType ids[4];
    for (int c = 0; c < 4; ++c)
    {
      double x[3];
      x[wall.axis] = wall.position;
      x[a] = extent(a, (c == 1 || c == 2) ? 1 : 0);
      x[b] = extent(b, c >= 2 ? 1 : 0);
      ids[c] = points->InsertNextPoint(x);
    }
    quads->InsertNextCell(4, ids);
    const double area = (extent(a, 1) - extent(a, 0)) * (extent(b, 1) - extent(b, 0));
    axis->InsertNextValue(wall.axis);
    side->InsertNextValue(wall.side);
    position->InsertNextValue(wall.position);
    velocity->InsertNextValue(wall.velocity);
    force->InsertNextTuple3(wall.force.x(), wall.force.y(), wall.force.z());
    // Compressive stress on the face: the normal push of the particles over its area.
    stress->InsertNextValue(area > 0.0 ? -wall.force.dot(wall.normal()) / area : 0.0);
  }
  output->SetPoints(points);
  output->SetPolys(quads);
  // The corners have a drawn size of zero: without a Radius array a Point Gaussian
  // representation of the model would draw them as spheres of the default radius (1 m).
  vtkNew<vtkDoubleArray> zeroRadius;
  zeroRadius->SetName("Radius");
  zeroRadius->SetNumberOfTuples(points->GetNumberOfPoints());
  zeroRadius->FillValue(std::numeric_limits<double>::quiet_NaN());
  output->GetPointData()->AddArray(zeroRadius);
  for (vtkDataArray* array : std::initializer_list<vtkDataArray*>{ axis, side, position, velocity, force, stress })
  {
    output->GetCellData()->AddArray(array);
  }
}

void ContactsToPolyData(const dem::Model& model, vtkPolyData* output)
{
  output->Initialize();
  const dem::ContactHistory& h = model.contacts;
  vtkFieldData* fd = output->GetFieldData();
  fd->AddArray(CopiedArray<vtkTypeInt64Array>("IdA", h.idA));
  fd->AddArray(CopiedArray<vtkTypeInt64Array>("IdB", h.idB));
  fd->AddArray(VectorArray("ShearSpring", h.shearSpring));
  fd->AddArray(VectorArray("RollingSpring", h.rollingSpring));
}

void BondsToPolyData(const dem::Model& model, vtkPolyData* output)
{
  output->Initialize();
  const dem::Bonds& b = model.bonds;
  const dem::Particles& p = model.particles;
  const dem::Domain& d = model.domain;
  const auto n = static_cast<vtkIdType>(b.size());

  std::unordered_map<std::int64_t, std::size_t> slotOf;
  slotOf.reserve(p.size());
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    slotOf.emplace(p.id[i], i);
  }
  // Two points per bond: the centre of A and A + the minimum-image branch to B, so that
  // a bond across a periodic seam is drawn short and never spans the box.
  vtkNew<vtkDoubleArray> xyz;
  xyz->SetNumberOfComponents(3);
  xyz->SetNumberOfTuples(2 * n);
  for (vtkIdType c = 0; c < n; ++c)
  {
    const auto ia = slotOf.find(b.idA[c]);
    const auto ib = slotOf.find(b.idB[c]);
    // A bond whose particle is gone (never produced by the engine) is drawn as a point.
    const dem::Vec3 xa = ia != slotOf.end() ? p.position[ia->second]
      : ib != slotOf.end()                  ? p.position[ib->second]
                                            : d.origin;
    const dem::Vec3 branch = ia != slotOf.end() && ib != slotOf.end()
      ? dem::minimumImage(d, xa, p.position[ib->second])
      : dem::Vec3::Zero();
    const dem::Vec3 xb = xa + branch;
    xyz->SetTuple3(2 * c, xa.x(), xa.y(), xa.z());
    xyz->SetTuple3(2 * c + 1, xb.x(), xb.y(), xb.z());
  }
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetData(xyz);
  output->SetPoints(points);

  vtkNew<vtkIdTypeArray> offsets;
  vtkNew<vtkIdTypeArray> connectivity;
  offsets->SetNumberOfTuples(n + 1);
  connectivity->SetNumberOfTuples(2 * n);
  for (vtkIdType c = 0; c <= n; ++c)
  {
    offsets->SetValue(c, 2 * c);
  }
  for (vtkIdType k = 0; k < 2 * n; ++k)
  {
    connectivity->SetValue(k, k);
  }
  vtkNew<vtkCellArray> lines;
  lines->SetData(offsets, connectivity);
  output->SetLines(lines);

  // The end points have a drawn size of zero: a Point Gaussian representation of the
  // model (particles as spheres scaled by Radius) shows nothing for them.
  vtkNew<vtkDoubleArray> zeroRadius;
  zeroRadius->SetName("Radius");
  zeroRadius->SetNumberOfTuples(2 * n);
  zeroRadius->FillValue(std::numeric_limits<double>::quiet_NaN());
  output->GetPointData()->AddArray(zeroRadius);

  vtkCellData* cd = output->GetCellData();
  cd->AddArray(CopiedArray<vtkTypeInt64Array>("IdA", b.idA));
  cd->AddArray(CopiedArray<vtkTypeInt64Array>("IdB", b.idB));
  cd->AddArray(ScalarArray("BondRadius", b.radius));
  cd->AddArray(ScalarArray("NormalStiffness", b.normalStiffness));
  cd->AddArray(ScalarArray("ShearStiffness", b.shearStiffness));
  cd->AddArray(ScalarArray("TensileStrength", b.tensileStrength));
  cd->AddArray(ScalarArray("Cohesion", b.cohesion));
  cd->AddArray(ScalarArray("FrictionAngle", b.frictionAngle));
  cd->AddArray(ScalarArray("MomentContribution", b.momentContribution));
  cd->AddArray(ScalarArray("SofteningRatio", b.softening));
  cd->AddArray(ScalarArray("NormalForce", b.normalForce));
  cd->AddArray(VectorArray("ShearForce", b.shearForce));
  cd->AddArray(ScalarArray("TwistingMoment", b.twistingMoment));
  cd->AddArray(VectorArray("BendingMoment", b.bendingMoment));
  cd->AddArray(ScalarArray("SofteningDamage", b.damage));
  cd->AddArray(CopiedArray<vtkUnsignedCharArray>("FailureMode", b.failure));
  cd->AddArray(ScalarArray("FailureTime", b.failureTime));
  cd->AddArray(VectorArray("FailurePosition", b.failurePosition));
  cd->AddArray(VectorArray("FailureNormal", b.failureNormal));
  // Derived, for Threshold (not read back).
  vtkNew<vtkUnsignedCharArray> broken;
  broken->SetName("Broken");
  broken->SetNumberOfTuples(n);
  for (vtkIdType c = 0; c < n; ++c)
  {
    broken->SetValue(c, b.failure[c] != static_cast<std::uint8_t>(dem::BondFailure::Intact) ? 1 : 0);
  }
  cd->AddArray(broken);
  // FailureMode is not made the active cell scalars: the whole model (particles drawn as
  // spheres) would then be coloured by a cell array that only the Bonds block has
  // ("FailureMode (partial)"). Colouring bonds by it is a choice; its colour map is
  // categorical (vtkSMDEMDefaults).
}

void DomainBoxToPolyData(const dem::Domain& domain, vtkPolyData* output)
{
  const dem::Vec3 lo = domain.origin;
  const dem::Vec3 hi = domain.upper();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (int k = 0; k < 8; ++k)
  {
    points->InsertNextPoint((k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(),
      (k & 4) ? hi.z() : lo.z());
  }
  vtkNew<vtkCellArray> lines;
  // Edges join corners that differ in exactly one bit.
  for (int a = 0; a < 8; ++a)
  {
    for (int bit = 1; bit < 8; bit <<= 1)
    {
      const int b = a | bit;
      if (b != a)
      {
        const vtkIdType edge[2] = { a, b };
        lines->InsertNextCell(2, edge);
      }
    }
  }
  output->Initialize();
  output->SetPoints(points);
  output->SetLines(lines);
}

void ModelToMultiBlock(const dem::Model& model, vtkMultiBlockDataSet* output,
  const std::vector<dem::StressTensor>* stresses)
{
  output->Initialize();
  vtkNew<vtkPolyData> particles;
  ParticlesToPolyData(model, particles, stresses);
  vtkNew<vtkPolyData> walls;
  WallsToPolyData(model, walls);
  vtkNew<vtkPolyData> contacts;
  ContactsToPolyData(model, contacts);
  vtkNew<vtkPolyData> bonds;
  BondsToPolyData(model, bonds);
  output->SetNumberOfBlocks(4);
  output->SetBlock(0, particles);
  output->GetMetaData(0u)->Set(vtkCompositeDataSet::NAME(), ParticlesBlockName);
  output->SetBlock(1, walls);
  output->GetMetaData(1u)->Set(vtkCompositeDataSet::NAME(), WallsBlockName);
  output->SetBlock(2, contacts);
  output->GetMetaData(2u)->Set(vtkCompositeDataSet::NAME(), ContactsBlockName);
  output->SetBlock(3, bonds);
  output->GetMetaData(3u)->Set(vtkCompositeDataSet::NAME(), BondsBlockName);

  vtkFieldData* fd = output->GetFieldData();
  const dem::Domain& d = model.domain;
  const dem::Material& m = model.material;
  AddIntField(fd, "RockDEMModelVersion", { ModelLayoutVersion });
  AddField(fd, "DomainOrigin", { d.origin.x(), d.origin.y(), d.origin.z() });
  AddField(fd, "DomainSize", { d.size.x(), d.size.y(), d.size.z() });
  AddIntField(fd, "DomainPeriodic", { d.periodic[0], d.periodic[1], d.periodic[2] });
  AddIntField(fd, "Section2D", { d.section2D ? 1 : 0 });
  AddIntField(fd, "CylinderAxis", { d.cylinderAxis });
  AddField(fd, "Density", { m.density });
  AddField(fd, "YoungsModulus", { m.youngsModulus });
  AddField(fd, "PoissonsRatio", { m.poissonsRatio });
  AddField(fd, "Restitution", { m.restitution });
  AddField(fd, "Friction", { m.friction });
  AddField(fd, "RollingFriction", { m.rollingFriction });
  AddField(fd, "Gravity", { model.gravity.x(), model.gravity.y(), model.gravity.z() });
  AddField(fd, "Time", { model.clock.time });
  AddIntField(fd, "Step", { model.clock.step });
  AddIntField(fd, "NextId", { model.nextId });
  const dem::SolverSettings& solver = model.solver;
  AddIntField(fd, "ContactLaw", { static_cast<int>(solver.contactLaw) });
  AddField(fd, "TimestepSafety", { solver.timestepSafety });
  AddField(fd, "RequestedTimestep", { solver.requestedTimestep });
  AddField(fd, "SettlingDamping", { solver.settlingDamping });
  AddField(fd, "VerletSkin", { solver.skin });
  AddIntField(fd, "Threads", { solver.threads });
  AddIntField(fd, "ParallelThreshold", { solver.parallelThreshold });
  AddField(fd, "Timestep", { model.clock.timestep });
  // Walls: six slots (low/high face of X, Y, Z), or none before the solver first ran.
  const vtkIdType nw = static_cast<vtkIdType>(model.walls.size());
  vtkNew<vtkDoubleArray> wallState;
  wallState->SetName("WallState");
  wallState->SetNumberOfComponents(WallStateComponents);
  wallState->SetNumberOfTuples(nw);
  for (vtkIdType w = 0; w < nw; ++w)
  {
    const dem::Wall& wall = model.walls[static_cast<std::size_t>(w)];
    const double state[WallStateComponents] = { static_cast<double>(wall.axis),
      static_cast<double>(wall.side), wall.position, wall.velocity, wall.active ? 1.0 : 0.0,
      wall.force.x(), wall.force.y(), wall.force.z(), wall.contactStiffness, wall.elasticForce,
      static_cast<double>(wall.contacts) };
    wallState->SetTuple(w, state);
  }
  fd->AddArray(wallState);
  LoadTestToFieldData(model.test, fd);
  vtkNew<vtkTypeUInt64Array> rng;
  rng->SetName("RandomState");
  rng->SetNumberOfTuples(4);
  for (int k = 0; k < 4; ++k)
  {
    rng->SetValue(k, model.random.state()[k]);
  }
  fd->AddArray(rng);
}

namespace
{
vtkPolyData* NamedBlock(vtkMultiBlockDataSet* input, const char* wanted)
{
  for (unsigned int b = 0; b < input->GetNumberOfBlocks(); ++b)
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

void ContactsFromPolyData(vtkMultiBlockDataSet* input, dem::Model& model)
{
  vtkPolyData* block = NamedBlock(input, ContactsBlockName);
  if (!block)
  {
    Missing("block 'Contacts'");
  }
  vtkFieldData* fd = block->GetFieldData();
  vtkDataArray* a = fd->GetArray("IdA");
  if (!a)
  {
    Missing("array 'IdA' of block 'Contacts'");
  }
  const vtkIdType n = a->GetNumberOfTuples();
  auto* idA = vtkTypeInt64Array::SafeDownCast(RequireArray(fd, "IdA", n, 1));
  auto* idB = vtkTypeInt64Array::SafeDownCast(RequireArray(fd, "IdB", n, 1));
  if (!idA || !idB)
  {
    Missing("64-bit integer arrays 'IdA' and 'IdB'");
  }
  dem::ContactHistory& h = model.contacts;
  h.idA.assign(idA->GetPointer(0), idA->GetPointer(0) + n);
  h.idB.assign(idB->GetPointer(0), idB->GetPointer(0) + n);
  auto readVectors = [&](const char* name, vtkIdType tuples, std::vector<dem::Vec3>& out) {
    auto* v = vtkDoubleArray::SafeDownCast(RequireArray(fd, name, tuples, 3));
    if (!v)
    {
      Missing(std::string("double array '") + name + "'");
    }
    out.resize(static_cast<std::size_t>(tuples));
    if (tuples > 0)
    {
      std::memcpy(out.data(), v->GetPointer(0), static_cast<std::size_t>(tuples) * sizeof(dem::Vec3));
    }
  };
  readVectors("ShearSpring", n, h.shearSpring);
  vtkDataArray* rolling = fd->GetArray("RollingSpring");
  readVectors("RollingSpring", rolling ? rolling->GetNumberOfTuples() : 0, h.rollingSpring);
  if (!h.rollingSpring.empty() && h.rollingSpring.size() != h.shearSpring.size())
  {
    throw dem::InputError("RockDEM model block 'Contacts' has " +
      std::to_string(h.rollingSpring.size()) + " rolling springs for " +
      std::to_string(h.shearSpring.size()) + " contacts.");
  }
}
template <typename ArrayT>
ArrayT* TypedCellArray(vtkFieldData* fd, const char* name, vtkIdType n, int comps, const char* type)
{
  vtkDataArray* found = fd->GetArray(name);
  if (!found)
  {
    Missing(std::string("array '") + name + "' of block 'Bonds'");
  }
  if (found->GetNumberOfTuples() != n || found->GetNumberOfComponents() != comps)
  {
    throw dem::InputError(std::string("RockDEM model array '") + name + "' of block 'Bonds' has " +
      std::to_string(found->GetNumberOfTuples()) + " x " +
      std::to_string(found->GetNumberOfComponents()) + " values; expected " + std::to_string(n) +
      " x " + std::to_string(comps) + " (one per bond).");
  }
  auto* a = ArrayT::SafeDownCast(found);
  if (!a)
  {
    Missing(std::string(type) + " array '" + name + "' of block 'Bonds'");
  }
  return a;
}

void BondsFromPolyData(vtkMultiBlockDataSet* input, dem::Model& model)
{
  dem::Bonds& b = model.bonds;
  b.clear();
  vtkPolyData* block = NamedBlock(input, BondsBlockName);
  if (!block)
  {
    return; // a model from before cementing: no bonds
  }
  vtkFieldData* cd = block->GetCellData();
  vtkDataArray* first = cd->GetArray("IdA");
  if (!first)
  {
    Missing("array 'IdA' of block 'Bonds'");
  }
  const vtkIdType n = first->GetNumberOfTuples();
  if (block->GetNumberOfCells() != n)
  {
    throw dem::InputError("RockDEM model block 'Bonds' has " +
      std::to_string(block->GetNumberOfCells()) + " lines for " + std::to_string(n) + " bonds.");
  }
  auto* idA = TypedCellArray<vtkTypeInt64Array>(cd, "IdA", n, 1, "64-bit integer");
  auto* idB = TypedCellArray<vtkTypeInt64Array>(cd, "IdB", n, 1, "64-bit integer");
  auto* mode = TypedCellArray<vtkUnsignedCharArray>(cd, "FailureMode", n, 1, "8-bit unsigned");
  auto scalars = [&](const char* name, std::vector<double>& out) {
    auto* a = TypedCellArray<vtkDoubleArray>(cd, name, n, 1, "double");
    out.assign(a->GetPointer(0), a->GetPointer(0) + n);
  };
  auto vectors = [&](const char* name, std::vector<dem::Vec3>& out) {
    auto* a = TypedCellArray<vtkDoubleArray>(cd, name, n, 3, "double");
    out.resize(static_cast<std::size_t>(n));
    if (n > 0)
    {
      std::memcpy(out.data(), a->GetPointer(0), static_cast<std::size_t>(n) * sizeof(dem::Vec3));
    }
  };
  b.idA.assign(idA->GetPointer(0), idA->GetPointer(0) + n);
  b.idB.assign(idB->GetPointer(0), idB->GetPointer(0) + n);
  scalars("BondRadius", b.radius);
  scalars("NormalStiffness", b.normalStiffness);
  scalars("ShearStiffness", b.shearStiffness);
  scalars("TensileStrength", b.tensileStrength);
  scalars("Cohesion", b.cohesion);
  scalars("FrictionAngle", b.frictionAngle);
  if (cd->GetArray("MomentContribution"))
  {
    scalars("MomentContribution", b.momentContribution);
  }
  else
  {
    b.momentContribution.assign(static_cast<std::size_t>(n), 1.0); // made before the factor
  }
  if (cd->GetArray("SofteningRatio"))
  {
    scalars("SofteningRatio", b.softening);
  }
  else
  {
    b.softening.assign(static_cast<std::size_t>(n), 0.0); // made before tension softening: brittle
  }
  scalars("NormalForce", b.normalForce);
  vectors("ShearForce", b.shearForce);
  scalars("TwistingMoment", b.twistingMoment);
  vectors("BendingMoment", b.bendingMoment);
  if (cd->GetArray("SofteningDamage"))
  {
    scalars("SofteningDamage", b.damage);
  }
  else
  {
    b.damage.assign(static_cast<std::size_t>(n), 0.0);
  }
  b.failure.assign(mode->GetPointer(0), mode->GetPointer(0) + n);
  scalars("FailureTime", b.failureTime);
  vectors("FailurePosition", b.failurePosition);
  vectors("FailureNormal", b.failureNormal);

  // The engine's invariants: pairs sorted by (IdA, IdB) with IdA < IdB, between
  // particles of the model, with a known failure mode.
  std::unordered_map<std::int64_t, int> known;
  known.reserve(model.particles.size());
  for (std::int64_t id : model.particles.id)
  {
    known.emplace(id, 0);
  }
  for (vtkIdType c = 0; c < n; ++c)
  {
    const std::int64_t a = b.idA[c];
    const std::int64_t bb = b.idB[c];
    if (!(a < bb) || (c > 0 && !(b.idA[c - 1] < a || (b.idA[c - 1] == a && b.idB[c - 1] < bb))))
    {
      throw dem::InputError("RockDEM model block 'Bonds' is not sorted by (IdA, IdB) with "
                            "IdA < IdB at bond " + std::to_string(c) + " (" + std::to_string(a) +
        ", " + std::to_string(bb) + ").");
    }
    if (!known.count(a) || !known.count(bb))
    {
      throw dem::InputError("RockDEM model block 'Bonds': bond " + std::to_string(c) + " joins " +
        std::to_string(a) + " and " + std::to_string(bb) +
        ", but the model has no particle with id " + std::to_string(known.count(a) ? bb : a) + ".");
    }
    if (b.failure[c] > static_cast<std::uint8_t>(dem::BondFailure::Inherited))
    {
      throw dem::InputError("RockDEM model block 'Bonds': bond " + std::to_string(c) +
        " has FailureMode " + std::to_string(b.failure[c]) + "; valid values are 0 to 3.");
    }
  }
}
} // namespace

dem::Model MultiBlockToModel(vtkMultiBlockDataSet* input)
{
  if (!input)
  {
    Missing("the model (no input data)");
  }
  if (input->GetNumberOfBlocks() == 0 && input->GetFieldData()->GetNumberOfArrays() == 0)
  {
    // What a RockDEM stage outputs after an error (or a source with nothing to build).
    throw dem::InputError("Input is not a RockDEM model: it is empty (no 'Particles' block), so "
                          "the stage before this one produced no model (see its message in Output "
                          "Messages or its Last Message).");
  }
  vtkPolyData* particles = NamedBlock(input, ParticlesBlockName);
  if (!particles)
  {
    Missing("block 'Particles'");
  }

  vtkFieldData* fd = input->GetFieldData();
  const vtkTypeInt64 version = IntField(fd, "RockDEMModelVersion");
  if (version != ModelLayoutVersion)
  {
    throw dem::InputError("RockDEM model layout version " + std::to_string(version) +
      " is not supported: this build reads version " + std::to_string(ModelLayoutVersion) + ".");
  }
  dem::Model model;
  for (int k = 0; k < 3; ++k)
  {
    model.domain.origin[k] = Field(fd, "DomainOrigin", k, 3);
    model.domain.size[k] = Field(fd, "DomainSize", k, 3);
    model.domain.periodic[k] = IntField(fd, "DomainPeriodic", k, 3) != 0;
    model.gravity[k] = Field(fd, "Gravity", k, 3);
  }
  model.domain.section2D = IntField(fd, "Section2D") != 0;
  // Data written before the specimen outline: a box.
  model.domain.cylinderAxis =
    fd->GetAbstractArray("CylinderAxis") ? static_cast<int>(IntField(fd, "CylinderAxis")) : -1;
  model.material.density = Field(fd, "Density");
  model.material.youngsModulus = Field(fd, "YoungsModulus");
  model.material.poissonsRatio = Field(fd, "PoissonsRatio");
  model.material.restitution = Field(fd, "Restitution");
  model.material.friction = Field(fd, "Friction");
  model.material.rollingFriction = Field(fd, "RollingFriction");
  model.clock.time = Field(fd, "Time");
  model.clock.step = IntField(fd, "Step");
  model.nextId = IntField(fd, "NextId");
  auto* rng = vtkTypeUInt64Array::SafeDownCast(RequireArray(fd, "RandomState", 4, 1));
  if (!rng)
  {
    Missing("64-bit unsigned array 'RandomState'");
  }
  std::array<std::uint64_t, 4> state{};
  for (int k = 0; k < 4; ++k)
  {
    state[k] = rng->GetValue(k);
  }
  model.random.setState(state);

  model.solver.contactLaw = static_cast<dem::ContactLaw>(IntField(fd, "ContactLaw"));
  model.solver.timestepSafety = Field(fd, "TimestepSafety");
  model.solver.requestedTimestep = Field(fd, "RequestedTimestep");
  model.solver.settlingDamping = Field(fd, "SettlingDamping");
  model.solver.skin = Field(fd, "VerletSkin");
  model.solver.threads = static_cast<int>(IntField(fd, "Threads"));
  model.solver.parallelThreshold = IntField(fd, "ParallelThreshold");
  model.clock.timestep = Field(fd, "Timestep");
  vtkDataArray* wallState = fd->GetArray("WallState");
  if (!wallState || wallState->GetNumberOfComponents() != WallStateComponents ||
    (wallState->GetNumberOfTuples() != 0 && wallState->GetNumberOfTuples() != 6))
  {
    Missing("array 'WallState' (6 walls x 11 values)");
  }
  for (vtkIdType w = 0; w < wallState->GetNumberOfTuples(); ++w)
  {
    double v[WallStateComponents];
    wallState->GetTuple(w, v);
    dem::Wall wall;
    wall.axis = static_cast<int>(v[0]);
    wall.side = static_cast<int>(v[1]);
    wall.position = v[2];
    wall.velocity = v[3];
    wall.active = v[4] != 0.0;
    wall.force = dem::Vec3(v[5], v[6], v[7]);
    wall.contactStiffness = v[8];
    wall.elasticForce = v[9];
    wall.contacts = static_cast<std::int64_t>(v[10]);
    model.walls.push_back(wall);
  }
  LoadTestFromFieldData(fd, model.solver.settlingDamping, model.test);
  ContactsFromPolyData(input, model);

  const vtkIdType n = particles->GetNumberOfPoints();
  dem::Particles& p = model.particles;
  p.position.resize(static_cast<std::size_t>(n));
  if (n > 0)
  {
    auto* pts = vtkDoubleArray::SafeDownCast(particles->GetPoints()->GetData());
    if (!pts)
    {
      Missing("double-precision particle positions");
    }
    std::memcpy(p.position.data(), pts->GetPointer(0), static_cast<std::size_t>(n) * sizeof(dem::Vec3));
  }
  vtkPointData* pd = particles->GetPointData();
  auto* ids = vtkTypeInt64Array::SafeDownCast(RequireArray(pd, "Id", n, 1));
  auto* flags = vtkTypeUInt32Array::SafeDownCast(RequireArray(pd, "Flags", n, 1));
  if (!ids || !flags)
  {
    Missing("integer arrays 'Id' and 'Flags'");
  }
  p.id.assign(ids->GetPointer(0), ids->GetPointer(0) + n);
  p.flags.assign(flags->GetPointer(0), flags->GetPointer(0) + n);
  ReadScalars(pd, "Radius", n, p.radius);
  ReadVectors(pd, "Velocity", n, p.velocity);
  ReadVectors(pd, "AngularVelocity", n, p.angularVelocity);
  ReadVectors(pd, "Displacement", n, p.displacement);
  ReadVectors(pd, "Force", n, p.force);
  ReadVectors(pd, "Torque", n, p.torque);
  ReadScalars(pd, "Mass", n, p.mass);
  ReadScalars(pd, "Inertia", n, p.inertia);
  BondsFromPolyData(input, model);
  return model;
}
} // namespace rockdem
