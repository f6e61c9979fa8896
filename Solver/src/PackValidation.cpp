// RockDEM engine: validation of the pack parameters (see dem/Pack.h). SI units: metres.
#include "dem/Pack.h"

#include "dem/Errors.h"
#include "dem/MemoryEstimate.h"

#include <algorithm>
#include <cstdio>
#include <string>

namespace dem {

namespace {

const char* const kAxisName[3] = { "X", "Y", "Z" };
constexpr double kBytesPerGiB = 1024.0 * 1024.0 * 1024.0;

void validateRadiusRange(const std::string& minimumLabel, double minimum,
                         const std::string& maximumLabel, double maximum)
{
  requirePositive(minimumLabel, minimum, "m");
  requirePositive(maximumLabel, maximum, "m");
  if (minimum > maximum) {
    throw InputError(minimumLabel + " = " + formatValue(minimum) + " m must not exceed " +
                     maximumLabel + " = " + formatValue(maximum) + " m.");
  }
}

void validateFineZone(const FineZone& zone, const Domain& domain)
{
  validateRadiusRange("Fine Zone Minimum Size", zone.minimumSize, "Fine Zone Maximum Size",
                      zone.maximumSize);
  // Only the moving axes matter: in a 2D section the zone is a rectangle in XY.
  for (int a = 0; a < domain.dimension(); ++a) {
    const std::string originLabel = std::string("Fine Zone Origin ") + kAxisName[a];
    const std::string sizeLabel = std::string("Fine Zone ") + kAxisName[a] + " Dimension";
    const double lower = domain.origin[a];
    const double upper = domain.upper()[a];
    requireInRange(originLabel, zone.origin[a], lower, upper, "m");
    requirePositive(sizeLabel, zone.size[a], "m");
    const double room = upper - zone.origin[a]; // m, from the zone origin to the box face
    if (zone.size[a] > room * (1.0 + 1.0e-12)) {
      throw InputError(sizeLabel + " = " + formatValue(zone.size[a]) +
                       " m reaches past the model box: valid range is (0, " + formatValue(room) +
                       "] m for " + originLabel + " = " + formatValue(zone.origin[a]) + " m.");
    }
    // Between walls, a fine particle's centre keeps its radius from each face: the zone
    // must reach into that band for the largest fine radius, or fine particles of that
    // size could never be placed.
    if (!domain.periodic[a]) {
      const double r = zone.maximumSize;
      if (std::min(zone.origin[a] + zone.size[a], upper - r) < std::max(zone.origin[a], lower + r)) {
        throw InputError(originLabel + " = " + formatValue(zone.origin[a]) + " m and " + sizeLabel +
                         " = " + formatValue(zone.size[a]) +
                         " m leave no room for a fine particle: its centre must lie at least "
                         "Fine Zone Maximum Size = " + formatValue(r) +
                         " m from the box faces, between " + formatValue(lower + r) + " and " +
                         formatValue(upper - r) + " m.");
      }
    }
  }
}

std::string gibibytes(double bytes)
{
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g", bytes / kBytesPerGiB);
  return text;
}

} // namespace

void requireMemoryForParticles(const std::string& what, double particles)
{
  // What the model takes while a stage steps it: more than placement alone (the particle,
  // its search grids and its drawn radius), so a pack that fits can also be run on.
  const double needed = estimateMemory(particles);
  const double available = static_cast<double>(availableMemoryBytes());
  if (needed > available) {
    throw InputError(what + " needs about " + gibibytes(needed) +
                     " GiB of memory but the machine has " + gibibytes(available) +
                     " GiB available.");
  }
}

void validate(const PackParameters& params, const Domain& domain)
{
  validate(domain);
  validateRadiusRange("Minimum Size", params.minimumSize, "Maximum Size", params.maximumSize);
  requireInOpenRange("Target Porosity", params.targetPorosity, 0.0, 1.0);
  if (params.initialElements < 0) {
    throw InputError("Initial Elements = " + std::to_string(params.initialElements) +
                     " is out of range: valid range is [0, inf).");
  }

  double largest = params.maximumSize; // m, the largest radius that can be placed
  std::string largestLabel = "Maximum Size";
  if (params.fineZone.enabled && params.fineZone.maximumSize > largest) {
    largest = params.fineZone.maximumSize;
    largestLabel = "Fine Zone Maximum Size";
  }
  for (int a = 0; a < domain.dimension(); ++a) {
    const std::string label = std::string(kAxisName[a]) + " Dimension";
    const double length = domain.size[a];
    // Radii are drawn up to Maximum Size and a drawn radius is kept until it is placed: a
    // box that only the smaller radii fit in would place none of the larger ones.
    if (!domain.periodic[a] && length < 2.0 * params.maximumSize) {
      throw InputError(label + " = " + formatValue(length) +
                       " m cannot hold a particle of Maximum Size " +
                       formatValue(params.maximumSize) + " m: valid range is at least 2 x Maximum Size = " +
                       formatValue(2.0 * params.maximumSize) + " m.");
    }
    if (domain.periodic[a] && length < 4.0 * largest) {
      // r_i + r_j <= L/2 keeps the minimum image the one true neighbour across the seam.
      throw InputError(label + " = " + formatValue(length) + " m is too short for Periodic " +
                       kAxisName[a] + " with " + largestLabel + " " + formatValue(largest) +
                       " m: a periodic length must be at least 4 x " + largestLabel + " = " +
                       formatValue(4.0 * largest) + " m.");
    }
  }
  requireMemoryForParticles("Initial Elements = " + std::to_string(params.initialElements),
                   static_cast<double>(params.initialElements));
  if (params.fineZone.enabled) {
    validateFineZone(params.fineZone, domain);
  }
}

} // namespace dem
