// RockDEM engine: what removing particles from a model removed (dem::removeParticles in
// Model.h; dem::startLoadTest removes the grains that escaped the box).
#pragma once

#include <cstddef>
#include <string>

namespace dem {

/// What removeParticles removed.
struct RemovedParticles {
  std::size_t particles = 0;
  std::size_t bonds = 0;        ///< bonds that joined a removed particle (intact or broken)
  std::size_t intactBonds = 0;  ///< of which intact
  std::size_t contacts = 0;     ///< contact history entries of a removed particle
  /// One line for the user ("" when nothing was removed); `why` says which particles.
  std::string summary(const std::string& why) const;
};

} // namespace dem
