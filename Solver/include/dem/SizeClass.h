// RockDEM engine: size classes of particles (one class per doubling of radius).
#pragma once

#include <cstdint>
#include <vector>

namespace dem {

/// Maximum number of size classes; the last class takes every larger particle.
constexpr int MaxSizeClasses = 4;

/// Class of a particle of radius `radius` (m) when the smallest radius in play is
/// `smallestRadius` (m): floor(log2(radius / smallestRadius)), clamped to [0, 3].
int sizeClassOf(double radius, double smallestRadius);

/// Size class of every particle, relative to the smallest radius among them.
std::vector<std::uint8_t> sizeClasses(const std::vector<double>& radius);

} // namespace dem
