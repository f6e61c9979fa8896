// The Model <-> VTK conversion is lossless (DESIGN.md, "Data flowing through the pipeline").
#include "vtkDEMModelConversion.h"

#include "dem/Errors.h"
#include "dem/Pack.h"
#include "dem/Simulation.h"

#include <vtkCompositeDataSet.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

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
}

TEST(ModelConversion, RoundTripIsBitwiseLossless)
{
  const dem::Model model = SamplePack();
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

TEST(ModelConversion, ParticlesBlockCarriesTheDocumentedArrays)
{
  const dem::Model model = SamplePack();
  vtkNew<vtkMultiBlockDataSet> mb;
  rockdem::ModelToMultiBlock(model, mb);
  ASSERT_EQ(mb->GetNumberOfBlocks(), 3u);
  EXPECT_STREQ(mb->GetMetaData(0u)->Get(vtkCompositeDataSet::NAME()), "Particles");
  EXPECT_STREQ(mb->GetMetaData(1u)->Get(vtkCompositeDataSet::NAME()), "Walls");
  EXPECT_STREQ(mb->GetMetaData(2u)->Get(vtkCompositeDataSet::NAME()), "Contacts");
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
