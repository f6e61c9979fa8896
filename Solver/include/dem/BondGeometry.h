// RockDEM engine: where the bonds of a model are (for sections and voxel models). SI units.
#pragma once

#include "dem/Model.h"

#include <cstddef>
#include <vector>

namespace dem {

/// Each bond's particles and segment: from the centre of A to A + the minimum-image
/// branch (the way the Bonds block draws it; the far end is B's centre, or its nearest
/// periodic image across a seam), and its contact point, which divides the branch in the
/// ratio of the radii (where the bond's cement sits, and where it breaks).
struct BondGeometry {
  std::vector<std::size_t> slotA, slotB; ///< particle slots
  std::vector<Vec3> start;               ///< m, centre of A
  std::vector<Vec3> branch;              ///< m, A to B by the minimum image
  std::vector<Vec3> contact;             ///< m, start + branch rA / (rA + rB)

  std::size_t size() const { return slotA.size(); }
  Vec3 end(std::size_t k) const { return start[k] + branch[k]; }
  Vec3 midpoint(std::size_t k) const { return start[k] + 0.5 * branch[k]; }
};

/// The geometry of every bond of the model, in bond order. Throws InputError naming the
/// bond when a bond joins a particle that is not in the model.
BondGeometry bondGeometry(const Model& model);

} // namespace dem
