#include "dem/EmbeddedShaders.h"

namespace dem {
namespace shaders {
namespace {
const std::uint32_t kParticleVolume[] = {
#include "particle_volume.spv.inc"
};
} // namespace

SpirvModule particleVolume()
{
  return { kParticleVolume, sizeof(kParticleVolume) / sizeof(kParticleVolume[0]),
           "particle_volume" };
}

} // namespace shaders
} // namespace dem
