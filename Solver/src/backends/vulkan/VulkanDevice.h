// RockDEM engine (internal): a headless Vulkan compute device, opened through the
// Vulkan loader at run time (dlopen of libvulkan.so.1: a machine without Vulkan still
// loads the engine and runs on the CPU).
//
// Requirements, checked when the device is opened (each missing one is a reason to fall
// back, named in the message): Vulkan 1.2, shaderFloat64, shaderInt64, bufferDeviceAddress
// and a compute queue. Arrays are addressed through buffer device addresses
// (GL_EXT_buffer_reference), so the per-binding range limit (maxStorageBufferRange,
// 128 MiB on lavapipe) does not cap an array; one allocation per array stays below
// maxMemoryAllocationSize.
//
// Test hooks (environment): ROCKDEM_VULKAN_DISABLE=1 refuses Vulkan;
// ROCKDEM_VULKAN_SIMULATE_NO_FP64=1 treats the device as lacking shaderFloat64;
// ROCKDEM_VULKAN_SIMULATE_MEMORY=<bytes> treats the device as having that much memory;
// ROCKDEM_VULKAN_FAIL_ALLOCATION=<k> makes the k-th device allocation (1-based) fail as
// out of device memory. ROCKDEM_VULKAN_DEVICE=<index> picks a physical device.
#pragma once

#define VK_NO_PROTOTYPES
#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

namespace dem {
namespace shaders {
struct SpirvModule;
}
namespace vk {

/// Vulkan cannot be used (no loader, no device, a missing feature, too little memory, a
/// failed allocation); what() says why, in words for the Solver Path.
class Unavailable : public std::runtime_error {
public:
  explicit Unavailable(const std::string& reason) : std::runtime_error(reason) {}
};

/// The Vulkan functions RockDEM calls, loaded from the loader.
struct Api {
#define ROCKDEM_VK_FUNCTIONS(X)                                                                 \
  X(vkDestroyInstance) X(vkEnumeratePhysicalDevices) X(vkGetPhysicalDeviceProperties)          \
  X(vkGetPhysicalDeviceFeatures2) X(vkGetPhysicalDeviceMemoryProperties)                        \
  X(vkGetPhysicalDeviceQueueFamilyProperties) X(vkCreateDevice) X(vkDestroyDevice)              \
  X(vkGetDeviceQueue) X(vkCreateBuffer) X(vkDestroyBuffer) X(vkGetBufferMemoryRequirements)     \
  X(vkAllocateMemory) X(vkFreeMemory) X(vkBindBufferMemory) X(vkMapMemory) X(vkUnmapMemory)    \
  X(vkGetBufferDeviceAddress) X(vkCreateShaderModule) X(vkDestroyShaderModule)                 \
  X(vkCreatePipelineLayout) X(vkDestroyPipelineLayout) X(vkCreateComputePipelines)             \
  X(vkDestroyPipeline) X(vkCreateCommandPool) X(vkDestroyCommandPool)                          \
  X(vkAllocateCommandBuffers) X(vkFreeCommandBuffers) X(vkBeginCommandBuffer)                  \
  X(vkEndCommandBuffer) X(vkCmdBindPipeline) X(vkCmdPushConstants) X(vkCmdDispatch)            \
  X(vkCmdDispatchIndirect) X(vkCmdPipelineBarrier) X(vkCmdCopyBuffer) X(vkCmdFillBuffer)       \
  X(vkQueueSubmit) X(vkQueueWaitIdle) X(vkCreateFence) X(vkDestroyFence) X(vkWaitForFences)    \
  X(vkResetFences) X(vkResetCommandBuffer) X(vkGetPhysicalDeviceProperties2) X(vkCmdUpdateBuffer)
#define ROCKDEM_VK_DECLARE(name) PFN_##name name = nullptr;
  PFN_vkGetInstanceProcAddr vkGetInstanceProcAddr = nullptr;
  PFN_vkCreateInstance vkCreateInstance = nullptr;
  ROCKDEM_VK_FUNCTIONS(ROCKDEM_VK_DECLARE)
#undef ROCKDEM_VK_DECLARE
};

/// A device buffer (storage, transfer, indirect; addressed from shaders by its device
/// address), or a host-visible staging buffer (mapped).
struct Buffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize bytes = 0;
  VkDeviceAddress address = 0;
  void* mapped = nullptr;
};

/// A compute pipeline with its layout (push constants only, no descriptor sets).
struct Pipeline {
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  std::uint32_t pushBytes = 0;
};

class Device {
public:
  /// The process's device (opened on first use, shared while anyone holds it). Throws
  /// Unavailable with the reason when Vulkan cannot be used.
  static std::shared_ptr<Device> open();
  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  const Api& api() const { return api_; }
  VkDevice handle() const { return device_; }
  /// The device's name as the driver reports it ("llvmpipe (LLVM 15.0.6, 256 bits)").
  const std::string& name() const { return name_; }
  /// Bytes of device-local memory (largest device-local heap), or the simulated amount.
  std::uint64_t memoryBytes() const { return memoryBytes_; }
  /// Largest single allocation, bytes.
  std::uint64_t maxAllocationBytes() const { return maxAllocation_; }
  std::uint32_t maxWorkgroupsX() const { return maxGroupsX_; }
  /// The largest range of one storage-buffer binding (which addressing by device address
  /// does not need to respect), bytes.
  std::uint64_t maxStorageBufferRange() const { return maxStorageRange_; }

  /// A device-local buffer of `bytes` (at least 16). Throws Unavailable when the device
  /// is out of memory.
  Buffer createBuffer(VkDeviceSize bytes);
  /// A host-visible, host-coherent staging buffer, mapped.
  Buffer createStaging(VkDeviceSize bytes);
  void destroy(Buffer& buffer);

  /// The compute pipeline of an embedded SPIR-V module (created once per process and
  /// module; every floating-point operation is decorated NoContraction first).
  const Pipeline& pipeline(const shaders::SpirvModule& module, std::uint32_t pushBytes);

  /// Records with `record` into a one-time command buffer, submits it and waits.
  template <class Record> void submit(Record&& record)
  {
    VkCommandBuffer cb = begin();
    record(cb);
    endSubmitWait(cb);
  }
  VkCommandBuffer begin();
  void endSubmitWait(VkCommandBuffer cb);

  /// A compute-to-compute (and transfer, indirect) memory barrier.
  void barrier(VkCommandBuffer cb) const;

private:
  Device() = default;
  void create();
  void allocateAndBind(Buffer& buffer, VkDeviceSize size, std::uint32_t type, const void* next,
                       const char* what);

  void* library_ = nullptr;
  Api api_;
  VkInstance instance_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  std::uint32_t queueFamily_ = 0;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkPhysicalDeviceMemoryProperties memoryProperties_{};
  std::string name_;
  std::uint64_t memoryBytes_ = 0;
  std::uint64_t maxAllocation_ = 0;
  std::uint32_t maxGroupsX_ = 65535;
  std::uint64_t maxStorageRange_ = 0;
  std::int64_t allocations_ = 0;
  std::int64_t failAllocation_ = 0;
  std::map<std::string, Pipeline> pipelines_;
  std::mutex mutex_;
};

/// Adds a NoContraction decoration to the result of every floating-point arithmetic
/// instruction of a SPIR-V module, so that no driver fuses a multiply and an add into an
/// FMA (the C++ side never does: x86-64 without -mfma, ISO C++ mode): the device then
/// rounds every operation where the CPU does. Returns the new module.
std::vector<std::uint32_t> withoutContraction(const std::uint32_t* words, std::size_t count);

} // namespace vk
} // namespace dem
