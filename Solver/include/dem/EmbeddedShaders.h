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

} // namespace shaders
} // namespace dem
