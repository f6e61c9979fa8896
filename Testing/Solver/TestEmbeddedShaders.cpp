// The SPIR-V compiled from shaders/ at build time is embedded in the engine.
#include "dem/EmbeddedShaders.h"

#include <gtest/gtest.h>

#include <string>

TEST(EmbeddedShaders, ParticleVolumeIsASpirvModule)
{
  const dem::shaders::SpirvModule module = dem::shaders::particleVolume();
  ASSERT_NE(module.words, nullptr);
  // A SPIR-V module has a five-word header (magic, version, generator, bound, schema) and
  // at least a few instructions; it starts with the magic number 0x07230203 (SPIR-V
  // specification, section 2.3 "Physical Layout of a SPIR-V Module and Instruction").
  ASSERT_GT(module.count, 5u);
  EXPECT_EQ(module.words[0], 0x07230203u);
  EXPECT_EQ(module.words[4], 0u); // schema, reserved: 0
  EXPECT_EQ(std::string(module.name), "particle_volume");
}
