// RockDEM engine: the Vulkan backend, the whole step on a GPU (DESIGN.md "Driver and
// backends"; Documentation/GPU.md).
//
// The state of the run lives on the device in double precision (particles, neighbour
// pairs with their history, the particle-wall list, bonds, walls and clock); each step is
// a sequence of compute kernels (shaders/solver/): half kick and drift, wall control and
// wall motion (the servo law on the device), the neighbour rebuild when a particle moved
// half the skin (cell binning per size class, a stable radix sort, per-particle lists
// sorted by partner, history carried over), pair and bond forces, the per-particle gather
// in the CPU's fixed order with Cundall damping and the closing half kick, and the walls'
// reaction sums in slot order. The kernels mirror the CPU backend operation for operation
// (no floating-point atomics, no contraction into FMAs), so a run gives the CPU's bits on a
// driver that rounds IEEE-754 double operations correctly (lavapipe does).
//
// One submission runs the steps up to the next history row or stability check; the host
// reads back only a few counters then, and the whole state when the driver needs it
// (sync: a history row, the end of advance()). The initial lists come from the CPU backend
// (the same code imports the stored contact history by global ids), which then serves as
// the host mirror that sync() fills. When a list outgrows its buffers the submission stops
// before overwriting anything, the host grows them and resumes.
#pragma once

#include "backends/ContactState.h"
#include "backends/cpu/CpuBackend.h"
#include "backends/vulkan/VulkanDevice.h"
#include "backends/vulkan/VulkanParams.h"
#include "dem/Backend.h"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

namespace dem {
namespace vk {
struct Transfer;
}

class VulkanBackend final : public Backend {
public:
  /// Opens the device, builds the initial lists on the CPU and uploads the state. Throws
  /// vk::Unavailable (its what() is the reason, for the Solver Path) when the device cannot
  /// run this model: no device or feature, too little memory, a failed allocation.
  /// `tightLists` (tests): the pair and wall lists get no headroom, so that the first
  /// growth of either makes the device halt and the host grow them.
  VulkanBackend(Model& model, const ContactModel& contactModel, double timestep, bool tightLists = false);
  ~VulkanBackend() override;

  std::string path() const override;
  void run(std::int64_t steps) override;
  const ContactState& sync() override;
  StabilityReport stability() override;
  void countDissipation(bool on) override;

  DeviceMemory deviceMemory() const override;
  /// Neighbour rebuilds done on the device so far.
  std::int64_t rebuilds() const { return rebuilds_; }
  /// Times the device's pair or wall list outgrew its buffers and was grown.
  std::int64_t growths() const { return growths_; }

private:
  struct Array;
  struct Images;
  void allocate();
  void release();
  void grow(bool pairs, bool walls, std::uint32_t neededPairs, std::uint32_t neededWalls);
  void setStageParameters();
  const vk::Buffer& array(const char* name) const;
  std::vector<vk::Transfer> dynamicState(Images& images);
  void upload();
  void download();
  void recordControlReadback(VkCommandBuffer cb);
  void readControlReadback(std::uint32_t* ctl);
  const vk::Pipeline& pipeline(const char* kernel, std::uint32_t pushBytes);
  void recordSteps(VkCommandBuffer cb, std::int64_t steps, bool resumeAtRebuild);
  void recordRebuild(VkCommandBuffer cb);
  void recordScan(VkCommandBuffer cb, std::uint64_t data, std::uint64_t result, std::uint32_t scanSlot,
                  std::uint32_t oneSlot);
  void dispatch(VkCommandBuffer cb, const char* kernel, const void* push, std::uint32_t pushBytes,
                std::uint32_t groupsX, std::uint32_t groupsY = 1);
  void dispatchIndirect(VkCommandBuffer cb, const char* kernel, const void* push,
                        std::uint32_t pushBytes, std::uint32_t slot);
  void dispatchItems(VkCommandBuffer cb, const char* kernel, std::uint64_t items);
  void runOnHost(std::int64_t steps);
  bool servoNeedsParticles() const;

  Model& model_;
  ContactModel contactModel_;
  double timestep_;
  std::unique_ptr<CpuBackend> host_;
  std::shared_ptr<vk::Device> device_;
  vk::Params params_{};
  vk::Params uploadedParams_{};
  std::vector<Array> arrays_;
  vk::Buffer paramsBuffer_;
  vk::Buffer staging_;
  const vk::Buffer* control_ = nullptr;   // arrays_ entries used by the host
  const vk::Buffer* indirect_ = nullptr;
  const vk::Buffer* clock_ = nullptr;
  const vk::Buffer* walls_ = nullptr;
  const vk::Buffer* partialSums_ = nullptr;
  std::uint32_t n_ = 0;
  bool countDissipation_ = false; // countDissipation: the device arrays travel with the state
  std::uint32_t bonds_ = 0;
  std::uint32_t sortPasses_ = 0;
  std::uint32_t pairCapacity_ = 0;
  std::uint32_t wallCapacity_ = 0;
  std::uint32_t pairs_ = 0;       // pairs on the device after the last submission
  std::uint32_t adjacency_ = 0;
  std::uint32_t wallEntries_ = 0;
  std::int64_t rebuilds_ = 0;
  std::int64_t growths_ = 0;
  std::int64_t batch_ = 16;       // steps per submission (follows the rebuild interval)
  std::unordered_map<const char*, const vk::Pipeline*> pipelines_;
  bool rolling_ = false;
  bool synced_ = true;
};

} // namespace dem
