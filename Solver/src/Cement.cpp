#include "dem/Cement.h"

#include "dem/Errors.h"
#include "dem/SizeClassGrids.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <tuple>

namespace dem {
namespace {

constexpr double Pi = 3.14159265358979323846;

/// splitmix64 finaliser: a well-mixed 64-bit hash step.
std::uint64_t mix(std::uint64_t z)
{
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

/// Uniform double in (0, 1) from a 64-bit hash (53 bits, never 0).
double unitOpen(std::uint64_t h)
{
  return (static_cast<double>(h >> 11) + 0.5) * 0x1.0p-53;
}

} // namespace

double strengthFactor(std::uint64_t seed, std::int64_t a, std::int64_t b, int which, double cov)
{
  if (cov <= 0.0) {
    return 1.0;
  }
  // A stream keyed by (seed, a, b, which): the same bond always draws the same value,
  // whatever the order in which bonds are made.
  std::uint64_t h = mix(seed);
  h = mix(h ^ static_cast<std::uint64_t>(a));
  h = mix(h ^ static_cast<std::uint64_t>(b));
  h = mix(h ^ static_cast<std::uint64_t>(which));
  const double u1 = unitOpen(h);
  const double u2 = unitOpen(mix(h));
  const double gauss = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * Pi * u2); // Box-Muller
  // Lognormal with mean 1 and coefficient of variation cov (always positive).
  const double s2 = std::log(1.0 + cov * cov);
  return std::exp(-0.5 * s2 + std::sqrt(s2) * gauss);
}

double bondedCoordination(std::size_t bonds, std::size_t particles)
{
  return particles > 0 ? 2.0 * static_cast<double>(bonds) / static_cast<double>(particles) : 0.0;
}

void validate(const CementParameters& p)
{
  if (!(p.gapTolerance >= 0.0 && p.gapTolerance <= kMaxGapTolerance)) {
    throw InputError("Gap Tolerance = " + formatValue(p.gapTolerance) +
                     " is out of range: valid range is [0, " + formatValue(kMaxGapTolerance) +
                     "] (a gap of at most one smaller radius; to bond over a longer range, use "
                     "Bond Range).");
  }
  if (!(p.bondRange >= 1.0 && p.bondRange <= kMaxBondRange)) {
    throw InputError("Bond Range = " + formatValue(p.bondRange) +
                     " is out of range: valid range is [1, " + formatValue(kMaxBondRange) +
                     "] (centre distance over rA + rB; 1 = touching pairs, 1.2-1.5 is usual).");
  }
  if (!(p.bondRadiusMultiplier > 0.0 && p.bondRadiusMultiplier <= 1.0)) {
    throw InputError("Bond Radius Multiplier = " + formatValue(p.bondRadiusMultiplier) +
                     " is out of range: valid range is (0, 1].");
  }
  requirePositive("Bond Modulus", p.bondModulus, "Pa");
  requirePositive("Bond Stiffness Ratio", p.bondStiffnessRatio);
  requireNonNegative("Bond Normal Stiffness", p.bondNormalStiffness, "N/m^3");
  requirePositive("Tensile Strength", p.tensileStrength, "Pa");
  requirePositive("Cohesion", p.cohesion, "Pa");
  if (!(p.frictionAngle >= 0.0 && p.frictionAngle < 90.0)) {
    throw InputError("Friction Angle = " + formatValue(p.frictionAngle) +
                     " degrees is out of range: valid range is [0, 90) degrees.");
  }
  requireInRange("Strength Scatter", p.strengthScatter, 0.0, 1.0);
  requireInRange("Moment Contribution", p.momentContribution, 0.0, 1.0);
  requireInRange("Softening Ratio", p.softeningRatio, 0.0, kMaxSofteningRatio);
}

std::string CementReport::summary() const
{
  std::ostringstream s;
  s << "Cement: installed " << bonds << " bonds";
  if (replaced > 0) {
    s << " (replacing " << replaced << ")";
  }
  char coordination[32];
  std::snprintf(coordination, sizeof(coordination), "%.2f", bondedCoordination);
  s << " between " << particles << " particles, bonded coordination " << coordination << " ("
    << longBonds << " across a gap)";
  s << "; bond stiffness " << formatValue(bondStiffness) << " N/m^3 for the largest particles.";
  return s.str();
}

CementReport cement(Model& model, const CementParameters& params)
{
  validate(params);
  const Particles& p = model.particles;
  const Domain& d = model.domain;
  CementReport report;
  report.replaced = model.bonds.size();
  model.bonds.clear();
  if (p.empty()) {
    return report;
  }
  const auto [rmin, rmax] = std::minmax_element(p.radius.begin(), p.radius.end());
  SizeClassGrids grids(d, *rmin, *rmax);
  grids.insertAll(p);

  struct Candidate {
    std::int64_t a, b;
    std::size_t i, j;
  };
  std::vector<Candidate> pairs;
  std::vector<std::size_t> keys;
  for (std::size_t i = 0; i < p.size(); ++i) {
    // The tolerance scales with the smaller radius, so r_i bounds its reach; the range
    // reaches a gap of (range - 1)(r_i + r_j) <= (range - 1)(r_i + r_max).
    // (slightly widened: the search is strict, the tests below are exact)
    const double gapReach = std::max(params.gapTolerance * p.radius[i],
                                     (params.bondRange - 1.0) * (p.radius[i] + *rmax));
    const double reach = gapReach * (1.0 + 1e-9) + 1e-9 * p.radius[i];
    grids.neighboursWithin(p.position[i], p.radius[i], reach, i, keys);
    for (std::size_t j : keys) {
      if (j <= i) {
        continue;
      }
      const double distance = grids.separation(p.position[i], p.position[j]).norm();
      const double gap = distance - p.radius[i] - p.radius[j];
      const bool nearlyTouching = gap <= params.gapTolerance * std::min(p.radius[i], p.radius[j]);
      const bool inRange =
        params.bondRange > 1.0 && distance <= params.bondRange * (p.radius[i] + p.radius[j]);
      if (nearlyTouching || inRange) {
        report.longBonds += gap > 0.0 ? 1 : 0;
        const bool ordered = p.id[i] < p.id[j];
        pairs.push_back({ ordered ? p.id[i] : p.id[j], ordered ? p.id[j] : p.id[i], i, j });
      }
    }
  }
  std::sort(pairs.begin(), pairs.end(),
    [](const Candidate& x, const Candidate& y) { return std::tie(x.a, x.b) < std::tie(y.a, y.b); });

  const double phi = params.frictionAngle * Pi / 180.0;
  for (const Candidate& c : pairs) {
    const double ri = p.radius[c.i];
    const double rj = p.radius[c.j];
    const double kn =
      params.bondNormalStiffness > 0.0 ? params.bondNormalStiffness : params.bondModulus / (ri + rj);
    const double ks = kn * params.bondStiffnessRatio;
    model.bonds.append(c.a, c.b, params.bondRadiusMultiplier * std::min(ri, rj), kn, ks,
      params.tensileStrength * strengthFactor(params.randomSeed, c.a, c.b, 0, params.strengthScatter),
      params.cohesion * strengthFactor(params.randomSeed, c.a, c.b, 1, params.strengthScatter), phi,
      params.momentContribution, params.softeningRatio);
  }
  report.bonds = model.bonds.size();
  report.particles = p.size();
  report.bondedCoordination = bondedCoordination(report.bonds, report.particles);
  report.bondStiffness =
    params.bondNormalStiffness > 0.0 ? params.bondNormalStiffness : params.bondModulus / (2.0 * *rmax);
  return report;
}

} // namespace dem
