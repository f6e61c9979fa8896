// RockDEM engine: the model as plain data (see dem/Model.h). SI units.
#include "dem/Model.h"

#include "dem/Errors.h"

#include <algorithm>
#include <limits>
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
// Removing particles

namespace {
/// Keeps the elements whose flag in `keep` is set (same length), in order.
template <class T>
void keepOnly(std::vector<T>& values, const std::vector<std::uint8_t>& keep)
{
  if (values.empty()) {
    return; // an optional array (rolling springs without rolling friction)
  }
  std::size_t out = 0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (keep[i]) {
      values[out++] = values[i];
    }
  }
  values.resize(out);
}
} // namespace

// ---------------------------------------------------------------------------------------
// Spatial order

std::vector<std::size_t> spatialOrder(const Model& model)
{
  const Particles& p = model.particles;
  const std::size_t n = p.size();
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) {
    order[i] = i;
  }
  if (n == 0) {
    return order;
  }
  const double cell = 2.0 * *std::max_element(p.radius.begin(), p.radius.end());
  constexpr double kLargestCell = 2097151.0; // 21 bits per axis
  auto spread = [](std::uint64_t v) { // 21 bits -> every third bit
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
  };
  auto cellOf = [&](double x) {
    return static_cast<std::uint64_t>(std::min(kLargestCell, std::max(0.0, std::floor(x / cell))));
  };
  std::vector<std::uint64_t> key(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 c = p.position[i] - model.domain.origin;
    key[i] = spread(cellOf(c.x())) | spread(cellOf(c.y())) << 1 | spread(cellOf(c.z())) << 2;
  }
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key[a] < key[b]; });
  return order;
}

namespace {
template <class T>
void permute(std::vector<T>& values, const std::vector<std::size_t>& order)
{
  if (values.empty()) {
    return;
  }
  std::vector<T> out(values.size());
  for (std::size_t s = 0; s < order.size(); ++s) {
    out[s] = values[order[s]];
  }
  values.swap(out);
}
} // namespace

void permuteParticles(Particles& p, const std::vector<std::size_t>& order)
{
  static_assert(sizeof(Particles) == 11 * sizeof(std::vector<double>), "permute the new particle array below");
  permute(p.position, order);
  permute(p.velocity, order);
  permute(p.angularVelocity, order);
  permute(p.displacement, order);
  permute(p.force, order);
  permute(p.torque, order);
  permute(p.radius, order);
  permute(p.mass, order);
  permute(p.inertia, order);
  permute(p.id, order);
  permute(p.flags, order);
}

std::string RemovedParticles::summary(const std::string& why) const
{
  if (particles == 0) {
    return "";
  }
  return "Removed " + std::to_string(particles) + " particle(s) " + why + ", with " + std::to_string(bonds) +
    " bond(s) (" + std::to_string(intactBonds) + " intact) and " + std::to_string(contacts) +
    " contact(s) of theirs.";
}

RemovedParticles removeParticles(Model& model, const std::vector<std::uint8_t>& remove)
{
  // Every per-particle, per-contact and per-bond array is filtered below: a new one must be
  // added there (these fail to compile when a struct gains an array).
  static_assert(sizeof(Particles) == 11 * sizeof(std::vector<double>), "filter the new particle array below");
  static_assert(sizeof(ContactHistory) == 4 * sizeof(std::vector<double>), "filter the new contact array below");
  static_assert(sizeof(Bonds) == 19 * sizeof(std::vector<double>), "filter the new bond array below");
  RemovedParticles removed;
  Particles& p = model.particles;
  std::vector<std::int64_t> gone; // ids, sorted
  std::vector<std::uint8_t> keep(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    keep[i] = remove[i] ? 0 : 1;
    if (remove[i]) {
      gone.push_back(p.id[i]);
    }
  }
  if (gone.empty()) {
    return removed;
  }
  std::sort(gone.begin(), gone.end());
  auto isGone = [&](std::int64_t id) { return std::binary_search(gone.begin(), gone.end(), id); };
  removed.particles = gone.size();
  keepOnly(p.position, keep);
  keepOnly(p.velocity, keep);
  keepOnly(p.angularVelocity, keep);
  keepOnly(p.displacement, keep);
  keepOnly(p.force, keep);
  keepOnly(p.torque, keep);
  keepOnly(p.radius, keep);
  keepOnly(p.mass, keep);
  keepOnly(p.inertia, keep);
  keepOnly(p.id, keep);
  keepOnly(p.flags, keep);

  ContactHistory& c = model.contacts;
  std::vector<std::uint8_t> keepContact(c.size());
  for (std::size_t k = 0; k < c.size(); ++k) {
    keepContact[k] = isGone(c.idA[k]) || (c.idB[k] >= 0 && isGone(c.idB[k])) ? 0 : 1;
    removed.contacts += keepContact[k] ? 0 : 1;
  }
  keepOnly(c.idA, keepContact);
  keepOnly(c.idB, keepContact);
  keepOnly(c.shearSpring, keepContact);
  keepOnly(c.rollingSpring, keepContact);

  Bonds& b = model.bonds;
  std::vector<std::uint8_t> keepBond(b.size());
  for (std::size_t k = 0; k < b.size(); ++k) {
    keepBond[k] = isGone(b.idA[k]) || isGone(b.idB[k]) ? 0 : 1;
    if (!keepBond[k]) {
      ++removed.bonds;
      removed.intactBonds += b.broken(k) ? 0 : 1;
    }
  }
  keepOnly(b.idA, keepBond);
  keepOnly(b.idB, keepBond);
  keepOnly(b.radius, keepBond);
  keepOnly(b.normalStiffness, keepBond);
  keepOnly(b.shearStiffness, keepBond);
  keepOnly(b.tensileStrength, keepBond);
  keepOnly(b.cohesion, keepBond);
  keepOnly(b.frictionAngle, keepBond);
  keepOnly(b.momentContribution, keepBond);
  keepOnly(b.softening, keepBond);
  keepOnly(b.damage, keepBond);
  keepOnly(b.normalForce, keepBond);
  keepOnly(b.shearForce, keepBond);
  keepOnly(b.twistingMoment, keepBond);
  keepOnly(b.bendingMoment, keepBond);
  keepOnly(b.failure, keepBond);
  keepOnly(b.failureTime, keepBond);
  keepOnly(b.failurePosition, keepBond);
  keepOnly(b.failureNormal, keepBond);
  return removed;
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

std::array<double, 2> grainExtent(const Particles& particles, int axis)
{
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    lo = std::min(lo, particles.position[i][axis] - particles.radius[i]);
    hi = std::max(hi, particles.position[i][axis] + particles.radius[i]);
  }
  return { lo, hi };
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
  const bool axisValid = domain.section2D ? (domain.cylinderAxis == -1 || domain.cylinderAxis == 2)
                                          : (domain.cylinderAxis >= -1 && domain.cylinderAxis <= 2);
  if (!axisValid) {
    throw InputError("Cylinder Axis = " + std::to_string(domain.cylinderAxis) + " is out of range: valid values are " +
                     (domain.section2D ? std::string("-1 (a box) and 2 (a disc in the XY plane of a 2D section).")
                                       : std::string("-1 (a box), 0 (X), 1 (Y) and 2 (Z).")));
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
