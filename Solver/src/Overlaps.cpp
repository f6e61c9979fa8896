// RockDEM engine: particles that overlap one another (see dem/Overlaps.h). SI units.
#include "dem/Overlaps.h"

#include "dem/Errors.h"
#include "dem/SizeClassGrids.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

namespace dem {

namespace {
constexpr double kPi = 3.14159265358979323846;
} // namespace

double sharedVolume(const Domain& domain, double a, double b, double distance)
{
  const double d = distance;
  if (!(d < a + b)) {
    return 0.0;
  }
  const double small = std::min(a, b);
  const double large = std::max(a, b);
  if (d <= large - small) {
    return particleVolume(domain, small); // one inside the other
  }
  if (domain.section2D) {
    // Lens of two discs (area) through the slab.
    const double ca = std::clamp((d * d + a * a - b * b) / (2.0 * d * a), -1.0, 1.0);
    const double cb = std::clamp((d * d + b * b - a * a) / (2.0 * d * b), -1.0, 1.0);
    const double k = (-d + a + b) * (d + a - b) * (d - a + b) * (d + a + b);
    const double area = a * a * std::acos(ca) + b * b * std::acos(cb) - 0.5 * std::sqrt(std::max(0.0, k));
    return std::max(0.0, area) * domain.slabThickness();
  }
  // Lens of two spheres: pi (a + b - d)^2 (d^2 + 2 d (a + b) - 3 (a - b)^2) / (12 d).
  const double h = a + b - d;
  return std::max(0.0, kPi * h * h * (d * d + 2.0 * d * (a + b) - 3.0 * (a - b) * (a - b)) / (12.0 * d));
}

namespace {
/// Adds the pair (i, j), i < j, to the report when it overlaps. The reports of both
/// measureOverlaps call this for each pair in (i, j) order: the same sums, the same bits.
void addIfOverlapping(OverlapReport& report, const Model& model, std::size_t i, std::size_t j)
{
  const Particles& p = model.particles;
  const double distance = minimumImage(model.domain, p.position[i], p.position[j]).norm();
  const double overlap = p.radius[i] + p.radius[j] - distance;
  if (!(overlap > 0.0)) {
    return;
  }
  ++report.pairs;
  report.volume += sharedVolume(model.domain, p.radius[i], p.radius[j], distance);
  if (overlap > report.largest) {
    report.largest = overlap;
    report.largestRelative = overlap / std::min(p.radius[i], p.radius[j]);
    report.idA = p.id[i];
    report.idB = p.id[j];
  }
}
} // namespace

OverlapReport measureOverlaps(const Model& model)
{
  OverlapReport report;
  const Particles& p = model.particles;
  if (p.size() < 2) {
    return report;
  }
  const auto [rmin, rmax] = std::minmax_element(p.radius.begin(), p.radius.end());
  SizeClassGrids grids(model.domain, *rmin, *rmax);
  grids.insertAll(p);
  std::vector<std::size_t> keys;
  for (std::size_t i = 0; i < p.size(); ++i) {
    grids.neighboursWithin(p.position[i], p.radius[i], 0.0, i, keys);
    std::sort(keys.begin(), keys.end()); // slot order: the sums do not depend on the grid
    for (std::size_t j : keys) {
      if (j > i) { // each pair once
        addIfOverlapping(report, model, i, j);
      }
    }
  }
  return report;
}

bool measureOverlaps(const Model& model, const std::vector<std::uint32_t>& pairI,
                     const std::vector<std::uint32_t>& pairJ, OverlapReport& out)
{
  const std::size_t n = model.particles.size();
  if (pairI.size() != pairJ.size()) {
    return false;
  }
  OverlapReport report;
  for (std::size_t k = 0; k < pairI.size(); ++k) {
    const bool ordered = pairI[k] < pairJ[k] && pairJ[k] < n &&
      (k == 0 || pairI[k - 1] < pairI[k] || (pairI[k - 1] == pairI[k] && pairJ[k - 1] < pairJ[k]));
    if (!ordered) {
      return false;
    }
    addIfOverlapping(report, model, pairI[k], pairJ[k]);
  }
  out = report;
  return true;
}

void requireDistinctCentres(const Domain& domain, const Particles& particles)
{
  const std::size_t n = particles.size();
  // Each centre as it is compared: wrapped into the box on periodic axes, z = 0 in 2D.
  std::vector<Vec3> centre(n);
  for (std::size_t i = 0; i < n; ++i) {
    Vec3 x = particles.position[i];
    for (int k = 0; k < 3; ++k) {
      if (domain.periodic[k]) {
        const double length = domain.size[k];
        x[k] -= length * std::floor((x[k] - domain.origin[k]) / length);
      }
    }
    if (domain.section2D) {
      x.z() = 0.0;
    }
    centre[i] = x;
  }
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t(0));
  auto before = [&](std::size_t a, std::size_t b) {
    const Vec3& x = centre[a];
    const Vec3& y = centre[b];
    if (x.x() != y.x()) {
      return x.x() < y.x();
    }
    if (x.y() != y.y()) {
      return x.y() < y.y();
    }
    if (x.z() != y.z()) {
      return x.z() < y.z();
    }
    return a < b;
  };
  std::sort(order.begin(), order.end(), before);
  for (std::size_t k = 1; k < n; ++k) {
    const std::size_t a = order[k - 1];
    const std::size_t b = order[k];
    if (centre[a] == centre[b]) {
      const Vec3& x = particles.position[a];
      throw InputError("Particles " + std::to_string(particles.id[std::min(a, b)]) + " and " +
                       std::to_string(particles.id[std::max(a, b)]) + " have the same centre (" +
                       formatValue(x.x()) + ", " + formatValue(x.y()) + ", " + formatValue(x.z()) +
                       ") m" + (domain.section2D ? " in the 2D section" : "") +
                       ": two particles cannot occupy one point (there is no direction to push "
                       "them apart). Move or remove one of them.");
    }
  }
}

} // namespace dem
