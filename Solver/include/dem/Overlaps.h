// RockDEM engine: particles that overlap one another.
//
// Two particles overlap when their centres are closer than the sum of their radii (by the
// minimum image on periodic axes; in a 2D section in the XY plane). A pack built by DEM
// Pack Source never overlaps; a model built from arbitrary points (DEM Model From Points)
// may, and contacts overlap slightly while a model runs. SI units: metres, m^3.
#pragma once

#include "dem/Model.h"

#include <cstdint>
#include <vector>

#include <cstddef>
#include <cstdint>

namespace dem {

/// The overlapping pairs of a model.
struct OverlapReport {
  std::size_t pairs = 0;           ///< pairs of particles that overlap (touching is not overlapping)
  double largest = 0.0;            ///< m, the largest overlap r_i + r_j - |x_j - x_i|
  double largestRelative = 0.0;    ///< that overlap over the smaller radius of its pair
  std::int64_t idA = -1;           ///< ids of the pair with the largest overlap (-1: none)
  std::int64_t idB = -1;
  double volume = 0.0;             ///< m^3, the volume shared by overlapping pairs, summed over pairs
};

/// Volume (m^3) shared by two particles of radii a and b (m) whose centres are `distance`
/// (m) apart: the lens of two spheres, or in a 2D section the lens of two discs times the
/// slab thickness; the smaller particle's volume when one contains the other; 0 apart.
double sharedVolume(const Domain& domain, double a, double b, double distance);

/// Finds every overlapping pair (one cell-grid search, O(n)).
OverlapReport measureOverlaps(const Model& model);
/// The same report, bit for bit, into `out` from candidate pairs that include every
/// overlapping pair, sorted by (i, j) with i < j: a solver's neighbour list
/// (Simulation::overlaps), without a search. False, `out` unchanged, when the lists are not
/// so sorted.
bool measureOverlaps(const Model& model, const std::vector<std::uint32_t>& pairI,
                     const std::vector<std::uint32_t>& pairJ, OverlapReport& out);

/// Throws InputError when two particles have exactly the same centre (after wrapping into
/// the box on periodic axes; z does not count in a 2D section): such a pair has no contact
/// direction, so it would stay stuck together with zero force. The message names both
/// particles by id (DEM Model From Points: the input point indices).
void requireDistinctCentres(const Domain& domain, const Particles& particles);

} // namespace dem
