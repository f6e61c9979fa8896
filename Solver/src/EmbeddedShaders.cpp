#include "dem/EmbeddedShaders.h"

#include <cstring>
#include <stdexcept>
#include <string>

namespace dem {
namespace shaders {
namespace {
#include "shader_registry.inc"
} // namespace

SpirvModule particleVolume()
{
  return module("particle_volume");
}

SpirvModule module(const char* name)
{
  for (const SpirvModule& m : kModules) {
    if (std::strcmp(m.name, name) == 0) {
      return m;
    }
  }
  throw std::out_of_range(std::string("no embedded shader named ") + name);
}

} // namespace shaders
} // namespace dem
