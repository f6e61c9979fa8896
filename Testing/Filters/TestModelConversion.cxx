// The Model <-> VTK conversion is lossless (DESIGN.md, "Data flowing through the pipeline").
#include "vtkDEMModelConversion.h"

#include "dem/Cement.h"
#include "dem/Errors.h"
#include "dem/Pack.h"
#include "dem/Simulation.h"

#include <vtkCellData.h>
#include <vtkCompositeDataSet.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkTypeInt64Array.h>
#include <vtkUnsignedCharArray.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <string>

namespace
{
dem::Model SamplePack()
{
  dem::Model model;
  model.domain.size = dem::Vec3(0.05, 0.04, 0.03);
  model.domain.origin = dem::Vec3(-1.0, 2.0, 3.5);
  model.domain.periodic = { { true, false, false } };
  model.material.density = 2500.0;
  model.material.friction = 0.35;
  dem::PackParameters params;
  params.initialElements = 300;
  params.minimumSize = 0.001;
  params.maximumSize = 0.002;
  params.randomSeed = 7;
  dem::buildPack(model, params);
  dem::growElements(model);
  // Step it so that walls, forces, torques and contact history are all populated.
  model.material.rollingFriction = 0.1;
  for (std::size_t i = 0; i < model.particles.size(); ++i)
  {
    // Sideways motion so that contacts slip and roll and carry history.
    model.particles.velocity[i] = dem::Vec3(0.05 * std::sin(1.0 * i), 0.05 * std::cos(1.0 * i), 0.0);
    model.particles.angularVelocity[i] = dem::Vec3(0.0, 0.0, 10.0 * std::sin(0.5 * i));
  }
  {
    dem::Simulation sim(model);
    sim.advance(200);
  }
  // Give every stored quantity a non-trivial value.
  for (std::size_t i = 0; i < model.particles.size(); ++i)
  {
    model.particles.velocity[i] = dem::Vec3(0.1 * i, -0.2, 1e-17 * i);
    model.particles.angularVelocity[i] = dem::Vec3(3.0, 1.0 / 3.0, -i);
    model.particles.displacement[i] = dem::Vec3(1e-9, 2e-9, 3e-9 * i);
    model.particles.force[i] = dem::Vec3(i, 0.7, -0.1);
  }
  model.particles.flags[3] |= dem::FlagFixed;
  model.clock.time = 0.125;
  model.clock.step = 123456789012LL;
  model.random.next();
  return model;
}

template <typename T>
bool BitwiseEqual(const std::vector<T>& a, const std::vector<T>& b)
{
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

/// A stepped pack (periodic in X), cemented with scattered strengths, stepped again so
/// that the bonds carry force and moment, with a few bonds broken by hand in every mode.
dem::Model CementedPack()
{
  dem::Model model;
  model.domain.size = dem::Vec3(0.05, 0.04, 0.03);
  model.domain.origin = dem::Vec3(-1.0, 2.0, 3.5);
  model.domain.periodic = { { true, false, false } };
  model.material.density = 2500.0;
  model.material.youngsModulus = 1.0e8;
  model.material.rollingFriction = 0.1;
  dem::PackParameters pack;
  pack.initialElements = 300;
  pack.minimumSize = 0.001;
  pack.maximumSize = 0.002;
  pack.randomSeed = 7;
  dem::buildPack(model, pack);
  dem::growElements(model);
  {
    dem::Simulation sim(model);
    sim.advance(200);
  }
  dem::CementParameters cement;
  cement.bondModulus = 1.0e8;
  cement.gapTolerance = 0.1;
  cement.strengthScatter = 0.2;
  cement.randomSeed = 11;
  dem::cement(model, cement);
  // Stir: sideways motion and spin so that the bonds stretch, shear, bend and twist.
  for (std::size_t i = 0; i < model.particles.size(); ++i)
  {
    model.particles.velocity[i] = dem::Vec3(0.01 * std::sin(1.0 * i), 0.01 * std::cos(1.0 * i), 0.0);
    model.particles.angularVelocity[i] = dem::Vec3(0.0, 2.0 * std::cos(0.3 * i), 2.0 * std::sin(0.5 * i));
  }
  {
    dem::Simulation sim(model);
    sim.advance(100);
  }
  dem::Bonds& b = model.bonds;
  for (std::size_t k = 0; k < b.size(); k += 7)
  {
    if (b.broken(k))
    {
      continue;
    }
    b.failure[k] = static_cast<std::uint8_t>(1 + (k / 7) % 3); // tension, shear, inherited
    b.failureTime[k] = model.clock.time - 1e-6 * static_cast<double>(k);
    b.failurePosition[k] = dem::Vec3(-0.99, 2.01 + 1e-5 * k, 3.51);
    b.failureNormal[k] = dem::Vec3(1.0, 2.0, -3.0 + 0.1 * k).normalized();
  }
  for (std::size_t k = 0; k < b.size(); k += 5) // tension softening: ratio and damage travel too
  {
    b.softening[k] = 0.5 + 0.25 * static_cast<double>(k % 11);
    b.damage[k] = b.broken(k) ? 0.0 : 0.1 + 0.1 * static_cast<double>(k % 7);
  }
  return model;
}

void ExpectBondsBitwiseEqual(const dem::Bonds& a, const dem::Bonds& b)
{
  EXPECT_TRUE(BitwiseEqual(a.idA, b.idA));
  EXPECT_TRUE(BitwiseEqual(a.idB, b.idB));
  EXPECT_TRUE(BitwiseEqual(a.radius, b.radius));
  EXPECT_TRUE(BitwiseEqual(a.normalStiffness, b.normalStiffness));
  EXPECT_TRUE(BitwiseEqual(a.shearStiffness, b.shearStiffness));
  EXPECT_TRUE(BitwiseEqual(a.tensileStrength, b.tensileStrength));
  EXPECT_TRUE(BitwiseEqual(a.cohesion, b.cohesion));
  EXPECT_TRUE(BitwiseEqual(a.frictionAngle, b.frictionAngle));
  EXPECT_TRUE(BitwiseEqual(a.momentContribution, b.momentContribution));
  EXPECT_TRUE(BitwiseEqual(a.softening, b.softening));
  EXPECT_TRUE(BitwiseEqual(a.damage, b.damage));
  EXPECT_TRUE(BitwiseEqual(a.normalForce, b.normalForce));
  EXPECT_TRUE(BitwiseEqual(a.shearForce, b.shearForce));
  EXPECT_TRUE(BitwiseEqual(a.twistingMoment, b.twistingMoment));
  EXPECT_TRUE(BitwiseEqual(a.bendingMoment, b.bendingMoment));
  EXPECT_TRUE(BitwiseEqual(a.failure, b.failure));
  EXPECT_TRUE(BitwiseEqual(a.failureTime, b.failureTime));
  EXPECT_TRUE(BitwiseEqual(a.failurePosition, b.failurePosition));
  EXPECT_TRUE(BitwiseEqual(a.failureNormal, b.failureNormal));
}

vtkPolyData* BondsBlock(vtkMultiBlockDataSet* mb)
{
  for (unsigned int k = 0; k < mb->GetNumberOfBlocks(); ++k)
  {
    if (mb->HasMetaData(k) && std::string(mb->GetMetaData(k)->Get(vtkCompositeDataSet::NAME())) == "Bonds")
    {
      return vtkPolyData::SafeDownCast(mb->GetBlock(k));
    }
  }
  return nullptr;
}
}

TEST(ModelConversion, RoundTripIsBitwiseLossless)
{
  dem::Model model = SamplePack();
  model.domain.cylinderAxis = 0; // a cylinder along X: the outline travels with the model
  vtkNew<vtkMultiBlockDataSet> mb;
  rockdem::ModelToMultiBlock(model, mb);
  const dem::Model back = rockdem::MultiBlockToModel(mb);

  const dem::Particles& a = model.particles;
  const dem::Particles& b = back.particles;
  EXPECT_TRUE(BitwiseEqual(a.position, b.position));
  EXPECT_TRUE(BitwiseEqual(a.velocity, b.velocity));
  EXPECT_TRUE(BitwiseEqual(a.angularVelocity, b.angularVelocity));
  EXPECT_TRUE(BitwiseEqual(a.displacement, b.displacement));
  EXPECT_TRUE(BitwiseEqual(a.force, b.force));
  EXPECT_TRUE(BitwiseEqual(a.torque, b.torque));
  ASSERT_GT(model.contacts.size(), 0u);
  EXPECT_TRUE(BitwiseEqual(model.contacts.idA, back.contacts.idA));
  EXPECT_TRUE(BitwiseEqual(model.contacts.idB, back.contacts.idB));
  EXPECT_TRUE(BitwiseEqual(model.contacts.shearSpring, back.contacts.shearSpring));
  EXPECT_TRUE(BitwiseEqual(model.contacts.rollingSpring, back.contacts.rollingSpring));
  ASSERT_EQ(model.walls.size(), 6u);
  ASSERT_EQ(back.walls.size(), 6u);
  for (std::size_t w = 0; w < 6; ++w)
  {
    EXPECT_EQ(model.walls[w].axis, back.walls[w].axis);
    EXPECT_EQ(model.walls[w].side, back.walls[w].side);
    EXPECT_EQ(model.walls[w].position, back.walls[w].position);
    EXPECT_EQ(model.walls[w].velocity, back.walls[w].velocity);
    EXPECT_EQ(model.walls[w].active, back.walls[w].active);
    EXPECT_EQ(model.walls[w].force, back.walls[w].force);
  }
  EXPECT_EQ(model.solver.contactLaw, back.solver.contactLaw);
  EXPECT_EQ(model.solver.timestepSafety, back.solver.timestepSafety);
  EXPECT_EQ(model.solver.settlingDamping, back.solver.settlingDamping);
  EXPECT_EQ(model.clock.timestep, back.clock.timestep);
  EXPECT_TRUE(BitwiseEqual(a.radius, b.radius));
  EXPECT_TRUE(BitwiseEqual(a.mass, b.mass));
  EXPECT_TRUE(BitwiseEqual(a.inertia, b.inertia));
  EXPECT_TRUE(BitwiseEqual(a.id, b.id));
  EXPECT_TRUE(BitwiseEqual(a.flags, b.flags));
  EXPECT_EQ(model.domain.origin, back.domain.origin);
  EXPECT_EQ(model.domain.size, back.domain.size);
  EXPECT_EQ(model.domain.periodic, back.domain.periodic);
  EXPECT_EQ(model.domain.section2D, back.domain.section2D);
  EXPECT_EQ(model.domain.cylinderAxis, back.domain.cylinderAxis);
  EXPECT_EQ(model.material.density, back.material.density);
  EXPECT_EQ(model.material.youngsModulus, back.material.youngsModulus);
  EXPECT_EQ(model.material.poissonsRatio, back.material.poissonsRatio);
  EXPECT_EQ(model.material.restitution, back.material.restitution);
  EXPECT_EQ(model.material.friction, back.material.friction);
  EXPECT_EQ(model.material.rollingFriction, back.material.rollingFriction);
  EXPECT_EQ(model.gravity, back.gravity);
  EXPECT_EQ(model.clock.time, back.clock.time);
  EXPECT_EQ(model.clock.step, back.clock.step);
  EXPECT_EQ(model.nextId, back.nextId);
  EXPECT_TRUE(model.random == back.random);
}

TEST(ModelConversion, DataWithoutTheCylinderAxisReadsAsABox)
{
  dem::Model model = SamplePack();
  model.domain.cylinderAxis = 2;
  vtkNew<vtkMultiBlockDataSet> mb;
  rockdem::ModelToMultiBlock(model, mb);
  EXPECT_EQ(rockdem::MultiBlockToModel(mb).domain.cylinderAxis, 2);
  mb->GetFieldData()->RemoveArray("CylinderAxis"); // data saved before the outline existed
  EXPECT_EQ(rockdem::MultiBlockToModel(mb).domain.cylinderAxis, -1);
}

TEST(ModelConversion, ConsolidationDampingTravelsAndOlderDataReadItAsTheirSettlingDamping)
{
  dem::Model model = SamplePack();
  model.solver.settlingDamping = 0.0;
  model.test.settings.consolidationDamping = 0.55;
  vtkNew<vtkMultiBlockDataSet> mb;
  rockdem::ModelToMultiBlock(model, mb);
  EXPECT_EQ(rockdem::MultiBlockToModel(mb).test.settings.consolidationDamping, 0.55);
  mb->GetFieldData()->RemoveArray("TestConsolidationDamping"); // data saved before it existed
  EXPECT_EQ(rockdem::MultiBlockToModel(mb).test.settings.consolidationDamping, 0.0);
}

TEST(ModelConversion, ParticlesBlockCarriesTheDocumentedArrays)
{
  const dem::Model model = SamplePack();
  vtkNew<vtkMultiBlockDataSet> mb;
  rockdem::ModelToMultiBlock(model, mb);
  ASSERT_EQ(mb->GetNumberOfBlocks(), 4u);
  EXPECT_STREQ(mb->GetMetaData(0u)->Get(vtkCompositeDataSet::NAME()), "Particles");
  EXPECT_STREQ(mb->GetMetaData(1u)->Get(vtkCompositeDataSet::NAME()), "Walls");
  EXPECT_STREQ(mb->GetMetaData(2u)->Get(vtkCompositeDataSet::NAME()), "Contacts");
  EXPECT_STREQ(mb->GetMetaData(3u)->Get(vtkCompositeDataSet::NAME()), "Bonds");
  // An uncemented model has an empty Bonds block.
  auto* bonds = vtkPolyData::SafeDownCast(mb->GetBlock(3));
  ASSERT_NE(bonds, nullptr);
  EXPECT_EQ(bonds->GetNumberOfLines(), 0);
  auto* pd = vtkPolyData::SafeDownCast(mb->GetBlock(0));
  ASSERT_NE(pd, nullptr);
  EXPECT_EQ(pd->GetNumberOfPoints(), static_cast<vtkIdType>(model.particles.size()));
  EXPECT_EQ(pd->GetNumberOfVerts(), static_cast<vtkIdType>(model.particles.size()));
  for (const char* name : { "Id", "Radius", "Velocity", "AngularVelocity", "Displacement", "Force", "Torque",
         "Mass", "Inertia", "Flags", "Fixed", "SizeClass" })
  {
    EXPECT_NE(pd->GetPointData()->GetArray(name), nullptr) << name;
  }
  EXPECT_EQ(pd->GetPointData()->GetArray("Fixed")->GetComponent(3, 0), 1.0);
}

// A round trip followed by a step is bitwise identical to the step without it
// (DESIGN.md "Data flowing through the pipeline").
TEST(ModelConversion, RoundTripThenStepEqualsStep)
{
  dem::Model direct = SamplePack();
  vtkNew<vtkMultiBlockDataSet> mb;
  rockdem::ModelToMultiBlock(direct, mb);
  dem::Model viaVtk = rockdem::MultiBlockToModel(mb);
  {
    dem::Simulation a(direct);
    a.advance(100);
  }
  {
    dem::Simulation b(viaVtk);
    b.advance(100);
  }
  EXPECT_TRUE(BitwiseEqual(direct.particles.position, viaVtk.particles.position));
  EXPECT_TRUE(BitwiseEqual(direct.particles.velocity, viaVtk.particles.velocity));
  EXPECT_TRUE(BitwiseEqual(direct.particles.angularVelocity, viaVtk.particles.angularVelocity));
  EXPECT_TRUE(BitwiseEqual(direct.contacts.shearSpring, viaVtk.contacts.shearSpring));
}

TEST(ModelConversion, RoundTripWithBondsIsBitwiseLossless)
{
  const dem::Model model = CementedPack();
  const dem::Bonds& b = model.bonds;
  ASSERT_GT(b.size(), 100u);
  // The state is non-trivial: forces and moments from the stirring, every failure mode.
  const dem::BondCounts counts = dem::countBonds(b);
  EXPECT_GT(counts.tension, 0u);
  EXPECT_GT(counts.shear, 0u);
  EXPECT_GT(counts.inherited, 0u);
  double fn = 0.0, fs = 0.0, mt = 0.0, mb = 0.0;
  for (std::size_t k = 0; k < b.size(); ++k)
  {
    fn += std::abs(b.normalForce[k]);
    fs += b.shearForce[k].norm();
    mt += std::abs(b.twistingMoment[k]);
    mb += b.bendingMoment[k].norm();
  }
  EXPECT_GT(fn, 0.0);
  EXPECT_GT(fs, 0.0);
  EXPECT_GT(mt, 0.0);
  EXPECT_GT(mb, 0.0);

  vtkNew<vtkMultiBlockDataSet> vtk;
  rockdem::ModelToMultiBlock(model, vtk);
  const dem::Model back = rockdem::MultiBlockToModel(vtk);
  ExpectBondsBitwiseEqual(model.bonds, back.bonds);
  EXPECT_TRUE(BitwiseEqual(model.particles.position, back.particles.position));
  EXPECT_TRUE(BitwiseEqual(model.contacts.shearSpring, back.contacts.shearSpring));
}

TEST(ModelConversion, BondsBlockDrawsOneShortLinePerBond)
{
  const dem::Model model = CementedPack();
  vtkNew<vtkMultiBlockDataSet> mb;
  rockdem::ModelToMultiBlock(model, mb);
  vtkPolyData* bonds = BondsBlock(mb);
  ASSERT_NE(bonds, nullptr);
  const auto n = static_cast<vtkIdType>(model.bonds.size());
  ASSERT_EQ(bonds->GetNumberOfLines(), n);
  ASSERT_EQ(bonds->GetNumberOfCells(), n);
  for (const char* name : { "IdA", "IdB", "BondRadius", "NormalStiffness", "ShearStiffness",
         "TensileStrength", "Cohesion", "FrictionAngle", "NormalForce", "ShearForce",
         "TwistingMoment", "BendingMoment", "Broken", "FailureMode", "FailureTime",
         "FailurePosition", "FailureNormal" })
  {
    vtkDataArray* a = bonds->GetCellData()->GetArray(name);
    ASSERT_NE(a, nullptr) << name;
    EXPECT_EQ(a->GetNumberOfTuples(), n) << name;
  }
  // Broken is 1 exactly where FailureMode is not 0.
  auto* broken = vtkUnsignedCharArray::SafeDownCast(bonds->GetCellData()->GetArray("Broken"));
  ASSERT_NE(broken, nullptr);
  for (vtkIdType c = 0; c < n; ++c)
  {
    EXPECT_EQ(broken->GetValue(c), model.bonds.broken(static_cast<std::size_t>(c)) ? 1 : 0);
  }
  // Each line joins A's centre to B's (minimum) image: never longer than the pair reach,
  // even for the bonds across the periodic X seam, of which there are some.
  std::map<std::int64_t, std::size_t> slot;
  for (std::size_t i = 0; i < model.particles.size(); ++i)
  {
    slot[model.particles.id[i]] = i;
  }
  int acrossSeam = 0;
  for (vtkIdType c = 0; c < n; ++c)
  {
    const std::size_t a = slot.at(model.bonds.idA[c]);
    const std::size_t b = slot.at(model.bonds.idB[c]);
    vtkIdType npts = 0;
    const vtkIdType* pts = nullptr;
    bonds->GetCellPoints(c, npts, pts);
    ASSERT_EQ(npts, 2);
    double p0[3], p1[3];
    bonds->GetPoint(pts[0], p0);
    bonds->GetPoint(pts[1], p1);
    const dem::Vec3 x0(p0[0], p0[1], p0[2]);
    const dem::Vec3 x1(p1[0], p1[1], p1[2]);
    EXPECT_EQ(x0, model.particles.position[a]);
    const double reach = model.particles.radius[a] + model.particles.radius[b];
    EXPECT_LT((x1 - x0).norm(), 1.5 * reach) << "bond " << c;
    if ((model.particles.position[b] - model.particles.position[a]).norm() > 0.5 * model.domain.size.x())
    {
      ++acrossSeam;
      EXPECT_NEAR(std::abs(x1.x() - model.particles.position[b].x()), model.domain.size.x(), 1e-12);
    }
    else
    {
      EXPECT_NEAR((x1 - model.particles.position[b]).norm(), 0.0, 1e-15);
    }
  }
  EXPECT_GT(acrossSeam, 0);
}

TEST(ModelConversion, ModelWithoutBondsBlockHasNoBonds)
{
  const dem::Model model = CementedPack();
  vtkNew<vtkMultiBlockDataSet> mb;
  rockdem::ModelToMultiBlock(model, mb);
  mb->SetNumberOfBlocks(3); // as written before bonds existed
  const dem::Model back = rockdem::MultiBlockToModel(mb);
  EXPECT_EQ(back.bonds.size(), 0u);
  EXPECT_TRUE(BitwiseEqual(model.particles.position, back.particles.position));
}

TEST(ModelConversion, InconsistentBondsAreRejected)
{
  const dem::Model model = CementedPack();
  auto expectError = [&](const char* what, const std::function<void(vtkPolyData*)>& spoil) {
    vtkNew<vtkMultiBlockDataSet> mb;
    rockdem::ModelToMultiBlock(model, mb);
    vtkPolyData* bonds = BondsBlock(mb);
    ASSERT_NE(bonds, nullptr);
    spoil(bonds);
    try
    {
      rockdem::MultiBlockToModel(mb);
      ADD_FAILURE() << what << ": expected dem::InputError";
    }
    catch (const dem::InputError& e)
    {
      EXPECT_NE(std::string(e.what()).find("Bonds"), std::string::npos) << what << ": " << e.what();
    }
  };
  expectError("short array", [](vtkPolyData* bonds) {
    vtkDataArray* a = bonds->GetCellData()->GetArray("TensileStrength");
    a->SetNumberOfTuples(a->GetNumberOfTuples() - 1);
  });
  expectError("missing array", [](vtkPolyData* bonds) { bonds->GetCellData()->RemoveArray("BendingMoment"); });
  expectError("wrong type", [](vtkPolyData* bonds) {
    vtkNew<vtkDoubleArray> mode;
    mode->SetName("FailureMode");
    mode->SetNumberOfTuples(bonds->GetNumberOfCells());
    mode->FillValue(0.0);
    bonds->GetCellData()->AddArray(mode);
  });
  expectError("unknown failure mode", [](vtkPolyData* bonds) {
    vtkUnsignedCharArray::SafeDownCast(bonds->GetCellData()->GetArray("FailureMode"))->SetValue(0, 9);
  });
  expectError("unsorted pairs", [](vtkPolyData* bonds) {
    auto* idA = vtkTypeInt64Array::SafeDownCast(bonds->GetCellData()->GetArray("IdA"));
    auto* idB = vtkTypeInt64Array::SafeDownCast(bonds->GetCellData()->GetArray("IdB"));
    const vtkTypeInt64 a = idA->GetValue(0);
    idA->SetValue(0, idB->GetValue(0));
    idB->SetValue(0, a);
  });
  expectError("unknown particle", [](vtkPolyData* bonds) {
    auto* idB = vtkTypeInt64Array::SafeDownCast(bonds->GetCellData()->GetArray("IdB"));
    const vtkIdType last = idB->GetNumberOfTuples() - 1;
    idB->SetValue(last, 1000000000);
  });
}

// A round trip followed by a step is bitwise identical to the step without it, with
// bonds carrying force, moment and broken bonds in the model.
TEST(ModelConversion, RoundTripThenStepEqualsStepWithBonds)
{
  dem::Model direct = CementedPack();
  vtkNew<vtkMultiBlockDataSet> mb;
  rockdem::ModelToMultiBlock(direct, mb);
  dem::Model viaVtk = rockdem::MultiBlockToModel(mb);
  {
    dem::Simulation a(direct);
    a.advance(100);
  }
  {
    dem::Simulation b(viaVtk);
    b.advance(100);
  }
  EXPECT_TRUE(BitwiseEqual(direct.particles.position, viaVtk.particles.position));
  EXPECT_TRUE(BitwiseEqual(direct.particles.velocity, viaVtk.particles.velocity));
  EXPECT_TRUE(BitwiseEqual(direct.particles.angularVelocity, viaVtk.particles.angularVelocity));
  EXPECT_TRUE(BitwiseEqual(direct.contacts.shearSpring, viaVtk.contacts.shearSpring));
  ExpectBondsBitwiseEqual(direct.bonds, viaVtk.bonds);
}

TEST(ModelConversion, RejectsDataThatIsNotAModel)
{
  vtkNew<vtkMultiBlockDataSet> empty;
  try
  {
    rockdem::MultiBlockToModel(empty);
    FAIL() << "expected dem::InputError";
  }
  catch (const dem::InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("Particles"), std::string::npos) << e.what();
  }
}

TEST(ModelConversion, DomainBoxHasTwelveEdgesAtTheBoxCorners)
{
  dem::Domain d;
  d.origin = dem::Vec3(1, 2, 3);
  d.size = dem::Vec3(4, 5, 6);
  vtkNew<vtkPolyData> box;
  rockdem::DomainBoxToPolyData(d, box);
  EXPECT_EQ(box->GetNumberOfLines(), 12);
  double b[6];
  box->GetBounds(b);
  EXPECT_DOUBLE_EQ(b[0], 1);
  EXPECT_DOUBLE_EQ(b[1], 5);
  EXPECT_DOUBLE_EQ(b[2], 2);
  EXPECT_DOUBLE_EQ(b[3], 7);
  EXPECT_DOUBLE_EQ(b[4], 3);
  EXPECT_DOUBLE_EQ(b[5], 9);
}

// A triaxial test in mid-shear survives the round trip with its whole state (settings,
// stage, servo walls, history) and then steps exactly like the run that never left the
// engine (DESIGN.md: the conversion is lossless; resume is exact).
TEST(ModelConversion, TriaxialMidShearResumesExactly)
{
  dem::Model model;
  model.domain.size = dem::Vec3(0.02, 0.02, 0.02);
  model.material.youngsModulus = 1e8;
  model.gravity.setZero();
  dem::PackParameters params;
  params.initialElements = 500;
  params.minimumSize = 0.001;
  params.maximumSize = 0.0015;
  dem::buildPack(model, params);
  dem::growElements(model);
  dem::LoadTestSettings s;
  s.mode = dem::TestMode::Triaxial;
  s.confiningStress = 1e5;
  s.strainRate = 0.5;
  s.sampleInterval = 100;
  dem::startLoadTest(model, s);
  {
    dem::Simulation sim(model);
    for (int k = 0; k < 200 && model.test.stage != dem::TestStage::Shear; ++k)
    {
      sim.advance(100);
    }
    sim.advance(750); // into shear, between two samples
  }
  ASSERT_EQ(model.test.stage, dem::TestStage::Shear);
  ASSERT_GT(model.test.history.size(), 3u);

  vtkNew<vtkMultiBlockDataSet> mb;
  rockdem::ModelToMultiBlock(model, mb);
  dem::Model back = rockdem::MultiBlockToModel(mb);
  EXPECT_EQ(back.test.settings.mode, dem::TestMode::Triaxial);
  EXPECT_EQ(back.test.stage, model.test.stage);
  EXPECT_EQ(back.test.initialLength, model.test.initialLength);
  EXPECT_EQ(back.test.initialSpread, model.test.initialSpread);
  EXPECT_EQ(back.test.peakDeviator, model.test.peakDeviator);
  EXPECT_EQ(back.test.stepsSinceSample, model.test.stepsSinceSample);
  EXPECT_EQ(back.test.history, model.test.history);
  for (std::size_t w = 0; w < 6; ++w)
  {
    EXPECT_EQ(back.walls[w].position, model.walls[w].position);
    EXPECT_EQ(back.walls[w].velocity, model.walls[w].velocity);
    EXPECT_EQ(back.walls[w].elasticForce, model.walls[w].elasticForce);
    EXPECT_EQ(back.walls[w].contactStiffness, model.walls[w].contactStiffness);
  }
  {
    dem::Simulation a(model);
    a.advance(500);
  }
  {
    dem::Simulation b(back);
    b.advance(500);
  }
  EXPECT_TRUE(BitwiseEqual(model.particles.position, back.particles.position));
  EXPECT_TRUE(BitwiseEqual(model.particles.velocity, back.particles.velocity));
  EXPECT_EQ(model.test.history, back.test.history);
  EXPECT_EQ(model.walls[5].position, back.walls[5].position);
}
