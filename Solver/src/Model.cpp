// RockDEM engine: the model as plain data (see dem/Model.h). SI units.
#include "dem/Model.h"

#include "dem/Errors.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#if defined(__unix__) || defined(__APPLE__)
#include <unistd.h>
#endif

namespace dem {

namespace {
constexpr double kPi = 3.14159265358979323846;
const char* const kAxisName[3] = { "X", "Y", "Z" };
} // namespace

// ---------------------------------------------------------------------------------------
// Particles

void Particles::clear()
{
  position.clear();
  velocity.clear();
  angularVelocity.clear();
  displacement.clear();
  force.clear();
  torque.clear();
  radius.clear();
  mass.clear();
  inertia.clear();
  id.clear();
  flags.clear();
}

void Particles::reserve(std::size_t n)
{
  position.reserve(n);
  velocity.reserve(n);
  angularVelocity.reserve(n);
  displacement.reserve(n);
  force.reserve(n);
  torque.reserve(n);
  radius.reserve(n);
  mass.reserve(n);
  inertia.reserve(n);
  id.reserve(n);
  flags.reserve(n);
}

void Particles::append(const Vec3& x, double r, std::int64_t globalId, std::uint32_t flagBits)
{
  position.push_back(x);
  velocity.push_back(Vec3::Zero());
  angularVelocity.push_back(Vec3::Zero());
  displacement.push_back(Vec3::Zero());
  force.push_back(Vec3::Zero());
  torque.push_back(Vec3::Zero());
  radius.push_back(r);
  mass.push_back(0.0);
  inertia.push_back(0.0);
  id.push_back(globalId);
  flags.push_back(flagBits);
}

// ---------------------------------------------------------------------------------------
// Mass properties

double particleVolume(const Domain& domain, double radius)
{
  const double r = radius;
  if (domain.section2D) {
    const double t = domain.slabThickness(); // m
    return kPi * r * r * t;                  // disc through the slab
  }
  return 4.0 / 3.0 * kPi * r * r * r;        // sphere
}

void updateMassProperties(Model& model)
{
  Particles& p = model.particles;
  const double rho = model.material.density; // kg/m^3
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double r = p.radius[i];
    const double m = rho * particleVolume(model.domain, r);
    p.mass[i] = m;
    // Solid sphere: I = 2/5 m r^2. Disc about its axis (z): I = 1/2 m r^2.
    p.inertia[i] = (model.domain.section2D ? 0.5 : 0.4) * m * r * r;
  }
}

// ---------------------------------------------------------------------------------------
// Validation

void validate(const Domain& domain)
{
  for (int a = 0; a < 3; ++a) {
    requireFinite(std::string("Origin ") + kAxisName[a], domain.origin[a], "m");
  }
  for (int a = 0; a < 3; ++a) {
    requirePositive(std::string(kAxisName[a]) + " Dimension", domain.size[a], "m");
  }
  if (domain.section2D && domain.periodic[2]) {
    throw InputError("Periodic Z = on cannot be combined with 2D Section (XY) = on: a section "
                     "has no motion along Z to wrap. Turn Periodic Z off.");
  }
}

void validate(const Material& material)
{
  requirePositive("Density", material.density, "kg/m^3");
  requirePositive("Young's Modulus", material.youngsModulus, "Pa");
  // Poisson's ratio of a stable isotropic solid is below 1/2; negative (auxetic) values are
  // not meaningful for rock grains, so the range is [0, 0.5).
  if (!(std::isfinite(material.poissonsRatio) && material.poissonsRatio >= 0.0 &&
        material.poissonsRatio < 0.5)) {
    throw InputError("Poisson's Ratio = " + formatValue(material.poissonsRatio) +
                     " is out of range: valid range is [0, 0.5).");
  }
  requireInRange("Restitution", material.restitution, 0.0, 1.0);
  requireNonNegative("Friction", material.friction);
  requireNonNegative("Rolling Friction", material.rollingFriction);
}

void validate(const Particles& particles)
{
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const std::string name = "particle " + std::to_string(particles.id[i]);
    for (int a = 0; a < 3; ++a) {
      requireFinite(std::string(kAxisName[a]) + " of " + name, particles.position[i][a], "m");
    }
    requirePositive("Radius of " + name, particles.radius[i], "m");
  }
}

// ---------------------------------------------------------------------------------------
// Derived quantities

double derivedContactStiffness(const Material& material, const Domain& domain, double radius)
{
  // PHYSICS.md section 3: kn = A E / L, A = pi r^2 (3D) or 2 r t (2D), L = 2 r.
  requirePositive("Maximum Size", radius, "m");
  const double r = radius;
  const double E = material.youngsModulus;                                      // Pa
  const double A = domain.section2D ? 2.0 * r * domain.slabThickness() : kPi * r * r; // m^2
  const double L = 2.0 * r;                                                     // m
  return A * E / L;                                                             // N/m
}

std::size_t availableMemoryBytes()
{
  std::ifstream meminfo("/proc/meminfo");
  std::string line;
  while (std::getline(meminfo, line)) {
    if (line.rfind("MemAvailable:", 0) == 0) {
      std::istringstream fields(line.substr(13));
      unsigned long long kibibytes = 0;
      if (fields >> kibibytes) {
        return static_cast<std::size_t>(kibibytes) * 1024u;
      }
    }
  }
#if defined(__unix__) || defined(__APPLE__)
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long pageSize = sysconf(_SC_PAGE_SIZE);
  if (pages > 0 && pageSize > 0) {
    return static_cast<std::size_t>(pages) * static_cast<std::size_t>(pageSize);
  }
#endif
  return static_cast<std::size_t>(-1); // unknown: do not refuse on memory grounds
}

} // namespace dem
