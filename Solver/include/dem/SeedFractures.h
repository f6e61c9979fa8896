// RockDEM engine: seeding a model with mapped fractures (reference guide "Current
// limitations": "The engine can pre-break bonds that cross fractures from a mapped
// network, so a model can start with inherited discontinuities rather than as intact
// rock"; Documentation/Fractures.md).
//
// Every intact bond whose segment between the two particle centres crosses a fracture
// polygon is broken with BondFailure::Inherited. SI units (m, s).
#pragma once

#include "dem/Model.h"

#include <cstddef>
#include <string>
#include <vector>

namespace dem {

/// A planar fracture polygon: its vertices in order (m), 3 or more, simple (not
/// self-intersecting), convex or not.
using FracturePolygon = std::vector<Vec3>;

/// Throws InputError naming the polygon (by its index) when it has fewer than three
/// vertices, a non-finite vertex, or no area.
void validate(const std::vector<FracturePolygon>& polygons);

/// Whether the segment p-q crosses the polygon. The polygon's plane is its Newell
/// normal through its vertex centroid; the segment crosses it when the signed distances
/// of p and q have opposite signs (or one is zero), and the crossing point is then
/// tested against the polygon projected onto the plane's dominant coordinate plane by
/// the even-odd (crossing number) rule, which handles non-convex polygons. A segment
/// lying in the plane does not cross it.
bool segmentCrossesPolygon(const Vec3& p, const Vec3& q, const FracturePolygon& polygon);

struct SeedReport {
  std::size_t polygons = 0;       ///< fracture polygons given
  std::size_t bonds = 0;          ///< bonds in the model
  std::size_t seeded = 0;         ///< intact bonds broken now (mode Inherited)
  std::size_t alreadyBroken = 0;  ///< bonds crossing a polygon that were already broken (left as they were)
  std::string summary() const;
};

/// Breaks every intact bond of `model` whose segment from the centre of particle A to
/// the centre of B (across a periodic seam: to A + the minimum-image branch, as the
/// Bonds block draws it, and also the image ending at B) crosses one of the polygons:
/// failure Inherited, failure time = the model's current time, failure position = the
/// bond's contact point (the branch divided in the ratio of the radii, as when a bond
/// breaks under load), failure normal = the unit branch A to B; forces and moments are
/// zeroed. Bonds already broken are left as they are.
SeedReport seedFractures(Model& model, const std::vector<FracturePolygon>& polygons);

} // namespace dem
