// Brute-force geometry over all particles, written independently of the engine's grids:
// the reference that the pack and grid tests check against. SI units (m).
#pragma once

#include "dem/Bonds.h"
#include "dem/Model.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace bruteforce {

/// Separation b - a with the minimum-image convention on periodic axes (z dropped in a
/// 2D section): each periodic component is folded into [-L/2, L/2].
inline dem::Vec3 separation(const dem::Domain& domain, const dem::Vec3& a, const dem::Vec3& b)
{
  dem::Vec3 d = b - a;
  for (int k = 0; k < 3; ++k) {
    if (domain.periodic[k]) {
      const double L = domain.size[k];
      d[k] = std::remainder(d[k], L); // IEEE remainder: result in [-L/2, L/2]
    }
  }
  if (domain.section2D) {
    d.z() = 0.0;
  }
  return d;
}

/// Number of pairs (i < j) whose centre distance is below the sum of their radii. O(N^2).
inline std::size_t countOverlaps(const dem::Model& model)
{
  const dem::Particles& p = model.particles;
  std::size_t overlaps = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double distance = separation(model.domain, p.position[i], p.position[j]).norm();
      if (distance < p.radius[i] + p.radius[j]) {
        ++overlaps;
      }
    }
  }
  return overlaps;
}

/// Number of particles that cross a wall on a walled moving axis (x, y in 2D; x, y, z in 3D).
inline std::size_t countWallViolations(const dem::Model& model, double tolerance = 1e-12)
{
  const dem::Particles& p = model.particles;
  const dem::Domain& d = model.domain;
  std::size_t violations = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (int a = 0; a < d.dimension(); ++a) {
      if (d.periodic[a]) {
        continue;
      }
      if (p.position[i][a] - p.radius[i] < d.origin[a] - tolerance ||
          p.position[i][a] + p.radius[i] > d.upper()[a] + tolerance) {
        ++violations;
      }
    }
  }
  return violations;
}

/// Gap from particle i's surface to the nearest other surface or wall (walled moving axes).
inline double nearestGap(const dem::Model& model, std::size_t i)
{
  const dem::Particles& p = model.particles;
  const dem::Domain& d = model.domain;
  double gap = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < p.size(); ++j) {
    if (j != i) {
      const double distance = separation(d, p.position[i], p.position[j]).norm();
      gap = std::min(gap, distance - p.radius[i] - p.radius[j]);
    }
  }
  for (int a = 0; a < d.dimension(); ++a) {
    if (!d.periodic[a]) {
      gap = std::min(gap, p.position[i][a] - p.radius[i] - d.origin[a]);
      gap = std::min(gap, d.upper()[a] - p.position[i][a] - p.radius[i]);
    }
  }
  return gap;
}

/// A bonded pair by particle ids (idA < idB, as DEM Cement stores them).
using IdPair = std::pair<std::int64_t, std::int64_t>;

/// The (idA, idB) pairs of a bond set, in its order.
inline std::vector<IdPair> bondPairs(const dem::Bonds& b)
{
  std::vector<IdPair> out;
  for (std::size_t k = 0; k < b.size(); ++k) {
    out.emplace_back(b.idA[k], b.idB[k]);
  }
  return out;
}

} // namespace bruteforce
