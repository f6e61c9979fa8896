// The GPU tests run on a Vulkan device (lavapipe, from mesa-vulkan-drivers, in CI). On a
// machine without one they are skipped, saying why (ctest reports them as skipped), never
// failed: the GPU solver is optional and falls back to the CPU there.
#pragma once

#include "dem/Simulation.h"

#include <gtest/gtest.h>

#include <string>

/// Skips the calling test when no Vulkan device can run the GPU solver.
#define ROCKDEM_REQUIRE_VULKAN_DEVICE()                                                        \
  do {                                                                                         \
    const std::string rockdemWhyNot = dem::gpuUnavailableReason();                             \
    if (!rockdemWhyNot.empty()) {                                                              \
      GTEST_SKIP() << "no usable Vulkan device on this machine (" << rockdemWhyNot             \
                   << "); install one (Debian: mesa-vulkan-drivers) to run this test";         \
    }                                                                                          \
  } while (0)
