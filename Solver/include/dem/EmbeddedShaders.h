// RockDEM engine: SPIR-V compute shaders compiled from shaders/ at build time.
#pragma once

#include <cstddef>
#include <cstdint>

namespace dem {
namespace shaders {

/// A SPIR-V module embedded in the library: `words` points at `count` 32-bit words.
struct SpirvModule {
  const std::uint32_t* words;
  std::size_t count;
  const char* name;
};

/// shaders/particle_volume.comp: per-particle sphere/disc volume (m^3).
SpirvModule particleVolume();

/// The module compiled from shaders/.../<name>.comp (e.g. "gather"). Throws
/// std::out_of_range for a name that is not embedded.
SpirvModule module(const char* name);

} // namespace shaders
} // namespace dem
