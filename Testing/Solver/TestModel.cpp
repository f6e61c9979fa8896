// The model as plain data: particle storage, mass properties, validation, derived values.
#include "dem/Errors.h"
#include "dem/Model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#if defined(__unix__)
#include <unistd.h>
#endif

namespace {

constexpr double kPi = 3.14159265358979323846;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

template <class F>
std::string messageOf(F&& f)
{
  try {
    f();
  } catch (const dem::InputError& e) {
    return e.what();
  }
  return "";
}

void expectMessage(const std::string& message, const std::string& parameter,
                   const std::string& value)
{
  EXPECT_NE(message.find(parameter), std::string::npos) << message;
  EXPECT_NE(message.find(value), std::string::npos) << message;
}

} // namespace

TEST(Particles, AppendStartsAtRestAndClearEmpties)
{
  dem::Particles p;
  p.reserve(4);
  p.append(dem::Vec3(1, 2, 3), 0.5, 17, dem::FlagFixed);
  p.append(dem::Vec3(4, 5, 6), 0.25, 18);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p.position[1], dem::Vec3(4, 5, 6));
  EXPECT_EQ(p.radius[0], 0.5);
  EXPECT_EQ(p.id[1], 18);
  EXPECT_EQ(p.flags[0], static_cast<std::uint32_t>(dem::FlagFixed));
  EXPECT_EQ(p.flags[1], 0u);
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_EQ(p.velocity[i], dem::Vec3::Zero());
    EXPECT_EQ(p.angularVelocity[i], dem::Vec3::Zero());
    EXPECT_EQ(p.displacement[i], dem::Vec3::Zero());
    EXPECT_EQ(p.force[i], dem::Vec3::Zero());
  }
  EXPECT_EQ(p.mass.size(), 2u);
  EXPECT_EQ(p.inertia.size(), 2u);
  p.clear();
  EXPECT_TRUE(p.empty());
  EXPECT_TRUE(p.position.empty() && p.velocity.empty() && p.id.empty() && p.flags.empty());
}

TEST(MassProperties, SolidSpheres)
{
  // Solid sphere: m = rho 4/3 pi r^3, I = 2/5 m r^2 (any mechanics textbook, e.g.
  // Goldstein, Classical Mechanics, table of moments of inertia).
  dem::Model model;
  model.material.density = 2650.0;
  model.particles.append(dem::Vec3(0.05, 0.05, 0.05), 0.003, 0);
  model.particles.append(dem::Vec3(0.02, 0.05, 0.05), 0.001, 1);
  dem::updateMassProperties(model);
  for (std::size_t i = 0; i < 2; ++i) {
    const double r = model.particles.radius[i];
    const double m = 2650.0 * 4.0 / 3.0 * kPi * r * r * r;
    EXPECT_NEAR(model.particles.mass[i], m, 1e-15 * m);
    EXPECT_NEAR(model.particles.inertia[i], 0.4 * m * r * r, 1e-15 * m * r * r);
  }
}

TEST(MassProperties, DiscsThroughTheSlab)
{
  // 2D section: a disc of radius r through a slab of thickness t, m = rho pi r^2 t, and
  // about its axis I = 1/2 m r^2 (solid cylinder).
  dem::Model model;
  model.domain.section2D = true;
  model.domain.size = dem::Vec3(0.2, 0.1, 0.004);
  model.material.density = 2000.0;
  model.particles.append(dem::Vec3(0.05, 0.05, model.domain.midPlaneZ()), 0.002, 0);
  dem::updateMassProperties(model);
  const double r = 0.002, t = 0.004;
  const double m = 2000.0 * kPi * r * r * t;
  EXPECT_NEAR(model.particles.mass[0], m, 1e-15 * m);
  EXPECT_NEAR(model.particles.inertia[0], 0.5 * m * r * r, 1e-15 * m * r * r);
  EXPECT_NEAR(dem::particleVolume(model.domain, r), kPi * r * r * t, 1e-20);
}

TEST(DomainValidation, AcceptsAnOrdinaryBox)
{
  dem::Domain d;
  d.origin = dem::Vec3(-1000.0, 5e5, 0.0);
  EXPECT_NO_THROW(dem::validate(d));
  d.section2D = true;
  d.periodic = { { true, true, false } };
  EXPECT_NO_THROW(dem::validate(d));
}

TEST(DomainValidation, RejectsNonPositiveOrNonFiniteDimensions)
{
  const char* labels[3] = { "X Dimension", "Y Dimension", "Z Dimension" };
  for (int a = 0; a < 3; ++a) {
    for (double bad : { 0.0, -0.1, kNaN, std::numeric_limits<double>::infinity() }) {
      dem::Domain d;
      d.size[a] = bad;
      const std::string m = messageOf([&] { dem::validate(d); });
      expectMessage(m, labels[a], dem::formatValue(bad) + " m");
    }
  }
}

TEST(DomainValidation, RejectsANaNOrigin)
{
  dem::Domain d;
  d.origin.y() = kNaN;
  expectMessage(messageOf([&] { dem::validate(d); }), "Origin Y", "nan");
}

TEST(DomainValidation, RejectsPeriodicZInA2DSection)
{
  dem::Domain d;
  d.section2D = true;
  d.periodic[2] = true;
  const std::string m = messageOf([&] { dem::validate(d); });
  expectMessage(m, "Periodic Z", "2D Section (XY)");
}

TEST(MaterialValidation, DefaultsAreValid)
{
  EXPECT_NO_THROW(dem::validate(dem::Material{}));
  dem::Material m;
  m.poissonsRatio = 0.0;
  m.restitution = 1.0;
  m.friction = 0.0;
  EXPECT_NO_THROW(dem::validate(m));
}

TEST(MaterialValidation, EachBadPropertyIsNamed)
{
  struct Case {
    void (*spoil)(dem::Material&);
    const char* label;
    const char* value;
  };
  const Case cases[] = {
    { [](dem::Material& m) { m.density = 0.0; }, "Density", "0 kg/m^3" },
    { [](dem::Material& m) { m.youngsModulus = -1e9; }, "Young's Modulus", "-1e+09 Pa" },
    { [](dem::Material& m) { m.poissonsRatio = 0.5; }, "Poisson's Ratio", "0.5" },
    { [](dem::Material& m) { m.poissonsRatio = -0.1; }, "Poisson's Ratio", "-0.1" },
    { [](dem::Material& m) { m.restitution = 1.5; }, "Restitution", "1.5" },
    { [](dem::Material& m) { m.friction = -0.2; }, "Friction", "-0.2" },
    { [](dem::Material& m) { m.rollingFriction = kNaN; }, "Rolling Friction", "nan" },
  };
  for (const Case& c : cases) {
    dem::Material m;
    c.spoil(m);
    expectMessage(messageOf([&] { dem::validate(m); }), c.label, c.value);
  }
}

TEST(ContactStiffness, FromTheModulus)
{
  // PHYSICS.md section 3: kn = A E / L, L = 2r; 3D A = pi r^2 gives kn = pi r E / 2;
  // 2D A = 2 r t gives kn = t E, independent of r.
  dem::Material material;
  material.youngsModulus = 70e9;
  dem::Domain domain;
  const double r = 0.002;
  EXPECT_NEAR(dem::derivedContactStiffness(material, domain, r), kPi * r * 70e9 / 2.0, 1.0);
  domain.section2D = true;
  domain.size.z() = 0.01;
  EXPECT_NEAR(dem::derivedContactStiffness(material, domain, r), 0.01 * 70e9, 1.0);
  EXPECT_NEAR(dem::derivedContactStiffness(material, domain, 5 * r), 0.01 * 70e9, 1.0);
  EXPECT_THROW(dem::derivedContactStiffness(material, domain, 0.0), dem::InputError);
}

TEST(Memory, AvailableMemoryIsPositiveAndAtMostPhysical)
{
  const std::size_t available = dem::availableMemoryBytes();
  EXPECT_GT(available, 0u);
#if defined(__unix__)
  const double physical =
    static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
  EXPECT_LE(static_cast<double>(available), physical);
#endif
}
